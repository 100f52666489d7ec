// The scene's checks before the lattice is built (lbm_check: sizes, sides, tau, stability) and the
// stops of a running lattice (a bad cell, a periodic wet/dry seam on several ranks).
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>

#include "huygens/common/finite.hpp"
#include "huygens/lbm/shallow.hpp"
#include "lattice_cell.hpp"

namespace huygens {

using namespace lbm_cell;

namespace {

// Grid size and the scalar parameters: positive, finite.
void check_scalars(const LbmParams& p) {
  if (p.cols < 1 || p.rows < 1 || p.cols > 65536 || p.rows > 65536)
    throw LbmRefused("cols", "grid must have 1..65536 rows and columns");
  if (!(p.cell_m > 0) || !std::isfinite(p.cell_m)) throw LbmRefused("cell_m", "cell size must be > 0");
  if (!(p.dt_s > 0) || !std::isfinite(p.dt_s)) throw LbmRefused("dt_s", "time step must be > 0");
  if (!(p.gravity_mps2 > 0)) throw LbmRefused("gravity_mps2", "gravity must be > 0");
  if (!(p.viscosity_m2s >= 0)) throw LbmRefused("viscosity_m2s", "viscosity must be >= 0");
  if (!(p.min_depth_m > 0)) throw LbmRefused("min_depth_m", "the dry threshold must be > 0");
}

// Every initial field is empty or has one value per cell; the depth is required.
void check_field_sizes(const LbmParams& p, const LbmFields& in) {
  const std::size_t n = static_cast<std::size_t>(p.rows) * static_cast<std::size_t>(p.cols);
  auto size_ok = [&](std::size_t s, const char* name) {
    if (s != 0 && s != n)
      throw LbmRefused(name, "field has " + std::to_string(s) + " values, the grid " + std::to_string(n));
  };
  size_ok(in.bed_m.size(), "bed_m");
  size_ok(in.depth_m.size(), "depth_m");
  size_ok(in.ux_mps.size(), "ux_mps");
  size_ok(in.uy_mps.size(), "uy_mps");
  size_ok(in.solid.size(), "solid");
  if (in.depth_m.empty()) throw LbmRefused("depth_m", "an initial depth field is required");
}

// Sides: periodic in pairs, inflow on the left and outflow on the right only.
void check_sides(const LbmParams& p) {
  const LbmSide sides[4] = {p.left, p.right, p.bottom, p.top};
  if ((p.left == LbmSide::periodic) != (p.right == LbmSide::periodic))
    throw LbmRefused(p.left == LbmSide::periodic ? "right" : "left", "periodic sides come in pairs (left and right)");
  if ((p.bottom == LbmSide::periodic) != (p.top == LbmSide::periodic))
    throw LbmRefused(p.bottom == LbmSide::periodic ? "top" : "bottom", "periodic sides come in pairs (bottom and top)");
  for (int i = 0; i < 4; ++i) {
    if (sides[i] == LbmSide::inflow && i != 0)
      throw LbmRefused(side_name(i), "inflow is supported on the left side only");
    if (sides[i] == LbmSide::outflow && i != 1)
      throw LbmRefused(side_name(i), "outflow is supported on the right side only");
  }
  if (p.outflow_depth_m < 0) throw LbmRefused("outflow_depth_m", "must be >= 0 (0 = zero gradient)");
}

// Extremes of the initial state over the fluid cells (unit: m/s for speeds, m for depth).
struct InitialScan {
  double smax = 0, hmax = 0, frmax = 0;
};

// Negative depths are refused, dry cells (h < min_depth_m) skipped; over the wet cells the signal
// speed, the Froude number and the smallest rest fraction f0/h = 1 - 5 g h / 6 - 2 u.u / 3 (lattice units, paper 002
// eq. 2).
InitialScan scan_initial(const LbmParams& p, const LbmFields& in, LbmLattice& lat) {
  const std::size_t n = static_cast<std::size_t>(p.rows) * static_cast<std::size_t>(p.cols);
  const double dx = p.cell_m, dt = p.dt_s, g = p.gravity_mps2;
  InitialScan s;
  std::size_t fluid = 0, wet = 0;
  lat.min_rest_fraction = 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!in.solid.empty() && in.solid[i]) continue;
    ++fluid;
    const double h = in.depth_m[i];
    const double ux = in.ux_mps.empty() ? 0.0 : in.ux_mps[i];
    const double uy = in.uy_mps.empty() ? 0.0 : in.uy_mps[i];
    if (!std::isfinite(h) || !std::isfinite(ux) || !std::isfinite(uy))
      throw LbmRefused("depth_m", "non-finite initial value at row " + std::to_string(i / p.cols) + ", col " +
                                      std::to_string(i % p.cols));
    if (h < 0)
      throw LbmRefused("depth_m", "cell (row " + std::to_string(i / p.cols) + ", col " + std::to_string(i % p.cols) +
                                      ") has negative depth " + g6(h) + " m");
    if (h < p.min_depth_m && p.bed_force == LbmBedForce::naive && !in.bed_m.empty())
      throw LbmRefused("bed_force", "the naive bed term has no wet/dry form: dry cells need \"centred\"");
    if (h < p.min_depth_m) continue;  // dry: at rest whatever velocity is given
    ++wet;
    const double u = std::hypot(ux, uy);
    s.frmax = std::max(s.frmax, u / std::sqrt(g * h));
    s.smax = std::max(s.smax, u + std::sqrt(g * h));
    s.hmax = std::max(s.hmax, h);
    const double ul = u * dt / dx;
    lat.riemann_ratio = std::max(lat.riemann_ratio, (u + 2.0 * std::sqrt(g * h)) * dt / dx);
    lat.min_rest_fraction = std::min(lat.min_rest_fraction, 1.0 - 5.0 * lat.g_lat_pm * h / 6.0 - 2.0 * ul * ul / 3.0);
  }
  if (fluid == 0) throw LbmRefused("solid", "no fluid cell left");
  if (wet == 0)
    throw LbmRefused("depth_m", "every fluid cell is dry (depth < min_depth_m = " + g6(p.min_depth_m) + " m)");
  return s;
}

