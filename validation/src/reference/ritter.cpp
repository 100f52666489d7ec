// Ritter (1892) dry-bed dam break: the formulas of ritter.hpp.
#include "huygens/validation/reference/ritter.hpp"

#include <cmath>

namespace huygens {

double ritter_depth(const RitterParams& p, double x, double t) {
  const double c0 = std::sqrt(p.gravity_mps2 * p.depth_m);
  if (x <= -c0 * t) return p.depth_m;
  if (x >= 2.0 * c0 * t) return 0.0;
  const double s = 2.0 * c0 - x / t;
  return s * s / (9.0 * p.gravity_mps2);
}

double ritter_velocity(const RitterParams& p, double x, double t) {
  const double c0 = std::sqrt(p.gravity_mps2 * p.depth_m);
  if (x <= -c0 * t || x >= 2.0 * c0 * t) return 0.0;
  return 2.0 * (c0 + x / t) / 3.0;
}

double ritter_front(const RitterParams& p, double t) { return 2.0 * std::sqrt(p.gravity_mps2 * p.depth_m) * t; }

double ritter_position_of_depth(const RitterParams& p, double h, double t) {
  return (2.0 * std::sqrt(p.gravity_mps2 * p.depth_m) - 3.0 * std::sqrt(p.gravity_mps2 * h)) * t;
}

}  // namespace huygens
