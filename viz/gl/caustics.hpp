// Caustics texture of paper 004 section 5 on the GPU (GL 3.3 core).
//
// Each frame: the heightfield is subsampled to the caustics mesh (default 96 x 96), sun
// rays are refracted through every vertex (the paper's linear approximation
// (x, y) = (x0, y0) + [a b; c d] (eta_x, eta_y), or the exact Snell projection) on the CPU
// (caustics_cpu.hpp), and all projected triangles are drawn into the caustics texture
// with additive blending, each triangle carrying the light of its surface triangle (its beam
// cross-section, or the same for all with flux_by_beam_area = false, as in the paper):
//  * MIP mode: a trilinear MIP map in surface coordinates with constant levels, each 4x
//    brighter than the previous until white (level 2 + mip_lod_offset = still water, the map
//    is 4x the target's size, so shrinking a triangle's area by 4 moves one level up); the
//    ship's shadow is drawn black into the levels still water reads and those below
//    (Figure 7; the higher levels are skipped as in the paper).
//  * Explicit mode: brightness = unit * (surface area) / (ground area) per triangle, computed on
//    the CPU and read by the fragment shader through gl_PrimitiveID from a buffer texture (a
//    geometry shader did this per triangle before); the ship's shadow
//    is a mask in surface coordinates.
// The mesh carries a skirt beyond its border (CausticsMesh in caustics_cpu.hpp), so the
// texture's outer texels are lit even where the waves move the border inwards.
// Values: unit irradiance (still water, sun light as it enters the surface) is 1 in a float
// target and CausticsParams::unit_level_u8 / 255 in the 8-bit target (GL_R8; additive
// blending saturates at 1). Texture row 0 is at the ground rect's y0 (ground_rect()).
#pragma once

#include <optional>
#include <vector>

#include "caustics_cpu.hpp"
#include "gl/gl.hpp"

namespace huygens::viz {

class CausticsRenderer {
 public:
  /// Creates programs, buffers and targets (a current GL context is needed).
  explicit CausticsRenderer(const CausticsParams& params);

  /// Compute the mesh from `field` and draw the caustics texture; `ship` may be null.
  void render(const HeightfieldView& field, const ShipShadow* ship = nullptr);

  /// Toggles (take effect at the next render()).
  void set_area(CausticsArea a) { params_.area = a; }
  void set_projection(CausticsProjection p) { params_.projection = p; }
  void set_sun_dir(float x, float y, float z) { params_.sun_dir = {x, y, z}; }

  const CausticsParams& params() const { return params_; }
  /// GL_R8 (8-bit) or GL_R32F (float_target) caustics texture.
  const gl::Texture& texture() const { return target_; }
  const gl::Framebuffer& framebuffer() const { return fb_; }
  const CausticsMesh& mesh() const { return mesh_; }
  /// CPU time of the last render's mesh update (unit: s).
  double last_cpu_seconds() const { return cpu_seconds_; }

 private:
  void ensure_mip();
  int shadow_top_level() const;
  void ensure_mask();
  void draw_shadow(const std::vector<std::array<float, 2>>& shadow, bool has_ship, const HeightfieldView& field);
  void upload_mesh();
  GLsizei bind_light_program(bool has_ship);
  void draw_shadow_polygon(const std::vector<std::array<float, 2>>& poly, const HeightfieldView& field);

  CausticsParams params_;
  CausticsMesh mesh_;
  gl::Texture target_;
  gl::Framebuffer fb_;
  gl::Program mip_prog_, explicit_prog_, shadow_prog_;
  GLuint vao_ = 0, vbo_ground_ = 0, vbo_surface_ = 0, ebo_ = 0, ebo_draw_ = 0, vbo_shadow_ = 0, vao_shadow_ = 0;
  // MIP map (surface coordinates, 4x the target size) and its per-level framebuffers 0..2
  std::optional<gl::Texture> mip_;
  std::vector<gl::Framebuffer> mip_fb_;
  bool mip_dirty_ = false;
  // shadow mask for the explicit mode
  std::optional<gl::Texture> mask_;
  std::optional<gl::Framebuffer> mask_fb_;
  double cpu_seconds_ = 0.0;
  // explicit mode: one gain per triangle (CausticsMesh::gains), read by gl_PrimitiveID from a buffer texture
  GLuint gain_buffer_ = 0, gain_texture_ = 0;

 public:
  ~CausticsRenderer();
  CausticsRenderer(const CausticsRenderer&) = delete;
  CausticsRenderer& operator=(const CausticsRenderer&) = delete;
};

/// Level of the MIP map that still water selects (the map is 2^kMipFlatLevel times the target size).
inline constexpr int kMipFlatLevel = 2;

}  // namespace huygens::viz