// tau = 1/2 + 3 nu dt / dx^2 >= 0.55 (Zhou 2004), else a refusal suggesting nu, dt or dx.
void check_tau(const LbmParams& p, const LbmLattice& lat, double smax) {
  if (lat.tau >= 0.55) return;
  const double dx = p.cell_m, dt = p.dt_s;
  const double nu_min = 0.05 * dx * dx / (3.0 * dt);
  const double dt_min = p.viscosity_m2s > 0 ? 0.05 * dx * dx / (3.0 * p.viscosity_m2s) : INFINITY;
  std::string fix = "raise viscosity_m2s to >= " + g6(nu_min) + " m^2/s";
  if (dt_min * smax / dx < 0.8)
    fix += ", or use dt_s >= " + g6(dt_min) + " s";
  else if (p.viscosity_m2s > 0)
    fix += ", or refine to cell_m <= " + g6(60.0 * p.viscosity_m2s * dt / dx) + " m with dt_s scaled in proportion";
  throw LbmRefused("viscosity_m2s",
                   "BGK relaxation time tau = 1/2 + 3 nu dt/dx^2 = " + g6(lat.tau) + " < 0.55 (unstable): " + fix);
}

// f0 >= 0, (|u| + sqrt(g h)) dt/dx < 0.8, Froude <= kLbmMaxFroude now (unless allowed for a run
// that starts dry) and expected, then tau.
void check_stability(const LbmParams& p, LbmLattice& lat, const InitialScan& s, bool starts_dry) {
  const double dx = p.cell_m, dt = p.dt_s;
  double smax = std::max(s.smax, p.expected_signal_speed_mps);
  if (p.left == LbmSide::inflow) smax = std::max(smax, p.inflow_discharge_m2s / std::max(s.hmax, p.min_depth_m));
  lat.signal_ratio = smax * dt / dx;
  const double dt_ok = 0.5 * dx / smax;  // a comfortable step: half the lattice speed
  if (lat.min_rest_fraction < 0)
    throw LbmRefused("dt_s",
                     "the rest population f0 = h (1 - 5 g h / 6 - 2 u^2 / 3) (lattice units) is negative (g h = " +
                         g6(lat.g_lat_pm * s.hmax) + " > 1.2 at the deepest cell): use dt_s <= " + g6(dt_ok) +
                         " s or cells of at least " + g6(2.0 * smax * dt) + " m");
  if (lat.signal_ratio >= 0.8)
    throw LbmRefused("dt_s", "(|u| + sqrt(g h)) dt/dx = " + g6(lat.signal_ratio) +
                                 " >= 0.8 of the lattice speed (largest signal speed " + g6(smax) +
                                 " m/s): use dt_s <= " + g6(dt_ok) + " s or cell_m >= " + g6(2.0 * smax * dt) + " m");
  const char* why =
      ": transcritical flow is refused (the BGK equilibrium cannot stay positive at "
      "u = sqrt(g h) within the lattice-speed limit)";
  if (s.frmax > kLbmMaxFroude && !(p.allow_supercritical_start && starts_dry))
    throw LbmRefused("depth_m", "the initial flow has Froude number |u|/sqrt(g h) = " + g6(s.frmax) + " > " +
                                    g6(kLbmMaxFroude) + why + "; lower the velocity or deepen the water");
  if (p.expected_froude > kLbmMaxFroude)
    throw LbmRefused("expected_froude", "the flow is expected to reach Froude number " + g6(p.expected_froude) + " > " +
                                            g6(kLbmMaxFroude) + why);
  check_tau(p, lat, smax);
}

}  // namespace

