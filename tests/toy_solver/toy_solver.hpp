#pragma once
// A test-only solver added through the registry (solvers/registry.hpp), with no edit to the library
// or the programs: the linear long-wave equation eta_tt = g H (eta_xx + eta_yy) on a periodic square
// grid, central differences in space, leapfrog in time. Its scene block:
//   "solver": "toy", "toy": {"n": 64, "length_m": 1, "depth_m": 0.1, "dt_s": 0.005, "amplitude_m": 0.01,
//                            "mode": 1}
// starts the standing wave eta = A cos(2 pi m x / L) at rest. The scheme's own solution of it is
// A cos(k x) cos(w_d t) with sin(w_d dt / 2) = (c dt / dx) sin(k dx / 2), c = sqrt(g H), so the
// validation case "toy_standing_wave" measures the period against 2 pi / (c k) (error
// ~ (k dx)^2 / 24 - (c k dt)^2 / 24).
#include <string>
#include <vector>

#include "huygens/pipeline/solver_entry.hpp"
#include "huygens/validation/validation.hpp"

namespace huygens::toy {

struct ToyParams {
  int n = 64;                 ///< grid points per side (unit: 1)
  double length_m = 1.0;      ///< side of the periodic square (unit: m)
  double depth_m = 0.1;       ///< H (unit: m)
  double dt_s = 0.005;        ///< time step (unit: s)
  double amplitude_m = 0.01;  ///< A (unit: m)
  int mode = 1;               ///< m: wavenumber k = 2 pi m / L (unit: 1)
};

/// Reads the "toy" block; throws SceneError naming the JSON path (also for c dt / dx >= 1 / sqrt(2)).
ToyParams parse_toy_scene(const Scene& scene);

/// The registry entry of the toy solver (name "toy").
SolverEntry toy_solver_entry();

/// Its validation case, "toy_standing_wave".
std::vector<ValidationCase> toy_validation_cases();

}  // namespace huygens::toy
