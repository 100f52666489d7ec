#pragma once
// Where the obstacles stand on the visible grid, and how the drawn surface closes around them
// (docs/viz.md "Obstacles"). Inside a box or cylinder a solver's height is meaningless (dry cells,
// an empty column): those points show the height of the nearest point outside all of them. Over a
// mesh obstacle the water may run, so there the surface is only kept from dropping below the
// mesh's top (a dry column then lies inside the solid). No GL.
#include <cstdint>
#include <span>
#include <vector>

#include "huygens/pipeline/render_info.hpp"
#include "refraction.hpp"

namespace huygens {

/// Per grid point (R x C, row-major) the nearest point outside `solid` (itself when outside):
/// multi-source breadth-first search over the 4-neighbourhood. Empty when every point is solid.
std::vector<std::uint32_t> nearest_outside(std::vector<std::uint8_t> solid, std::size_t R, std::size_t C);

class Footprints {
 public:
  /// The footprints of `obstacles` on `g`; `offset` (m) is subtracted from the meshes' heights.
  void build(const GridPlacement& g, std::span<const RenderObstacle> obstacles, float offset);
  /// Closes the heights `eta` (rows x cols, m, after the offset) around the solids: a box's or
  /// cylinder's points take the nearest outside point's height; over a mesh the height is at least
  /// min(the mesh's top - dx/4, the height at the nearest point outside its footprint), so a solid
  /// standing in shallower water or on a dry floor keeps its footprint's own height.
  void apply(std::span<float> eta, double dx) const;
  /// Grid point k lies under a box or cylinder, or on a mesh footprint's outline (grey in the plan
  /// view).
  bool solid(std::size_t k) const {
    return (!fill_from_.empty() && fill_from_[k] != k) || (!mesh_outline_.empty() && mesh_outline_[k]);
  }

 private:
  void build_mesh_tops(const GridPlacement& g, std::span<const RenderObstacle> obstacles, float offset);
  void build_fill(const GridPlacement& g, std::span<const RenderObstacle> obstacles);
  std::vector<std::uint32_t> fill_from_;    // per grid point: the point whose height it shows
  std::vector<float> mesh_top_;             // per grid point: a mesh obstacle's top (m), -inf off it
  std::vector<std::uint32_t> mesh_from_;    // per grid point: the nearest point outside the meshes' footprints
  std::vector<std::uint8_t> mesh_outline_;  // per grid point: on a mesh footprint's outline
};

}  // namespace huygens