LbmLattice lbm_check(const LbmParams& p, const LbmFields& in) {
  check_scalars(p);
  check_field_sizes(p, in);
  check_sides(p);
  LbmLattice lat;
  const double dx = p.cell_m, dt = p.dt_s, g = p.gravity_mps2;
  lat.speed_mps = dx / dt;
  lat.g_lat_pm = g * dt * dt / (dx * dx);
  lat.tau = 0.5 + 3.0 * p.viscosity_m2s * dt / (dx * dx);
  const InitialScan scan = scan_initial(p, in, lat);
  check_stability(p, lat, scan, lbm_starts_dry(p, in));
  return lat;
}

bool lbm_starts_dry(const LbmParams& p, const LbmFields& in) {
  for (std::size_t i = 0; i < in.depth_m.size(); ++i)
    if ((in.solid.empty() || !in.solid[i]) && in.depth_m[i] < p.min_depth_m) return true;
  return false;
}

// y-periodic sides on several ranks hold one image row; the MUSCL slopes of the wet/dry pass read
// two rows across the periodic seam: refused (every rank at the same step: dry_ and flagged are
// agreed) rather than run with first-order faces at the seam.
void LbmShallow::throw_periodic_wet_dry() const {
  throw LbmRefused("bottom", "step " + std::to_string(steps_) +
                                 ": a cell dried with y-periodic sides on several ranks (the wet/dry pass needs "
                                 "two image rows, one is held): run this scene on one rank");
}

// The first bad cell in row-major order over all ranks: a non-finite depth anywhere stops the run
// as NonFiniteError, else the first negative depth (or below h_min with the naive bed term) as
// LbmDryError naming it; every rank throws the same (the reductions are identities on one rank).
void LbmShallow::throw_bad_cell() const {
  bool nonfinite = false;
  for (const Span& sp : spans_)
    for (std::uint32_t c = sp.begin; c < sp.end; ++c) nonfinite = nonfinite || !std::isfinite(ha_[c]);
  if (ranks_ > 1 ? comm::any(nonfinite) : nonfinite) throw NonFiniteError("stream_collide", steps_);
  constexpr std::int64_t kNoCell = INT64_MAX;
  std::int64_t first = kNoCell;
  double depth = 0.0;
  for (const Span& sp : spans_)
    for (std::uint32_t c = sp.begin; c < sp.end && first == kNoCell; ++c)
      if (ha_[c] < 0.0f || (ha_[c] < hmin_ && p_.bed_force == LbmBedForce::naive && has_bed_)) {
        const std::int64_t col = static_cast<std::int64_t>(c % stride_ - kPad);
        const std::int64_t row = static_cast<std::int64_t>(c / stride_) - halo_ + row0_;
        first = row * p_.cols + col;
        depth = ha_[c];
      }
  if (ranks_ > 1) {
    const std::int64_t owner = comm::min(first);
    depth = comm::sum(first == owner ? depth : 0.0);  // one rank adds its depth, the others 0: exact
    first = owner;
  }
  if (first == kNoCell) return;
  const float h = static_cast<float>(depth);
  throw LbmDryError(steps_, "step " + std::to_string(steps_) + ": cell (row " + std::to_string(first / p_.cols) +
                                ", col " + std::to_string(first % p_.cols) + ") fell to depth " + g6(h) + " m" +
                                (h < 0.0f ? " < 0" : " < min_depth_m with the naive bed term (no wet/dry form)"));
}

}  // namespace huygens
