#include "huygens/lbm/stoker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace huygens {

namespace {

// Residual of the middle-state relation: fan invariant minus shock relation, decreasing in h_m.
double residual(double hm, double hl, double hr, double g) {
  return 2.0 * (std::sqrt(g * hl) - std::sqrt(g * hm)) - (hm - hr) * std::sqrt(0.5 * g * (hm + hr) / (hm * hr));
}

}  // namespace

StokerSolution stoker_solve(const StokerParams& p) {
  const double hl = p.left_depth_m, hr = p.right_depth_m, g = p.gravity_mps2;
  if (!(g > 0) || !(hr > 0) || !(hl > hr) || !std::isfinite(hl))
    throw std::invalid_argument("stoker_solve: needs 0 < right_depth_m < left_depth_m and gravity_mps2 > 0");
  // residual(h_R) = 2 (c_L - c_R) > 0 and residual(h_L) < 0: bisection keeps a bracket.
  double lo = hr, hi = hl;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hl; ++i) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid, hl, hr, g) > 0 ? lo : hi) = mid;
  }
  double hm = 0.5 * (lo + hi);
  // Newton polish with a numerical derivative (stays inside the bracket or is discarded).
  for (int i = 0; i < 3; ++i) {
    const double d = 1e-7 * hm;
    const double f = residual(hm, hl, hr, g);
    const double df = (residual(hm + d, hl, hr, g) - residual(hm - d, hl, hr, g)) / (2 * d);
    const double next = hm - f / df;
    if (df != 0 && next > hr && next < hl) hm = next;
  }
  StokerSolution s;
  s.params = p;
  s.middle_depth_m = hm;
  s.middle_velocity_mps = 2.0 * (std::sqrt(g * hl) - std::sqrt(g * hm));
  s.shock_speed_mps = hm * s.middle_velocity_mps / (hm - hr);
  s.fan_head_speed_mps = -std::sqrt(g * hl);
  s.fan_tail_speed_mps = s.middle_velocity_mps - std::sqrt(g * hm);
  // |u| + c: c_L at the fan head; u + c grows monotonically through the fan to the middle state.
  s.max_signal_speed_mps =
      std::max({std::sqrt(g * hl), s.middle_velocity_mps + std::sqrt(g * hm), std::sqrt(g * hr), s.shock_speed_mps});
  return s;
}

double StokerSolution::depth(double xi) const {
  const double g = params.gravity_mps2;
  if (xi <= fan_head_speed_mps) return params.left_depth_m;
  if (xi <= fan_tail_speed_mps) {
    const double c = (2.0 * std::sqrt(g * params.left_depth_m) - xi) / 3.0;
    return c * c / g;
  }
  if (xi < shock_speed_mps) return middle_depth_m;
  return params.right_depth_m;
}

double StokerSolution::velocity(double xi) const {
  if (xi <= fan_head_speed_mps) return 0.0;
  if (xi <= fan_tail_speed_mps) return 2.0 * (std::sqrt(params.gravity_mps2 * params.left_depth_m) + xi) / 3.0;
  if (xi < shock_speed_mps) return middle_velocity_mps;
  return 0.0;
}

}  // namespace huygens
