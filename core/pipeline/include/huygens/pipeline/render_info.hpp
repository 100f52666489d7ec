#pragma once
// What a solver tells a viewer besides its frames (docs/design.md 2, one-way data): where the
// visible heightfield sits, the ground under it, obstacles, ship hulls, the display rate, the
// features it can switch at run time and what the scene's "render" block asked for. Each solver
// adapter builds it from its parsed scene (Solver::render_info); a viewer reads nothing else of
// the scene and has no physics of its own. Positions are metres in the full grid's frame (origin
// at the corner of cell (0, 0), x along columns, y along rows, z up; the water at rest is z = 0
// after rest_level_m is subtracted), as in scene files (docs/design.md 6).
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace huygens {

/// Placement of the visible heightfield (Solver::height(), rows = y, cols = x).
struct RenderGrid {
  /// Points along y (unit: points).
  std::size_t rows = 0;
  /// Points along x (unit: points).
  std::size_t cols = 0;
  /// Point spacing (unit: m).
  double dx_m = 1.0;
  /// Position of point (0, 0) (unit: m).
  double x0_m = 0.0, y0_m = 0.0;
};

/// A solid obstacle in the water: an axis-aligned box, a vertical cylinder or a closed triangle
/// mesh (an SPH scene's OBJ obstacle, placed and scaled as the solver has it).
struct RenderObstacle {
  enum class Kind { box, cylinder, mesh };
  Kind kind = Kind::box;
  /// Box: the corners (x, y, z) (unit: m). Mesh: its bounding box.
  std::array<double, 3> min_m{}, max_m{};
  /// Mesh: the triangles, three corners (x, y, z) each, 9 values per triangle (unit: m); the
  /// corners in the OBJ file's order.
  std::vector<float> triangles_m;
  /// Cylinder: axis position (x, y) (unit: m).
  std::array<double, 2> centre_m{};
  /// Cylinder radius (unit: m).
  double radius_m = 0.0;
  /// Cylinder bottom and top (unit: m); +-infinity for a 2D solver's obstacle (the whole column).
  double z0_m = 0.0, z1_m = 0.0;
};

/// A ship's hull (drawn as a Wigley hull at the poses every frame carries, FrameInfo::ships).
struct RenderHull {
  /// Length along the heading (unit: m).
  double length_m = 1.0;
  /// Beam, the width across the heading (unit: m).
  double beam_m = 0.3;
  /// Draft, the depth of the deepest point (unit: m).
  double draft_m = 0.05;
};

/// How the caustics are blurred (paper 004 section 6).
enum class BlurMode { accumulation, float_target, none };

/// How the caustics texture is made ("caustics_mode"; docs/viz.md "Caustics").
enum class CausticsModeRequest { conserving, mip_paper, mip_float, explicit_u8, simple };

/// The kind of picture ("look"; docs/viz.md "Looks"): open ocean (no floor), pool / pond (floor,
/// walls, caustics), shallow water (LBM: bed, solid walls) or SPH (solids, closed surface).
enum class LookRequest { pool, ocean, shallow, sph };

/// The start-up camera ("camera"); unset fields keep the viewer's framing.
struct CameraRequest {
  /// "target_m": the point looked at (x, y, z) (unit: m).
  std::optional<std::array<double, 3>> target_m;
  /// "distance_m": from the target to the eye (unit: m).
  std::optional<double> distance_m;
  /// "yaw_deg": heading of the eye around the target from +x toward +y (unit: deg).
  std::optional<double> yaw_deg;
  /// "pitch_deg": elevation of the eye above the horizontal, negative below it (unit: deg).
  std::optional<double> pitch_deg;
  /// "follow_ship": keep the first ship in view (default: true when the scene has ships).
  std::optional<bool> follow_ship;
};

/// What a scene's optional "render" block asks the viewer for; unset = the viewer's default.
struct RenderRequest {
  /// "caustics": light the ground with the caustics pass.
  std::optional<bool> caustics;
  /// "blur": "accumulation" (the paper's 8-bit emulation), "float" or "none".
  std::optional<BlurMode> blur;
  /// "caustics_mode": "conserving", "mip_paper", "mip_float", "explicit_u8" or "simple".
  std::optional<CausticsModeRequest> caustics_mode;
  /// "look": "pool", "ocean", "shallow" or "sph".
  std::optional<LookRequest> look;
  /// "view": "perspective" or "plan" (the colour-mapped plan view).
  std::optional<bool> plan_view;
  CameraRequest camera;
  /// "sun": {"elevation_deg", "azimuth_deg"}: the sun's elevation above the horizon and its
  /// azimuth from +x toward +y (unit: deg).
  std::optional<double> sun_elevation_deg, sun_azimuth_deg;
  /// "foam": draw the foam a flow carries (LBM scenes; default on).
  std::optional<bool> foam;
};

/// A feature the solver switches at run time on cmd::Toggle (a viewer shows a checkbox for it).
struct RenderToggle {
  /// The cmd::Toggle feature name ("stokes", "wind").
  std::string name;
  /// Text for the control.
  std::string label;
  /// State at construction.
  bool on = false;
};

/// The sea beyond the visible region as the solver computes it: its slopes on a periodic tile of
/// n x n points and side length_m whose point (0, 0) is at the origin of the full grid's frame (a
/// Huygens scene's wind sea without the ships', the drops' and the second-order waves; its
/// implementation is the solver's, huygens/ambient_slopes.hpp). Called on the viewer's thread.
class FarSeaSlopes {
 public:
  virtual ~FarSeaSlopes() = default;
  /// Points per side of the tile (unit: points).
  virtual int n() const = 0;
  /// Side of the tile (unit: m).
  virtual double length_m() const = 0;
  /// Slopes (d eta/dx, d eta/dy) at time t (unit: s) at point (row r = y, column c = x),
  /// interleaved, row-major, 2 n^2 floats (unit: 1), valid until the next call. No allocation
  /// after the first call.
  virtual std::span<const float> compute(double t) = 0;
  /// Mean square slope |grad eta|^2 over the tile (unit: 1; constant in time); with
  /// `central_differences`, of the slopes central differences on the tile's grid resolve.
  virtual double mean_square_slope(bool central_differences) = 0;
};

/// At most this many points a side for the far sea's tile (its longest waves).
constexpr int kMaxAmbientModes = 1024;
/// The ambient wind sea of a scene, for the open-ocean look's sea beyond the region.
struct RenderAmbientSea {
  /// The solver's slope source.
  std::shared_ptr<FarSeaSlopes> slopes;
  /// Wind speed at 10 m (unit: m/s): Cox and Munk's mean square slope 0.003 + 5.12e-3 U of the
  /// sea's waves down to the shortest, of which the tile resolves a part.
  double wind_speed_mps = 0.0;
};

struct RenderInfo {
  RenderGrid grid;
  /// Level of the water at rest in height() (unit: m): 0 for an elevation field (Huygens), the
  /// mean initial height for a height above a floor (SPH, LBM). A viewer draws height() - rest.
  double rest_level_m = 0.0;
  /// Depth of the flat bottom below the water at rest (unit: m); nullopt = deep water.
  std::optional<double> depth_m;
  /// Bed elevation per point of height() (rows x cols, unit: m, same frame as height()); empty
  /// when the bottom is flat.
  std::vector<float> bed_m;
  std::vector<RenderObstacle> obstacles;
  /// Hull i belongs to ship i of the frames.
  std::vector<RenderHull> hulls;
  /// A particle solver's container, the box from (0, 0, 0) to box_m (unit: m): the particle
  /// view's extent (Solver::particles()); nullopt for grid solvers.
  std::optional<std::array<double, 3>> particle_box_m;
  /// The particles' spacing at rest (unit: m): the particle view draws discs of this diameter.
  double particle_spacing_m = 0.0;
  /// Full step (unit: s); 0 when the step is adaptive (SPH).
  double dt_s = 0.0;
  /// Displayed frames per full step (unit: 1; Solver::display_per_step()).
  int display_per_step = 1;
  /// Simulated time between two displayed frames (unit: s): dt_s / display_per_step, or the
  /// solver's choice for an adaptive step.
  double frame_dt_s = 1.0 / 60.0;
  /// Features cmd::Toggle switches; anything else is refused (no control for it).
  std::vector<RenderToggle> toggles;
  RenderRequest request;
  /// The look the solver's water is drawn with unless the scene's "render.look" names one: each
  /// solver states its own (the viewer guesses nothing from the fields it is given).
  LookRequest default_look = LookRequest::pool;
  /// The ambient sea (a Huygens scene with a wind block); nullopt otherwise. It is on while the
  /// "wind" toggle is.
  std::optional<RenderAmbientSea> ambient_sea;
};

/// The mean of a height field (unit: m): RenderInfo::rest_level_m of a solver whose height() is a
/// level above a floor, taken before the first step; 0 for an empty field.
double mean_level(std::span<const float> height);

/// (pipeline/render_request.hpp reads the scene's "render" block into a RenderRequest.)

}  // namespace huygens
