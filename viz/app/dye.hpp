#pragma once
// Dye carried by the flow (paper 002's flow visualisation, docs/viz.md "Flow"): a passive
// tracer c(x, y) on the visible grid, advected by the solver's depth-averaged velocity u that
// the frames carry (Frame::velocity, an LBM's "u"): dc/dt + u . grad c = 0, by the
// semi-Lagrangian step c'(x) = c(x - u(x) dt) with bilinear interpolation, clamped at the
// region's edge (a boundary point whose backtrace leaves the region keeps its value, so an
// inflow edge keeps feeding its bands in). It starts as bands along x alternating across y, so
// the flow shows as their deformation: a vortex street as a wavy wake, a dam break's front as
// the bands pushed through the breach.
#include <span>
#include <vector>

#include "refraction.hpp"

namespace huygens {

/// The semi-Lagrangian step of a scalar carried by `velocity` (rows x cols x 2, (u, v) per
/// point, m/s) over `dt` seconds: out(x) = in(x - u(x) dt), bilinear, the backtrace clamped to
/// the region (an edge point whose backtrace leaves it keeps its value). `in` and `out` are
/// rows x cols and distinct; nothing is allocated. Shared by the dye and the foam (foam.hpp).
void advect_semi_lagrangian(const GridPlacement& grid, std::span<const float> velocity, double dt,
                            std::span<const float> in, std::span<float> out);

class DyeField {
 public:
  /// `bands` alternating bands across y (unit: bands).
  explicit DyeField(const GridPlacement& grid, int bands = 10);
  /// Back to the initial bands.
  void reset();
  /// One step of `dt` seconds with `velocity` (rows x cols x 2, (u, v) per point, m/s).
  void advect(std::span<const float> velocity, double dt);
  /// Dye per point, rows x cols, in [0, 1] (unit: 1).
  std::span<const float> values() const { return c_; }

 private:
  GridPlacement grid_;
  int bands_;
  std::vector<float> c_, next_;
};

}  // namespace huygens
