#pragma once
// The solids the surface's rays meet (docs/viz.md "Solids seen in and through the water"): the
// boxes and vertical cylinders of a scene and the hulls afloat, packed for the exact per-pixel ray
// trace of shaders/solids_trace.glsl that the surface pass runs on its refracted and reflected
// rays (paper 000's penetrating obstacles, traced instead of its environment maps). No GL: the
// surface pass uploads the packing, the tests read it.
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "solid_geometry.hpp"

namespace huygens {

/// Three vec4 per solid, as solids_trace.glsl reads them (w of the first: 0 box, 1 cylinder, 2 hull):
///   box       (x0, y0, z0, 0)         (x1, y1, z1, 0)          -
///   cylinder  (cx, cy, z0, 1)         (r, 0, z1, 0)            -
///   hull      (x, y, heading, 2)      (L, B, T, freeboard)     (heave, slope along, across, 0)
class TracedSolids {
 public:
  /// The most solids a frame traces (the shader's uniform array); further ones are drawn but
  /// neither reflected nor seen through the water.
  static constexpr int kMax = 32;
  /// The scene's boxes and cylinders (set once); the hulls afloat (every frame).
  void set_prisms(std::span<const Prism> prisms);
  void set_hulls(std::span<const ShipPose> ships);
  /// The packing: prisms then hulls, at most kMax solids.
  std::span<const glm::vec4> packed() const { return {packed_.data(), 3 * static_cast<std::size_t>(count())}; }
  int count() const;
  /// A box holding every packed solid (m; empty when there are none): rays that miss it meet none.
  glm::vec3 lo() const { return lo_; }
  glm::vec3 hi() const { return hi_; }

 private:
  void repack();
  std::vector<glm::vec4> prisms_, hulls_, packed_;
  glm::vec3 prisms_lo_{1e30f}, prisms_hi_{-1e30f}, hulls_lo_{1e30f}, hulls_hi_{-1e30f}, lo_{1e30f}, hi_{-1e30f};
};

}  // namespace huygens
