#include "solids_pass.hpp"

namespace huygens {

void SolidsPass::set_obstacles(std::span<const RenderObstacle> obstacles, const SolidsFrame& frame) {
  solids_.clear();
  append_mesh_solids(obstacles, frame, solids_);
  append_prism_solids(prisms(obstacles, frame), solids_);
}

void SolidsPass::draw(const FrameContext& f, const FlatDrawer& flat, std::span<const ShipPose> afloat,
                      const SolidsFrame& frame) const {
  if (f.s.draw_ship && !afloat.empty()) {
    std::vector<float> tri;
    for (const ShipPose& sp : afloat) append_hull(sp, tri);
    flat.draw(tri, FlatKind::hull, f);
  }
  if (!solids_.empty() && f.s.draw_solids) flat.draw(solids_, FlatKind::obstacle, f);
  if (tank_[0] > 0.0) flat.draw(tank_walls(tank_, frame, f.camera.eye()), FlatKind::tank_wall, f);
}

}  // namespace huygens
