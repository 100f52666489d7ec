#pragma once
// The solids of a scene as triangles (x, y, z per vertex, world coordinates, m): the ships'
// hulls, the obstacles (boxes, cylinders, meshes), a particle solver's tank walls. No GL: the
// solids pass (solids_pass.hpp) draws them, the tests check them.
#include <algorithm>
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "huygens/pipeline/render_info.hpp"
#include "refraction.hpp"

namespace huygens {

/// A ship drawn as a Wigley hull y = B/2 (1 - (2x/L)^2)(1 - (z/T)^2) below the waterline.
struct ShipPose {
  /// Centre position (unit: m) and heading from +x toward +y (unit: rad).
  double x = 0.0, y = 0.0, heading = 0.0;
  /// Length, beam, draft (unit: m).
  double length = 1.0, beam = 0.3, draft = 0.05;
  /// Afloat (float_ship): height of the rest waterline (unit: m) and the surface's slope along and
  /// across the heading (unit: 1) the hull is drawn with; 0 = level at the rest level.
  double heave = 0.0, slope_along = 0.0, slope_across = 0.0;
};

/// The drawn hull's freeboard, its deck's height above the waterline (unit: m): 0.08 of its length
/// (small craft carry 0.07-0.1; the 8 m boat of ocean.json 0.64 m: with 0.04 the crests of its
/// sea broke through the deck), at least 0.6 of its draft.
inline double hull_freeboard(const ShipPose& s) { return std::max(0.6 * s.draft, 0.08 * s.length); }

/// A hull afloat on the heights `eta` (rows x cols of `g`, m): the least-squares plane through the
/// surface sampled on rings 0.6 to 0.8 hull lengths from the hull's centre (outside the hull, and
/// a hull does not follow waves much shorter than itself) gives its heave and its slopes along and
/// across the heading (each kept within +-0.3). Ring points outside the grid are left out; with
/// none inside the hull stays level at 0. A drawing aid, not ship dynamics: the solver's hull is
/// a pressure patch moving on its path.
void float_ship(const GridPlacement& g, std::span<const float> eta, ShipPose& s);

/// Wigley hull triangles of one ship (below the waterline the Wigley form, topsides flaring 12 %
/// to a crowned deck at hull_freeboard), appended to `out`.
void append_hull(const ShipPose& s, std::vector<float>& out);

/// The grid points under the ships' waterlines (1 there, else 0): in the ship's frame (lx along
/// the heading) a Wigley hull's waterline is |ly| <= B/2 (1 - (2 lx / L)^2), |lx| <= L/2.
void mark_hulls(const GridPlacement& g, std::span<const ShipPose> ships, std::vector<std::uint8_t>& out);

/// Where the solids stand: the visible grid, the floor's height and the level subtracted from
/// every height (m), and whether the floor is terrain (a bed) rather than flat.
struct SolidsFrame {
  GridPlacement grid;
  double ground_z = 0.0, offset = 0.0;
  bool over_terrain = false;
};

/// The mesh obstacles' triangles (lowered by the offset), appended to `out`.
void append_mesh_solids(std::span<const RenderObstacle> obstacles, const SolidsFrame& f, std::vector<float>& out);

/// A box or a vertical cylinder where it is drawn (m, after the offset).
struct Prism {
  bool cylinder = false;
  /// Box: the corners in x and y. Cylinder: the axis (lo) and the radius (hi.x).
  glm::dvec2 lo{0.0}, hi{0.0};
  /// Bottom and top.
  double z0 = 0.0, z1 = 0.0;
};

/// The boxes and cylinders of `obstacles` as drawn: from the floor (or the obstacle's bottom) to its
/// top, or for a 2D solver's obstacle (infinite z) to a quarter of the depth above the water at
/// rest; over terrain at least 3 % of the region's size (houses in a flood). Boxes are clipped to
/// the visible region (and left out when nothing is left).
std::vector<Prism> prisms(std::span<const RenderObstacle> obstacles, const SolidsFrame& f);

/// The prisms' triangles (cylinders with 48 sides), appended to `out`.
void append_prism_solids(std::span<const Prism> prisms, std::vector<float>& out);

/// A particle solver's container (0, 0, 0)-(box_m) (m, before the offset): the side walls from the
/// floor to the lid that the eye is inside of (a wall between the eye and the water is left out).
std::vector<float> tank_walls(const std::array<double, 3>& box_m, const SolidsFrame& f, const glm::dvec3& eye);

}  // namespace huygens
