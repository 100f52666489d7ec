#pragma once
// The shallow-water LBM (paper 002) validation runs that the tests and the benchmarks call at
// their own sizes; `huygens validate` runs them at full size through lbm_validation_cases()
// (validation.hpp). References: Stoker's dam break (huygens/lbm/stoker.hpp), the lake at rest
// over the Goutal-Maurel bump, volume conservation, the long-wave speed sqrt(g h).
#include <cstdint>
#include <string>

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

/// Speed of a small long-wave pulse (amplitude 1e-4 h, 1 m deep) over sqrt(g h), measured by
/// the centroid of the right-going half; `cells` along a 1-row periodic channel.
double lbm_wave_speed_ratio(int cells);

}  // namespace huygens
