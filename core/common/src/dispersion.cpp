#include "huygens/common/dispersion.hpp"

namespace huygens {

namespace {
double tension_ratio(const Water& w) { return w.surface_tension_npm / w.density_kgpm3; }
}  // namespace

double omega(const Water& w, double k) {
  if (k <= 0.0) return 0.0;
  const double s = tension_ratio(w);
  const double deep = w.gravity_mps2 * k + s * k * k * k;
  return std::sqrt(w.deep() ? deep : deep * std::tanh(k * w.depth_m));
}

double phase_speed(const Water& w, double k) {
  if (k <= 0.0) return w.deep() ? std::numeric_limits<double>::infinity() : std::sqrt(w.gravity_mps2 * w.depth_m);
  return omega(w, k) / k;
}

double group_speed(const Water& w, double k) {
  if (k <= 0.0) return w.deep() ? std::numeric_limits<double>::infinity() : std::sqrt(w.gravity_mps2 * w.depth_m);
  // omega^2 = F(k) T(k) with F = g k + s k^3, T = tanh(k h); d omega/dk = (F' T + F T') / (2 omega).
  const double s = tension_ratio(w);
  const double f = w.gravity_mps2 * k + s * k * k * k;
  const double df = w.gravity_mps2 + 3.0 * s * k * k;
  if (w.deep()) return df / (2.0 * std::sqrt(f));
  const double t = std::tanh(k * w.depth_m);
  const double dt = w.depth_m * (1.0 - t * t);
  return (df * t + f * dt) / (2.0 * std::sqrt(f * t));
}

double min_phase_speed(const Water& w) { return std::pow(4.0 * w.gravity_mps2 * tension_ratio(w), 0.25); }

double min_phase_speed_wavenumber(const Water& w) { return std::sqrt(w.gravity_mps2 / tension_ratio(w)); }

}  // namespace huygens
