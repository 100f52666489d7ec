#include "caustics_stage.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "accum_blur.hpp"
#include "caustics.hpp"
#include "render_settings.hpp"
#include "solid_geometry.hpp"

namespace huygens {
namespace {

// The caustics texture's side: 512 texels, 1024 for fields of more than 256 points a side (the
// kelvin wake's focal points were 10 cm texels, 15 px squares, at 512). Square also for a
// non-square field, and the mesh n x n: on the 2:1 channel, a texture (or a mesh) with the
// field's aspect, i.e. half the texels (rows) across, lost the sharp focal points of the
// grid-scale ripples at the cylinder (up to 132/255 on 0.06 % of the pixels at 1280x720).
int texture_side(const GridPlacement& g) { return std::max(g.rows, g.cols) > 256 ? 1024 : 512; }

// The pass's parameters for a caustics mode (RenderSettings::caustics_mode, docs/viz.md
// "Caustics"): the light-conserving default (explicit area, float target, float blur) or the
// paper's MIP trick and 8-bit target. The texture always covers the floor under the water.
viz::CausticsParams mode_params(CausticsMode mode, int mesh, int texture) {
  viz::CausticsParams p;
  p.texture_width = p.texture_height = texture;
  p.mesh_cols = p.mesh_rows = mesh;
  p.cover_domain = true;
  p.area = mode == CausticsMode::conserving || mode == CausticsMode::explicit_u8 ? viz::CausticsArea::Explicit
                                                                                 : viz::CausticsArea::Mip;
  p.float_target = mode == CausticsMode::conserving || mode == CausticsMode::mip_float;
  // the default projects every vertex by exact Snell refraction: the paper's linearised
  // projection moves light across the floor wrongly where the slopes are steep (the windy pool
  // at full mesh resolution, sun 30 degrees: 3 % too much light in the interior, docs/viz.md)
  if (mode == CausticsMode::conserving) p.projection = viz::CausticsProjection::Exact;
  // and draws blocks of up to 16 x 16 cells whose light is uniform as one fan each (to 0.5 % in
  // gain and 0.05 texel in position; caustics_mesh_triangles): fewer triangles, the same light
  if (mode == CausticsMode::conserving) p.merge_block = 16;
  // starting from still-water light and skipping the still blocks (the fill of the target is
  // the pass's larger cost under llvmpipe)
  if (mode == CausticsMode::conserving) p.skip_still = true;
  return p;
}

// The mesh size in steps of 32 vertices; it follows the field up (one rebuild per step) and
// down only when the field needs less than half of it (no rebuild every frame).
int quantised_mesh(int want, int current) {
  const int q = std::max(32, (want + 31) / 32 * 32);
  if (current == 0 || q > current || 2 * q < current) return q;
  return current;
}

class PaperCaustics final : public CausticsStage {
 public:
  PaperCaustics(const GridPlacement& grid, double ground_z)
      : grid_(grid), depth_(static_cast<float>(-ground_z)), blur_(texture_side(grid), texture_side(grid)) {}

  bool available() const override { return true; }

  void run(std::span<const float> eta, std::span<const ShipPose> ships, const RenderSettings& s) override {
    viz::HeightfieldView field{eta, static_cast<int>(grid_.rows), static_cast<int>(grid_.cols),
                               static_cast<float>(grid_.dx), depth_};
    // at least ~8 mesh cells per dominant wavelength, up to the grid's own resolution
    const int mesh =
        s.caustics_mesh > 0 ? s.caustics_mesh : quantised_mesh(viz::mesh_size_for_field(field), caustics_ ? mesh_ : 0);
    const CausticsMode drawn = s.caustics_mode == CausticsMode::simple ? CausticsMode::conserving : s.caustics_mode;
    if (!caustics_ || mesh != mesh_ || s.caustics_mode != mode_) {
      caustics_.reset();
      caustics_.emplace(
          mode_params(drawn, std::min(mesh, static_cast<int>(std::max(grid_.rows, grid_.cols))), texture_side(grid_)));
      mesh_ = mesh;
      mode_ = s.caustics_mode;
    }
    const glm::vec3 sun = glm::normalize(s.sun_dir);
    caustics_->set_sun_dir(-sun.x, -sun.y, -sun.z);  // the pass wants the direction light travels
    // the first ship casts the shadow (the pass takes one outline)
    viz::ShipShadow shadow;
    const viz::ShipShadow* ship = nullptr;
    if (!ships.empty() && s.draw_ship) {
      const ShipPose& p = ships[0];
      shadow = viz::make_ellipse_hull(static_cast<float>(p.x - grid_.x0), static_cast<float>(p.y - grid_.y0),
                                      static_cast<float>(p.heading), static_cast<float>(p.length),
                                      static_cast<float>(p.beam));
      shadow.height_m = static_cast<float>(hull_freeboard(p));
      ship = &shadow;
    }
    const viz::GroundRect r = viz::ground_rect(caustics_->params(), field);
    origin_ = {grid_.x0 + r.x0, grid_.y0 + r.y0};
    extent_ = {r.width, r.height};
    if (s.caustics_mode == CausticsMode::simple) {  // paper 000's eq. 4 on the same rect, no ship shadow
      run_simple(field);
      return;
    }
    caustics_->render(field, ship);
    // blur (paper 004 sec. 6): float targets in float; the 8-bit target by the
    // accumulation-buffer emulation unless the float blur is asked for
    const bool u8 = !caustics_->params().float_target;
    tex_ = !s.blur               ? caustics_->texture().id()
           : u8 && !s.blur_float ? blur_.blur_emulated(caustics_->texture()).id()
                                 : blur_.blur_float(caustics_->texture()).id();
    scale_ = u8 ? 255.0f / caustics_->params().unit_level_u8 : 1.0f;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  // Paper 000's simple caustics (eq. 4) into their own float texture.
  void run_simple(const viz::HeightfieldView& field) {
    const viz::CausticsParams& p = caustics_->params();
    if (!simple_tex_ || simple_tex_->width() != p.texture_width)
      simple_tex_.emplace(p.texture_width, p.texture_height, GL_R32F);
    simple_tex_->set_filter(GL_LINEAR, GL_LINEAR);
    const std::vector<float> light = viz::simple_caustics(p, field);
    simple_tex_->upload(light.data(), GL_RED, GL_FLOAT);
    tex_ = simple_tex_->id();
    scale_ = 1.0f;
  }

  GLuint texture() const override { return tex_; }
  glm::dvec2 origin() const override { return origin_; }
  glm::dvec2 extent() const override { return extent_; }
  float scale() const override { return scale_; }
  const viz::CausticsParams* params() const override { return caustics_ ? &caustics_->params() : nullptr; }

 private:
  GridPlacement grid_;
  float depth_;
  std::optional<viz::CausticsRenderer> caustics_;
  int mesh_ = 0;
  CausticsMode mode_ = CausticsMode::conserving;
  viz::AccumBlur blur_;
  std::optional<gl::Texture> simple_tex_;
  GLuint tex_ = 0;
  float scale_ = 1.0f;
  glm::dvec2 origin_{0.0}, extent_{1.0};
};

}  // namespace

std::unique_ptr<CausticsStage> make_caustics_stage(const GridPlacement& grid, double ground_z) {
  return std::make_unique<PaperCaustics>(grid, ground_z);
}

}  // namespace huygens
