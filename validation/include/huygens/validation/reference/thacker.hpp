#pragma once
// Thacker's (1981, J. Fluid Mech. 107, 499-508) planar oscillation in a parabolic bowl, in its
// one-dimensional form (a cross-section of his planar solution; no friction). Bed
// z(x) = h0 (x/a)^2 (x from the bowl's centre); the water is a parabolic lens that slides rigidly
// with a planar surface. Substituting eta = alpha(t) x + beta(t), u = U(t) into the shallow-water
// equations gives U'' = -omega^2 U with omega = sqrt(2 g h0) / a, so with U = U0 sin(omega t):
//   h(x, t) = h0 (1 - ((x - s(t)) / a)^2)  for |x - s(t)| < a, else 0,  s(t) = -(U0 / omega) cos(omega t)
//   u(x, t) = U0 sin(omega t),  eta = h0 (1 + (2 x s - s^2) / a^2),  shorelines x = s(t) -/+ a
// Period T = 2 pi a / sqrt(2 g h0).
namespace huygens {

struct ThackerParams {
  /// Depth of the lens at its centre, and the bed height at |x| = a (unit: m).
  double depth_m = 0.5;
  /// Half width of the lens (unit: m).
  double half_width_m = 1.0;
  /// Amplitude of the uniform velocity (unit: m/s).
  double speed_mps = 0.5;
  /// Gravitational acceleration (unit: m/s^2).
  double gravity_mps2 = 9.81;
};

/// Angular frequency omega = sqrt(2 g h0) / a (unit: 1/s).
double thacker_omega(const ThackerParams& p);
/// Period 2 pi / omega (unit: s).
double thacker_period(const ThackerParams& p);
/// Bed z(x) = h0 (x/a)^2 at x from the centre (unit: m).
double thacker_bed(const ThackerParams& p, double x_m);
/// Centre of the lens s(t) (unit: m).
double thacker_centre(const ThackerParams& p, double t_s);
/// Depth h(x, t) (unit: m), 0 outside the lens.
double thacker_depth(const ThackerParams& p, double x_m, double t_s);
/// Velocity u(t) inside the lens (unit: m/s).
double thacker_velocity(const ThackerParams& p, double t_s);

}  // namespace huygens
