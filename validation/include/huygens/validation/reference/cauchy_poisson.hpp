#pragma once
// The exact linear (Cauchy-Poisson) ring wave of an axisymmetric Gaussian elevation released
// from rest, for validating the Huygens propagator (paper 004 section 3; docs/design.md 3.3):
//   eta(r, t) = (1 / 2 pi) int_0^inf k eta0^(k) cos(omega(k) t) J0(k r) dk,
//   eta0(r) = A exp(-r^2 / (2 sigma^2))  =>  eta0^(k) = 2 pi sigma^2 A exp(-k^2 sigma^2 / 2)
// (2D Fourier transform int eta0 e^{-i k.x} d^2x of a radial function is its Hankel transform
// 2 pi int_0^inf r eta0(r) J0(k r) dr; at t = 0 the inverse gives back the Gaussian since
// int_0^inf k e^{-k^2 sigma^2/2} J0(k r) dk = e^{-r^2/(2 sigma^2)} / sigma^2).
// The integral is evaluated with the project's own adaptive Gauss-Kronrod (7, 15) quadrature.
#include <functional>

#include "huygens/common/dispersion.hpp"

namespace huygens {

/// Result of an adaptive quadrature.
struct QuadratureResult {
  /// Integral estimate.
  double value = 0;
  /// Estimated absolute error (sum over panels of |K15 - G7|).
  double error = 0;
  /// Integrand evaluations.
  long evaluations = 0;
  /// Panels in the final partition.
  int panels = 0;
};

/// Globally adaptive Gauss-Kronrod (7, 15) quadrature of f over [a, b]: starts from
/// `initial_panels` equal panels and bisects the panel with the largest error estimate until
/// the summed estimate is <= abs_tol or `max_panels` is reached.
QuadratureResult integrate_gk15(const std::function<double(double)>& f, double a, double b, double abs_tol,
                                int initial_panels = 16, int max_panels = 200000);

/// J0(x) (glibc ::j0, checked against std::cyl_bessel_j in the tests; 40x faster).
double bessel_j0(double x);

/// A Gaussian hump released from rest.
struct CauchyPoissonGaussian {
  /// Water (dispersion omega(k)).
  Water water;
  /// Standard deviation of the Gaussian (unit: m).
  double sigma_m = 0.1;
  /// Peak elevation A at t = 0 (unit: m).
  double amplitude_m = 0.01;
  /// Absolute tolerance of the quadrature relative to A (unit: 1).
  double rel_tolerance = 1e-10;
};

/// eta(r, t) of the Cauchy-Poisson problem (unit: m); r in m, t in s. The spectrum is cut at
/// k sigma = 9.5, where exp(-k^2 sigma^2 / 2) < 2e-20.
double cauchy_poisson_eta(const CauchyPoissonGaussian& g, double r_m, double t_s);
/// The same with the quadrature report.
QuadratureResult cauchy_poisson_quadrature(const CauchyPoissonGaussian& g, double r_m, double t_s);

/// Independent check at the centre for deep gravity water (sigma_surface = 0):
///   eta(0, t) / A = sum_n (-1)^n Gamma(n/2 + 1) q^n / (2n)!,  q = sqrt(2) g t^2 / sigma,
/// from cos(sqrt(g k) t) = sum_n (-1)^n (g k t^2)^n / (2n)! and
/// int_0^inf k^{n+1} e^{-k^2 sigma^2/2} dk = Gamma(n/2 + 1) 2^{n/2} / sigma^{n+2}.
/// Accurate while q is moderate (q < 30: terms stay below 1e6).
double cauchy_poisson_center_gravity_series(double gravity, double sigma_m, double amplitude_m, double t_s);

}  // namespace huygens
