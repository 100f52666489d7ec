#pragma once
// What the viewer knows of a scene: only what the solver tells it (Solver::render_info, core
// render_info.hpp) and the frames. The scene file is read by the core (load_scene, or the built-in
// default.json through parse_scene_text) and the solver made by make_solver; the viewer never
// parses the scene's JSON and has no physics of its own. A ship is drawn where the frames put it
// (FrameInfo::ships, the solver's poses: a ship steered by cmd::ShipTarget too) with its hull.
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "huygens/common/scene.hpp"
#include "huygens/pipeline/frame.hpp"
#include "huygens/pipeline/render_info.hpp"
#include "huygens/pipeline/solver.hpp"
#include "refraction.hpp"
#include "renderer.hpp"

namespace huygens {

/// The viewer's placement of a solver's heightfield, from its RenderInfo.
struct SceneView {
  GridPlacement grid;
  /// Ground plane height (unit: m): -depth, or -kDeepGround for deep water.
  double ground_z = -kDeepGround;
  /// Level of the water at rest in height() (unit: m; RenderInfo::rest_level_m), subtracted.
  double height_offset = 0.0;
  /// Simulated time between two displayed frames (unit: s; RenderInfo::frame_dt_s).
  double frame_dt = 1.0 / 60.0;
  std::vector<RenderHull> hulls;
  std::vector<RenderObstacle> obstacles;
  /// A particle solver's container (0, 0, 0)-(particle_box) and particle spacing (unit: m;
  /// RenderInfo): the particle view's extent and disc size; nullopt for grid solvers.
  std::optional<std::array<double, 3>> particle_box;
  /// The bed (rows x cols, m; RenderInfo::bed_m) when it is not flat: drawn as terrain
  /// (WaterRenderer::set_bed); empty for a flat floor.
  std::vector<float> bed;
  double particle_spacing = 0.0;
  /// The ambient wind sea (RenderInfo::ambient_sea): the open-ocean look draws the sea beyond the
  /// region with its slopes (WaterRenderer::set_ambient_sea).
  std::optional<RenderAmbientSea> ambient_sea;
  /// The kind of picture (RenderInfo's request, else from what the solver is: a height above
  /// a floor with an adaptive step is SPH, with a fixed step shallow water (LBM); an elevation
  /// field with a wind sea is the open ocean, without one a pool).
  Look look = Look::pool;
  /// A quasi-2D slab (one side over 8x the other; a particle solver's tank over 2.5x): seen from
  /// low along its short side (a particle solver's: its container floor to lid), no deck, a
  /// plain floor, no caustics.
  bool slab = false;
  /// Start in the plan view ("view": "plan").
  bool plan_view = false;
  /// The plan view's quantity: "height" (elevation about rest, diverging map) or "depth".
  bool plan_depth = false;
  /// The camera keeps the first ship in view (render.camera.follow_ship; default with ships).
  bool follow_ship = false;
  CameraRequest camera_request;
  /// Depth at which deep-water scenes draw their ground (unit: m).
  static constexpr double kDeepGround = 3.0;
  /// Hull i placed at a pose the frames carry.
  ShipPose ship(std::size_t i, const ShipState& s) const;
};

SceneView scene_view(const RenderInfo& info);

/// Gives the renderer what the view places in the scene: the rest level, the bed, the obstacles,
/// for a particle solver's slab its container's walls (WaterRenderer::set_tank), and for the
/// open-ocean look the ambient sea beyond the region (WaterRenderer::set_ambient_sea).
void place_scene(WaterRenderer& renderer, const SceneView& view);

/// The picture's scale: the visible region's size and, where the floor's tiles show (not deep
/// water), their side, e.g. "region 41.6 x 41.6 m, tiles 5 m" (WaterRenderer::tile_m): the
/// headless caption's and the window panel's.
std::string scale_text(const SceneView& view, const RenderSettings& s, double tile_m);

/// The ships of a frame pair at display time t (FramePair::ship), each with its hull.
void frame_ships(const SceneView& view, const FramePair& frames, double t, std::vector<ShipPose>& out);

/// Applies what the scene's "render" block asked for (caustics, blur, mode, sun) to the settings.
void apply_render_request(const RenderRequest& request, RenderSettings& s);

/// The start-up camera for an image of aspect `aspect`: the scene's camera request, else the
/// look's framing (the whole region from the south; a quasi-2D slab from low; with a ship to
/// follow, the ship and its wake from the side at 10-12 hull lengths), then `ship` placed.
OrbitCamera start_camera(const SceneView& view, double aspect, const ShipPose* ship);
/// Moves a following camera's target with the first ship (its yaw and distance stay).
void follow_ship(const SceneView& view, const ShipPose& ship, OrbitCamera& camera);

/// The settings of the scene's look (docs/viz.md "Looks") for the start-up camera `camera`, then
/// the scene's "render" block (apply_render_request).
RenderSettings look_settings(const SceneView& view, const RenderRequest& request, const OrbitCamera& camera);

/// A solver made for the viewer, and what it tells the viewer.
struct ViewerSolver {
  /// The loaded scene, kept only to make a fresh solver for Reset (make_solver).
  Scene scene;
  RunOptions options;
  std::unique_ptr<Solver> solver;
  RenderInfo info;
  /// The scene as the user named it (a path, or "built-in NAME").
  std::string name;
};

/// Opens `arg` with open_scene (a scene file, or a shipped scene by name; "" the shipped
/// default.json: huygens/common/shipped_scenes.hpp) and makes its solver.
/// Throws SceneError for a bad scene or a file that does not exist.
ViewerSolver open_viewer_solver(const std::string& arg, const RunOptions& options);

/// What huygens-viz shows of a scene before any option: its view, start-up camera (for an image
/// of aspect `aspect`, the ships where the solver has them now) and the look's settings.
struct ViewSetup {
  SceneView view;
  OrbitCamera camera;
  RenderSettings settings;
};
ViewSetup view_setup(const ViewerSolver& vs, double aspect);

/// What the plan view shows: the level (the height about rest, or the depth for LBM/SPH), the
/// flow's speed |u|, the dye or the foam it carries (these need the frames' velocity: LBM
/// scenes), or the particles seen from the side coloured by speed (particle solvers: SPH scenes).
enum class PlanQuantity { level, speed, dye, foam, particles };

/// The frame's data a plan view may show (empty spans: not there).
struct PlanData {
  /// The solver's height() (rows x cols; unit: m).
  std::span<const float> field;
  /// The flow's velocity (rows x cols x 2; unit: m/s; Frame::velocity).
  std::span<const float> velocity;
  /// The dye (rows x cols, in [0, 1]; dye.hpp).
  std::span<const float> dye;
  /// The foam (rows x cols, in [0, 1]; foam.hpp).
  std::span<const float> foam;
  /// x, y, z, speed per particle (Frame::particles).
  std::span<const float> particles;
};

/// Plan view at time `t_s` (WaterRenderer::render_plan): the level of data.field (the height
/// about rest with a diverging map, or the depth, sequential), the speed of data.velocity, the dye, the foam,
/// in mm, cm or m (mm/s, cm/s, m/s) by its range; or the particle view (render_particles); titled
/// with the scene's name and the time.
void render_plan_view(WaterRenderer& renderer, const SceneView& view, const PlanData& data, PlanQuantity quantity,
                      double t_s, const std::string& name, const RenderTarget& target);

}  // namespace huygens
