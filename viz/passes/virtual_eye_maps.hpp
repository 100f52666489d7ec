#pragma once
// Paper 000's method for solids crossing the water (section 2, RenderSettings::solid_optics =
// virtual_eye): per object, the part under the plane that approximates the water round it drawn
// from the virtual refracted eye (eq. 2, with the size correction of Fig. 3) and the part above it
// from the virtual reflected eye (eq. 1), each into a 256 x 256 tile of one atlas; the surface reads
// a tile along its per-pixel refracted or reflected direction (shaders/solids_optics.glsl). The
// geometry is viz/cpu/virtual_eye.hpp. A map is read only over the surface in the object's trapezium
// (Fig. 8: from x' = x - R r behind the object's centre x, along r towards the eye's foot, R the
// half-diagonal of its footprint, half-width R + s / 2 at distance s, blended out over its outer
// quarter), where the paper switches from its static to its dynamic map. Not done: the paper's
// blending of the surface towards the plane near the object (section 2.2).
#include <array>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "gl.hpp"
#include "render_settings.hpp"

namespace huygens {

/// One object the maps draw: its triangles (x, y, z per vertex, m), bounding box, solid_colour
/// kind (0 hull, 1 obstacle) and the height of the plane approximating the water round it (m).
struct EyeObject {
  std::vector<float> tri;
  glm::dvec3 lo{0.0}, hi{0.0};
  int kind = 1;
  double plane = 0.0;
};

class VirtualEyeMaps {
 public:
  static constexpr int kMaxObjects = 8, kTile = 256, kTilesAcross = 4;
  VirtualEyeMaps();
  ~VirtualEyeMaps();
  VirtualEyeMaps(const VirtualEyeMaps&) = delete;
  VirtualEyeMaps& operator=(const VirtualEyeMaps&) = delete;
  /// Draws the first kMaxObjects objects seen from `eye` (the sun along s.sun_dir; index s.index).
  void build(std::span<const EyeObject> objects, const glm::dvec3& eye, const RenderSettings& s);
  /// Binds the atlas to `unit` and sets the uniforms solids_optics.glsl reads (p current).
  void set_uniforms(const gl::Program& p, int unit) const;

 private:
  struct Tile {
    glm::mat4 vp{1.0f};
    glm::vec3 eye{0.0f};
    glm::vec2 axis{0.0f, 1.0f};  // the image direction of the main axis (refraction tiles)
  };
  Tile draw_tile(const EyeObject& o, const glm::dvec3& eye_v, bool above, int tile, const glm::vec3& light);
  glm::vec4 size_fix(const EyeObject& o, const glm::dvec3& eye, const glm::dvec3& a, Tile& t, double index) const;
  gl::Program prog_;
  gl::Texture atlas_;
  gl::Framebuffer fbo_;
  GLuint depth_ = 0, vao_ = 0, vbo_ = 0;
  int count_ = 0;
  std::array<Tile, 2 * kMaxObjects> tiles_{};
  std::array<glm::vec4, kMaxObjects> fix_{};   // per object: uv of a in its refraction tile, k, |E - a|
  std::array<glm::vec4, kMaxObjects> trap_{};  // per object: the trapezium's foot x' and direction r
  std::array<float, kMaxObjects> radius_{};    // per object: R, its footprint's half-diagonal
};

}  // namespace huygens
