#include "caustics_stage.hpp"

#include <cmath>

#include "accum_blur.hpp"
#include "caustics.hpp"
#include "renderer.hpp"

namespace huygens {
namespace {

class PaperCaustics final : public CausticsStage {
 public:
  PaperCaustics(const GridPlacement& grid, double ground_z)
      : grid_(grid), depth_(static_cast<float>(-ground_z)), caustics_(params()), blur_(512, 512) {}

  bool available() const override { return true; }

  void run(std::span<const float> eta, std::span<const ShipPose> ships, const RenderSettings& s) override {
    const glm::vec3 sun = glm::normalize(s.sun_dir);
    caustics_.set_sun_dir(-sun.x, -sun.y, -sun.z);  // the pass wants the direction light travels
    viz::HeightfieldView field{eta, static_cast<int>(grid_.rows), static_cast<int>(grid_.cols),
                               static_cast<float>(grid_.dx), depth_};
    // the first ship casts the shadow (the pass takes one outline)
    viz::ShipShadow shadow;
    const viz::ShipShadow* ship = nullptr;
    if (!ships.empty() && s.draw_ship) {
      const ShipPose& p = ships[0];
      shadow = viz::make_ellipse_hull(static_cast<float>(p.x - grid_.x0), static_cast<float>(p.y - grid_.y0),
                                      static_cast<float>(p.heading), static_cast<float>(p.length),
                                      static_cast<float>(p.beam));
      shadow.height_m = static_cast<float>(std::max(0.6 * p.draft, 0.04 * p.length));
      ship = &shadow;
    }
    caustics_.render(field, ship);
    const viz::GroundRect r = viz::ground_rect(caustics_.params(), field);
    origin_ = {grid_.x0 + r.x0, grid_.y0 + r.y0};
    extent_ = {r.width, r.height};
    tex_ = !s.blur        ? caustics_.texture().id()
           : s.blur_float ? blur_.blur_float(caustics_.texture()).id()
                          : blur_.blur_emulated(caustics_.texture()).id();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }

  GLuint texture() const override { return tex_; }
  glm::dvec2 origin() const override { return origin_; }
  glm::dvec2 extent() const override { return extent_; }
  float scale() const override { return 255.0f / caustics_.params().unit_level_u8; }

 private:
  static viz::CausticsParams params() { return viz::CausticsParams{}; }
  GridPlacement grid_;
  float depth_;
  viz::CausticsRenderer caustics_;
  viz::AccumBlur blur_;
  GLuint tex_ = 0;
  glm::dvec2 origin_{0.0}, extent_{1.0};
};

}  // namespace

std::unique_ptr<CausticsStage> make_caustics_stage(const GridPlacement& grid, double ground_z) {
  return std::make_unique<PaperCaustics>(grid, ground_z);
}

}  // namespace huygens
