#pragma once
// The shallow-water LBM (paper 002) validation runs that the tests and the benchmarks call at
// their own sizes; `huygens validate` runs them at full size through lbm_validation_cases()
// (validation.hpp). References: Stoker's dam break (huygens/lbm/stoker.hpp), the lake at rest
// over the Goutal-Maurel bump, volume conservation, the long-wave speed sqrt(g h).
#include <cstdint>
#include <string>
#include <vector>

#include "huygens/lbm/shallow.hpp"

namespace huygens {

/// The one-dimensional wet-bed dam break of the validation (a 100 m channel of one row,
/// periodic in y, walls at both ends; dam at 50 m, h_L = 1 m, h_R = h_L / ratio), run until the
/// fan head or the shock is 5 m from a wall, against stoker_solve().
struct LbmDamBreakResult {
  /// sum |h - h_exact| / sum h_exact over all cells (cell-centre values) at the end.
  double l1_relative = 0;
  /// Wall time of the run (unit: s).
  double wall_s = 0;
  /// Steps asked for: until the fan head or the shock is 5 m from a wall (unit: 1).
  std::int64_t steps = 0;
  /// Simulated time at the end (unit: s).
  double time_s = 0;
  /// Non-empty when the parameters were refused before the run.
  std::string refused;
  /// Non-empty when the run stopped (non-finite value or a dry cell).
  std::string stopped;
  /// Steps completed when the run ended or stopped.
  std::int64_t done_steps = 0;
  /// Froude number of the Stoker middle state (unit: 1).
  double froude = 0;
};
/// tau: BGK relaxation time; cfl: largest Stoker signal speed over the lattice speed.
/// froude_check = false skips the transcritical refusal (to show what happens without it).
LbmDamBreakResult lbm_dam_break_1d(double ratio, int cells, double tau = 0.55, double cfl = 0.5,
                                   bool froude_check = true);

/// Lake at rest over the Goutal-Maurel bump z_b = 0.2 - 0.05 (x - 10)^2 (8 < x < 12) in a 25 m
/// channel (250 x 4 cells, walls), still surface at 0.7 m (0.5 m above the crest), after `steps`.
struct LbmLakeResult {
  /// Largest |u| (unit: m/s).
  double max_speed_mps = 0;
  /// Largest |h + z_b - 0.7| (unit: m).
  double max_surface_error_m = 0;
};
LbmLakeResult lbm_lake_at_rest(std::int64_t steps, LbmBedForce force);

/// Relative change of the total volume over `steps` in a closed rows x cols box (no-slip walls)
/// with a bed mound and a released hump of water (accumulated in double).
double lbm_mass_drift(int rows, int cols, std::int64_t steps);

/// Ritter's dry-bed dam break (validation/reference/ritter.hpp): a channel of `cells` (length_m,
/// walls at both ends) and `rows` (periodic in y, or free-slip sides), h0 = depth_m at rest left of
/// the dam at dam_fraction of the length, dry beyond; run until the rarefaction head is `head_gap`
/// of the dam's distance from the upstream wall (the front is then 2 (1 - head_gap) of that
/// distance beyond the dam). Depths are compared cell by cell (L1, local error); the 0.1 h0 and
/// 0.01 h0 points and the profile use the depth averaged over the rows.
struct LbmRitterSetup {
  int cells = 1024, rows = 1;
  bool slip_sides = false;
  double length_m = 100.0, depth_m = 1.0;
  /// BGK relaxation time, and the Courant number of the front speed 2 sqrt(g h0).
  double tau = 0.55, cfl = 0.5;
  /// > 0: the run starts at the first step at or after start_s (unit: s) from Ritter's exact state
  /// there (cell averages of depth and discharge) instead of the dam, and ends at the same step as
  /// from the dam; this removes the first steps, in which the fan and its thin tip span only a few
  /// cells (docs/lbm.md, "The front of a dam break onto a dry bed").
  double start_s = 0.0;
  double head_gap = 0.1;
  /// The dam's distance from the upstream wall as a fraction of the length.
  double dam_fraction = 1.0 / 3.0;
  /// Keep the end state's profile (LbmRitterResult::x_m, depth_m, velocity_mps).
  bool keep_profile = false;
};
struct LbmRitterResult {
  /// sum |h - h_exact| / sum h_exact over all cells at the end.
  double l1_relative = 0;
  /// Largest |h - h_exact| / h_exact over the cells whose exact depth exceeds 0.05 h0, and the
  /// cell centre where it is (unit: m from the dam).
  double max_local_error = 0, max_local_error_x_m = 0;
  /// Numerical front: right face of the last wet cell (unit: m from the dam).
  double front_m = 0;
  /// Exact front 2 sqrt(g h0) t (unit: m from the dam).
  double front_exact_m = 0;
  /// Where the exact depth falls to the dry threshold min_depth_m, (2 sqrt(g h0) - 3 sqrt(g
  /// min_depth_m)) t (unit: m from the dam): what the last wet cell's face is compared with.
  double front_threshold_exact_m = 0;
  /// Where the depth falls to 0.01 h0 (the last crossing), measured (interpolated) and exact (unit: m from the dam).
  double x01_m = 0, x01_exact_m = 0;
  /// Where the depth falls to 0.1 h0 (the last crossing), measured (interpolated) and exact (unit: m from the dam).
  double x10_m = 0, x10_exact_m = 0;
  /// Smallest depth over the run's end state (unit: m) and the relative volume change.
  double min_depth_m = 0, volume_drift = 0;
  /// Cell size (unit: m), steps and the simulated time (unit: s).
  double cell_m = 0, time_s = 0;
  std::int64_t steps = 0;
  /// Non-empty when the run stopped (negative depth or a non-finite value).
  std::string stopped;
  /// With keep_profile: cell centres (unit: m from the dam), depth (m) and velocity (m/s) at the end.
  std::vector<double> x_m, depth_m, velocity_mps;
};
LbmRitterResult lbm_ritter(const LbmRitterSetup& setup);
/// The 100 m channel of 1 m depth at `cells`.
LbmRitterResult lbm_ritter(int cells, double tau = 0.55, double cfl = 0.5, double start_s = 0.0);

/// Thacker's planar oscillation in a parabolic bowl (validation/reference/thacker.hpp), one row
/// (periodic in y) of `cells` across [-2a, 2a], a = 1 m, h0 = 0.5 m, U0 = 0.5 m/s, released at
/// rest (t = 0: s = -U0/omega); measured after `periods` periods.
struct LbmThackerResult {
  /// Shorelines where h = 0.01 h0, measured (interpolated) minus exact, left and right (unit: m).
  double left_error_m = 0, right_error_m = 0;
  /// sum |h - h_exact| / sum h_exact over all cells.
  double l1_relative = 0;
  /// Largest |eta - eta_exact| over cells where the exact depth exceeds 0.1 h0 (unit: m).
  double surface_error_m = 0;
  /// Relative volume change and the smallest depth at the end (unit: m).
  double volume_drift = 0, min_depth_m = 0;
  /// Cell size (unit: m); non-empty when the run stopped.
  double cell_m = 0;
  std::string stopped;
};
LbmThackerResult lbm_thacker(int cells, double periods, double tau = 0.55);

/// Still water (surface 1 m) around islands that stand above it (two cones and a flat-topped
/// rectangle) in a closed 64 x 64 box of 1 m cells, after `steps`: the wet/dry rule must leave it still.
struct LbmIslandsResult {
  /// Largest |u| over the cells (unit: m/s) and largest |h + z_b - 1| over wet cells (unit: m).
  double max_speed_mps = 0, max_surface_error_m = 0;
  /// Largest depth over the cells that started dry (unit: m).
  double max_dry_depth_m = 0;
  /// Dry cells at the start and at the end.
  std::size_t dry_start = 0, dry_end = 0;
};
LbmIslandsResult lbm_islands_at_rest(std::int64_t steps);

/// Wetting and drying in a closed rows x cols box of 1 m cells: a hump of water released on a
/// beach sloping up to dry land on one side, with an island; relative volume change over `steps`
/// (accumulated in double), the smallest depth seen at the end and the dry cells at the end.
struct LbmWetDryMassResult {
  double volume_drift = 0, min_depth_m = 0;
  std::size_t dry_end = 0;
  std::string stopped;
};
LbmWetDryMassResult lbm_wet_dry_mass(int rows, int cols, std::int64_t steps);

/// Zhou's partial dam break (the setting of scenes/dam_break.json: 200 m x 200 m basin, dam at
/// x = 100 m with a 75 m breach) with 10 m upstream and 10/ratio m downstream, `steps` steps.
struct LbmPartialDamResult {
  std::int64_t steps = 0, done_steps = 0;
  double time_s = 0, volume_drift = 0, min_depth_m = 0;
  /// Largest number of dry cells seen at the end of a step.
  std::size_t max_dry = 0;
  /// Steps the all-wet pass handed to the wet/dry pass to redo (LbmShallow::redone_steps()).
  std::int64_t redone_steps = 0;
  std::string refused, stopped;
};
LbmPartialDamResult lbm_partial_dam(double ratio, std::int64_t steps);

/// Speed of a small long-wave pulse (amplitude 1e-4 h, 1 m deep) over sqrt(g h), measured by
/// the centroid of the right-going half; `cells` along a 1-row periodic channel.
double lbm_wave_speed_ratio(int cells);

}  // namespace huygens
