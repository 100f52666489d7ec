#pragma once
// Foam carried by the flow (paper 002 sec. 3.2, docs/viz.md "Flow"): a scalar f(x, y) in [0, 1]
// on the visible grid, advected by the frames' depth-averaged velocity u (Frame::velocity) with
// the dye's semi-Lagrangian step (dye.hpp, f'(x) = f(x - u dt)), seeded where the flow is fast
// or breaking and fading with a half-life. Paper 002 seeds a time-to-live texture where splash
// particles fall back and counts it down linearly; a shallow-water solver has no splash
// particles, so the seed here is where the depth-averaged flow would make them, from three
// dimensionless numbers of the frame (h the depth, c = sqrt(g h) the long-wave speed):
//   Fr = |u| / c                       supercritical flow (a jet, a surge onto dry land),
//   B  = -div(h u) / c = eta_t / c     the surface rising faster than c allows: a bore or a
//                                      breaking front (the breaking-onset criterion
//                                      eta_t > alpha c of Kennedy et al. 2000, Boussinesq
//                                      waves; eta_t = -div(h u) is the shallow-water mass balance),
//   W  = |omega| h / c                 shear: the vorticity omega = dv/dx - du/dy over the
//                                      gravity-wave time sqrt(h / g) (shear layers at solids,
//                                      the vortices shed behind them),
// each ramped to a seed s_i = clamp((X - X_on) / (X_full - X_on), 0, 1), s = max_i s_i (0 where
// h < min_depth). Over a step dt, after the advection, with s held:
//   df/dt = -lambda f + r s (1 - f),   lambda = ln 2 / half_life,  r = 1 / seed_time,
// solved exactly: f <- f* + (f - f*) exp(-(lambda + r s) dt),  f* = r s / (lambda + r s),
// so still water (s = 0) halves its foam every half_life and a steady seed holds f at f*.
#include <span>
#include <vector>

#include "refraction.hpp"

namespace huygens {

// The thresholds (docs/viz.md "Foam" has the measured ranges of Fr, B and W in the shipped
// scenes): Fr from 4.5, where a flow stopped by a jump makes a steady, strongly aerated jump (the
// usual classification of hydraulic jumps by their upstream Froude number), so the thin fast
// sheet at a surge's tip foams and not the whole supercritical flood behind it (Fr ~ 1 there);
// B from 0.15 to 0.65, Kennedy et al.'s breaking cessation and onset values of eta_t / c; W from
// 0.3 to 0.8, a visual choice: the shear layers off a cylinder and a breach's corners.
struct FoamParams {
  /// Time in which unseeded foam halves (unit: s).
  double half_life_s = 4.0;
  /// Time constant of the seeding where s = 1 (unit: s).
  double seed_time_s = 0.1;
  /// Gravity in c = sqrt(g h) (unit: m/s^2; the viewer does not know the scene's).
  double gravity_mps2 = 9.81;
  /// Thinner water is dry: no seed (unit: m; the renderer's dry depth).
  double min_depth_m = 0.002;
  /// Froude number where the seed starts and where it is full (unit: 1).
  double froude_on = 4.5, froude_full = 9.0;
  /// eta_t / c where the seed starts and where it is full (unit: 1).
  double breaking_on = 0.15, breaking_full = 0.65;
  /// |omega| sqrt(h / g) where the seed starts and where it is full (unit: 1).
  double shear_on = 0.3, shear_full = 0.8;
};

class FoamField {
 public:
  /// `bed`: the bed under the heights (rows x cols, m, the heights' frame; RenderInfo::bed_m),
  /// empty = 0: the depth is h = max(0, height - bed).
  FoamField(const GridPlacement& grid, std::span<const float> bed, const FoamParams& params = {});
  /// No foam.
  void reset();
  /// One step of `dt` seconds: advect with `velocity` (rows x cols x 2, m/s), then seed from
  /// the frame's `height` (rows x cols, m; the solver's height(), bed + depth) and its velocity,
  /// then fade. Nothing is allocated.
  void step(std::span<const float> height, std::span<const float> velocity, double dt);
  /// Foam per point, rows x cols, in [0, 1] (unit: 1).
  std::span<const float> values() const { return f_; }
  /// The last step's seed s per point, rows x cols, in [0, 1] (unit: 1).
  std::span<const float> seed() const { return s_; }
  const FoamParams& params() const { return p_; }

 private:
  void compute_seed(std::span<const float> height, std::span<const float> velocity);
  GridPlacement grid_;
  FoamParams p_;
  std::vector<float> bed_, f_, next_, s_, hu_;
};

}  // namespace huygens
