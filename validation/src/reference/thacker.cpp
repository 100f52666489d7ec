// Thacker (1981) planar oscillation in a parabolic bowl: the formulas of thacker.hpp.
#include "huygens/validation/reference/thacker.hpp"

#include <cmath>
#include <numbers>

namespace huygens {

double thacker_omega(const ThackerParams& p) { return std::sqrt(2.0 * p.gravity_mps2 * p.depth_m) / p.half_width_m; }

double thacker_period(const ThackerParams& p) { return 2.0 * std::numbers::pi / thacker_omega(p); }

double thacker_bed(const ThackerParams& p, double x) {
  const double r = x / p.half_width_m;
  return p.depth_m * r * r;
}

double thacker_centre(const ThackerParams& p, double t) {
  const double w = thacker_omega(p);
  return -(p.speed_mps / w) * std::cos(w * t);
}

double thacker_depth(const ThackerParams& p, double x, double t) {
  const double r = (x - thacker_centre(p, t)) / p.half_width_m;
  return std::abs(r) < 1.0 ? p.depth_m * (1.0 - r * r) : 0.0;
}

double thacker_velocity(const ThackerParams& p, double t) { return p.speed_mps * std::sin(thacker_omega(p) * t); }

}  // namespace huygens
