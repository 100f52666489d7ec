#pragma once
// Linear dispersion of gravity-capillary water waves (paper 004 section 3; docs/design.md 3.1):
//   omega(k) = sqrt((g k + (sigma/rho) k^3) tanh(k h)),  deep water (h = infinity): tanh -> 1.
#include <cmath>
#include <limits>

namespace huygens {

/// Physical properties of the water body.
struct Water {
  /// Gravitational acceleration (unit: m/s^2).
  double gravity_mps2 = 9.81;
  /// Surface tension sigma (unit: N/m); 0 gives pure gravity waves.
  double surface_tension_npm = 0.072;
  /// Mass density rho (unit: kg/m^3).
  double density_kgpm3 = 1000.0;
  /// Still-water depth h (unit: m); infinity means deep water.
  double depth_m = std::numeric_limits<double>::infinity();

  bool deep() const { return !std::isfinite(depth_m); }
};

/// Angular frequency omega(k) (unit: rad/s) for wavenumber k (unit: rad/m); omega(0) = 0.
double omega(const Water& w, double k);
/// Phase speed omega/k (unit: m/s); the k -> 0 limit sqrt(g h) (finite depth) or infinity (deep).
double phase_speed(const Water& w, double k);
/// Group speed d omega / dk (unit: m/s), analytic derivative.
double group_speed(const Water& w, double k);
/// Minimum phase speed of deep-water gravity-capillary waves c_min = (4 g sigma / rho)^(1/4) (unit: m/s).
double min_phase_speed(const Water& w);
/// Wavenumber of the minimum phase speed k_m = sqrt(rho g / sigma) (unit: rad/m).
double min_phase_speed_wavenumber(const Water& w);

}  // namespace huygens
