#pragma once
// Ritter's (1892) exact dam break onto a dry bed: depth h0 at rest for x < 0, dry for x > 0,
// released at t = 0 on a flat frictionless bed. With c0 = sqrt(g h0) the flow is one centred
// rarefaction (Stoker 1957, sec. 10.7):
//   h = h0                                  for x < -c0 t
//   h = (2 c0 - x/t)^2 / (9 g),  u = 2 (c0 + x/t) / 3     for -c0 t <= x <= 2 c0 t
//   h = 0                                   for x > 2 c0 t (the front moves at 2 c0)
namespace huygens {

struct RitterParams {
  /// Depth behind the dam (unit: m).
  double depth_m = 1.0;
  /// Gravitational acceleration (unit: m/s^2).
  double gravity_mps2 = 9.81;
};

/// Depth at position x from the dam (unit: m) at time t > 0 (unit: s).
double ritter_depth(const RitterParams& p, double x_m, double t_s);
/// Velocity at x and t (unit: m/s); 0 where the bed is dry or the water is still.
double ritter_velocity(const RitterParams& p, double x_m, double t_s);
/// Position of the front, where h = 0: 2 c0 t (unit: m).
double ritter_front(const RitterParams& p, double t_s);
/// Position where the depth falls to `depth_m` (0 < depth_m < h0) at time t: x = (2 c0 - 3 sqrt(g h)) t (unit: m).
double ritter_position_of_depth(const RitterParams& p, double depth_m, double t_s);

}  // namespace huygens
