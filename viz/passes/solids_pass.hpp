#pragma once
// The solids pass (docs/viz.md "Solids"): the ships' hulls afloat on the waves (float_ship), the
// obstacles (boxes, cylinders, meshes) and a particle solver's tank walls, flat-shaded.
#include <array>
#include <span>
#include <vector>

#include "flat_drawer.hpp"
#include "solid_geometry.hpp"

namespace huygens {

class SolidsPass {
 public:
  /// The obstacles' triangles (meshes first, then boxes and cylinders) placed by `frame`.
  void set_obstacles(std::span<const RenderObstacle> obstacles, const SolidsFrame& frame);
  /// A particle solver's container (0, 0, 0)-(box_m) (m, before the offset); 0 = none.
  void set_tank(const std::array<double, 3>& box_m) { tank_ = box_m; }
  /// The hulls at their poses afloat (float_ship), the obstacles and the tank walls the eye is
  /// inside of.
  void draw(const FrameContext& f, const FlatDrawer& flat, std::span<const ShipPose> afloat,
            const SolidsFrame& frame) const;

 private:
  std::vector<float> solids_;     // obstacle triangles (x, y, z)
  std::array<double, 3> tank_{};  // set_tank's box (m); 0 = none
};

}  // namespace huygens
