#pragma once
// Analytic one-dimensional dam break on a wet, flat, frictionless bed (Stoker 1957, "Water Waves",
// ch. 10): depth h_L for x < x0, h_R < h_L beyond, at rest at t = 0. Self-similar in xi = (x - x0)/t:
//   xi < -c_L                   h = h_L, u = 0                     (undisturbed)
//   -c_L <= xi <= u_m - c_m     h = (2 c_L - xi)^2 / (9 g), u = 2 (c_L + xi) / 3   (rarefaction fan)
//   u_m - c_m < xi < s          h = h_m, u = u_m                   (middle state)
//   xi >= s                     h = h_R, u = 0                     (undisturbed)
// with c = sqrt(g h); h_m solves the fan's Riemann invariant with the shock's Rankine-Hugoniot
// relations: u_m = 2 (c_L - c_m) = (h_m - h_R) sqrt(g (h_m + h_R) / (2 h_m h_R)), s = h_m u_m / (h_m - h_R).
// stoker_solve() finds h_m by bisection refined by Newton. It lives in core/lbm, not in validation,
// because the LBM scene adapter bounds a dam's time step and refuses its transcritical flow with it.
namespace huygens {

struct StokerParams {
  /// Depth upstream of the dam, x < x0 (unit: m).
  double left_depth_m = 1.0;
  /// Depth downstream of the dam, x > x0 (unit: m); must be > 0 and < left_depth_m.
  double right_depth_m = 0.5;
  /// Gravitational acceleration (unit: m/s^2).
  double gravity_mps2 = 9.81;
};

struct StokerSolution {
  StokerParams params;
  /// Depth of the middle state between fan and shock (unit: m).
  double middle_depth_m = 0;
  /// Velocity of the middle state (unit: m/s).
  double middle_velocity_mps = 0;
  /// Speed of the shock (bore) moving into the shallow side (unit: m/s).
  double shock_speed_mps = 0;
  /// Speed of the fan's head moving into the deep side, -sqrt(g h_L) (unit: m/s).
  double fan_head_speed_mps = 0;
  /// Speed of the fan's tail, u_m - sqrt(g h_m) (unit: m/s; > 0 when the flow turns supercritical).
  double fan_tail_speed_mps = 0;
  /// Largest characteristic speed |u| + sqrt(g h) anywhere in the solution (unit: m/s).
  double max_signal_speed_mps = 0;

  /// Depth (unit: m) at self-similar coordinate xi = (x - x0) / t (unit: m/s).
  double depth(double xi) const;
  /// Velocity (unit: m/s) at xi = (x - x0) / t.
  double velocity(double xi) const;
};

/// Solves the middle state. Throws std::invalid_argument unless 0 < h_R < h_L and g > 0.
StokerSolution stoker_solve(const StokerParams& p);

}  // namespace huygens
