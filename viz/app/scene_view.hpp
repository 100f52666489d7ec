#pragma once
// What the renderer needs to know about a scene besides the heights: where the visible
// region sits in the world, how deep the ground is, the display rate, the ships' hulls, and
// where the ships are. A ship is drawn where the SOLVER has it (Solver::ship_poses, carried by
// every frame as FrameInfo::ships): a ship steered by cmd::ShipTarget leaves its scene path.
// The scene path (piecewise linear; heading along the path) is only the fallback for a
// solver that reports no pose.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "refraction.hpp"
#include "renderer.hpp"

namespace huygens {

/// A ship as the scene file describes it (named apart from the core's huygens::ShipPath).
struct SceneShipPath {
  /// Hull size (unit: m).
  double length = 1.0, beam = 0.3, draft = 0.05;
  /// Waypoints: time (unit: s) and position (unit: m).
  std::vector<double> t, x, y;
  /// Pose at time `time` along the scene path (holds the end points outside the path).
  ShipPose pose(double time) const;
  /// The hull placed at a pose the solver reports.
  ShipPose pose(const ShipState& s) const;
};

struct SceneGeometry {
  GridPlacement grid;
  /// Ground plane height (unit: m): -depth_m of the scene, or -kDeepGround for deep water.
  double ground_z = -2.0;
  /// Full step (unit: s) and displayed frames per step.
  double dt = 0.05;
  int display_per_step = 3;
  std::vector<SceneShipPath> ships;
  /// Level of the water at rest in the solver's height() (unit: m): 0 for elevation fields
  /// (Huygens); the mean initial height for solvers whose height is a depth or a level
  /// above the floor (LBM, SPH). The renderer draws height() - height_offset.
  double height_offset = 0.0;
  /// Depth at which deep-water scenes draw their ground (unit: m).
  static constexpr double kDeepGround = 3.0;
};

/// Reads the geometry of `scene` for the solver (before its first step). Uses grid.n,
/// grid.length_m, grid.margin (docs/design.md 6); other solvers are placed at the origin with
/// the spacing their meta() reports ("dx"), else 1 cm, and the ground at their mean
/// initial height below the rest level.
SceneGeometry scene_geometry(const Scene& scene, Solver& solver);

/// The ships to draw for `solver` in its current state: the poses it reports (ship_poses), each
/// with its scene hull; ships it does not report follow their scene path at solver.time().
/// For the synchronous callers (headless capture, --benchmark); the window reads the poses from
/// the frames instead (FramePair::ship).
std::vector<ShipPose> solver_ship_poses(const SceneGeometry& geo, const Solver& solver);

/// Applies a scene file's "render" block (caustics: bool, blur: "accumulation" | "float" | "none").
void apply_scene_render_block(const std::string& scene_file, RenderSettings& s);

}  // namespace huygens
