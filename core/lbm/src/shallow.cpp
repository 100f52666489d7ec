#include "huygens/lbm/shallow.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>
#include <sstream>

#include "huygens/common/finite.hpp"

// A second copy of the all-wet kernel with AVX-512 (span_kernel_wide): GCC, in an AVX2 + FMA build
// without AVX-512 (x86-64-v3), so both copies contract the same products into FMAs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__AVX2__) && defined(__FMA__) && \
    !defined(__AVX512F__)
#define HUYGENS_LBM_WIDE_CLONE 1
#else
#define HUYGENS_LBM_WIDE_CLONE 0
#endif

namespace huygens {

namespace {

constexpr int kEx[9] = {0, 1, 0, -1, 0, 1, -1, -1, 1};
constexpr int kEy[9] = {0, 0, 1, 0, -1, 1, 1, -1, -1};
constexpr int kOpp[9] = {0, 3, 4, 1, 2, 7, 8, 5, 6};
constexpr int kMirrorX[9] = {0, 3, 2, 1, 4, 6, 5, 8, 7};
constexpr int kMirrorY[9] = {0, 1, 4, 3, 2, 8, 7, 6, 5};
constexpr double kLambda[9] = {0, 1, 1, 1, 1, 0.25, 0.25, 0.25, 0.25};

std::string g6(double x) {
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

const char* side_name(int i) {
  static const char* n[4] = {"left", "right", "bottom", "top"};
  return n[i];
}

}  // namespace

std::array<double, 9> lbm_equilibrium(double g, double h, double ux, double uy) {
  std::array<double, 9> f{};
  const double usq = ux * ux + uy * uy;
  for (int a = 1; a < 9; ++a) {
    const double eu = kEx[a] * ux + kEy[a] * uy;
    f[a] = kLambda[a] * h * (g * h / 6.0 + eu / 3.0 + eu * eu / 2.0 - usq / 6.0);
  }
  f[0] = h * (1.0 - 5.0 * g * h / 6.0 - 2.0 * usq / 3.0);
  return f;
}

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

LbmShallow::LbmShallow(const LbmParams& p, const LbmFields& in, LbmDecomposition d) : p_(p), lat_(lbm_check(p, in)) {
  set_slab(d);  // this rank's rows and halo (all rows with one rank)
  const int nx = p.cols;
  const int lattice_rows = rows_ + 2 * halo_ + (image_row_ >= 0 ? 1 : 0);  // one rank: rows + 2 ghost rows
  stride_ = (kPad + static_cast<std::size_t>(nx) + 1 + 15) / 16 * 16;
  plane_ = stride_ * static_cast<std::size_t>(lattice_rows) + 64;  // skew planes against cache-set aliasing
  fa_ = AlignedBuffer<float>(9 * plane_);
  fb_ = AlignedBuffer<float>(9 * plane_);
  ha_ = AlignedBuffer<float>(plane_);
  hb_ = AlignedBuffer<float>(plane_);
  z_ = AlignedBuffer<float>(plane_);
  theta_ = AlignedBuffer<float>(plane_);
  solid_.assign(plane_, 1);
  if (lbm_starts_dry(p, in)) carry_ = AlignedBuffer<float>(plane_);  // zeroed (see the header)

  omega_ = static_cast<float>(1.0 / lat_.tau);
  g_ = static_cast<float>(lat_.g_lat_pm);
  const double acc = p.dt_s * p.dt_s / p.cell_m;  // m/s^2 -> lattice units
  ax_ = static_cast<float>(p.accel_mps2[0] * acc);
  ay_ = static_cast<float>(p.accel_mps2[1] * acc);
  hmin_ = static_cast<float>(p.min_depth_m);
  umax_ = static_cast<float>(std::min(0.7, std::max(lat_.signal_ratio, lat_.riemann_ratio)));
  init_lattice(in);
  build_rules(in);

  const std::uint64_t bytes =
      (fa_.size() + fb_.size() + ha_.size() + hb_.size() + z_.size() + carry_.size()) * sizeof(float);
  st_fill_ = stats_.add("boundary_fill", rules_.size() * sizeof(Rule));
  st_kernel_ = stats_.add("stream_collide", bytes);
  if (ranks_ > 1) {
    std::uint64_t buffers = 0;
    for (int i = 0; i < 3; ++i) buffers += (send_[i].size() + recv_[i].size()) * sizeof(float);
    st_halo_ = stats_.add("halo_exchange", buffers);
    st_reduce_ = stats_.add("reduce", 0);
  }
}

// Bed, fluid flags, initial populations and depth over the lattice rows of this rank (its rows,
// halo rows and image row: every rank starts from the same global fields), the row spans.
void LbmShallow::init_lattice(const LbmFields& in) {
  const int nx = p_.cols, ny = p_.rows;
  // Bed everywhere in the lattice: ghosts take the nearest interior value.
  const auto at = [&](const std::vector<float>& v, int r, int c) {
    return v.empty() ? 0.0f : v[static_cast<std::size_t>(r) * nx + c];
  };
  for_lattice_rows([&](int r) {
    for (int c = -1; c <= nx; ++c) z_[idx(r, c)] = at(in.bed_m, std::clamp(r, 0, ny - 1), std::clamp(c, 0, nx - 1));
  });
  float zlo = at(in.bed_m, 0, 0), zhi = zlo;  // over the whole grid: every rank takes the same kernel
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) {
      zlo = std::min(zlo, at(in.bed_m, r, c));
      zhi = std::max(zhi, at(in.bed_m, r, c));
    }
  has_bed_ = zhi > zlo;

  // Fluid cells and their initial equilibrium populations, shifted by the still-water
  // equilibrium of the mean depth; with a dry cell, unshifted (a dry cell's f_a = 0 is then exact).
  const double vl = p_.dt_s / p_.cell_m;  // m/s -> lattice
  double hsum = 0;
  std::size_t nfluid = 0;
  for (std::size_t i = 0; i < in.depth_m.size(); ++i)
    if (in.solid.empty() || !in.solid[i]) {
      hsum += in.depth_m[i];
      ++nfluid;
      if (in.depth_m[i] < p_.min_depth_m) ++dry_;
    }
  href_ = dry_ ? 0.0f : static_cast<float>(hsum / static_cast<double>(nfluid));
  shift_ = lbm_equilibrium(lat_.g_lat_pm, href_, 0.0, 0.0);
  for (int a = 0; a < 9; ++a) shift_f_[a] = static_cast<float>(shift_[a]);
  for_lattice_rows([&](int r) {
    if (r < 0 || r >= ny) return;
    for (int c = 0; c < nx; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * nx + c;
      if (!in.solid.empty() && in.solid[i]) continue;
      const std::size_t k = idx(r, c);
      solid_[k] = 0;
      const double h = in.depth_m[i];
      auto f = lbm_equilibrium(lat_.g_lat_pm, h, at(in.ux_mps, r, c) * vl, at(in.uy_mps, r, c) * vl);
      if (h < p_.min_depth_m) f = {h, 0, 0, 0, 0, 0, 0, 0, 0};  // dry: all water at rest
      for (int a = 0; a < 9; ++a) fa_[a * plane_ + k] = fb_[a * plane_ + k] = static_cast<float>(f[a] - shift_[a]);
      ha_[k] = hb_[k] = static_cast<float>(h);
    }
  });
  // Row spans of fluid cells: this rank's rows (the kernels), the first halo rows and the image
  // row (their populations are unshifted with the rank's own, halo.cpp).
  auto add_spans = [&](int r, std::vector<Span>& out) {
    int c = 0;
    while (c < nx) {
      while (c < nx && solid_[idx(r, c)]) ++c;
      const int c0 = c;
      while (c < nx && !solid_[idx(r, c)]) ++c;
      if (c > c0)
        out.push_back({static_cast<std::uint32_t>(idx(r, c0)), static_cast<std::uint32_t>(idx(r, c0) + (c - c0))});
    }
  };
  for (int r = row0_; r < row0_ + rows_; ++r) add_spans(r, spans_);
  if (ranks_ > 1)
    for (int r : {row0_ - 1, row0_ + rows_, image_row_})
      if (r >= 0 && r < ny && (r != image_row_ || image_row_ >= 0)) add_spans(r, halo_spans_);
  for (const Span& sp : spans_) ncells_ += sp.end - sp.begin;
  if (ranks_ > 1) {  // the edge rows read the halo, the inner rows do not
    for (int r = row0_; r < row0_ + rows_; ++r)
      add_spans(r, r == row0_ || r == row0_ + rows_ - 1 ? edge_spans_ : inner_spans_);
  }
}

// The ghost rules of this rank's fluid cells; on several ranks also the rules of the cells up to
// two rows beyond its own that set a ghost depth in its lattice (set_ghost_depths replays them in
// one process's order, so every ghost depth a kernel reads is the one one process writes last).
void LbmShallow::build_rules(const LbmFields& in) {
  rules_ = make_rules(row0_, row0_ + rows_, row0_ - halo_, row0_ + rows_ + halo_, in.solid);
  if (ranks_ > 1) {
    const int first = row0_ + 1, last = row0_ + rows_ - 2;  // inner rows
    inner_rules_ = make_rules(first, last + 1, row0_ - halo_, row0_ + rows_ + halo_, in.solid);
    for (const Rule& r : make_rules(row0_, first, row0_ - halo_, row0_ + rows_ + halo_, in.solid))
      edge_rules_.push_back(r);
    for (const Rule& r : make_rules(last + 1, row0_ + rows_, row0_ - halo_, row0_ + rows_ + halo_, in.solid))
      edge_rules_.push_back(r);
  }
  if (ranks_ > 1)
    depth_rules_ = make_rules(std::max(0, row0_ - 2), std::min(p_.rows, row0_ + rows_ + 2), row0_ - halo_,
                              row0_ + rows_ + halo_, in.solid);
}

// The rules of the fluid cells of global rows [r0, r1) whose ghost lies in rows [s0, s1), in one
// process's order (rows, columns, links; copies before inflow/outflow). `solid` is the global
// obstacle mask (empty: none).
std::vector<LbmShallow::Rule> LbmShallow::make_rules(int r0, int r1, int s0, int s1,
                                                     const std::vector<std::uint8_t>& solid) const {
  const int nx = p_.cols, ny = p_.rows;
  const LbmSide sides[4] = {p_.left, p_.right, p_.bottom, p_.top};
  auto inside = [&](int r, int c) { return r >= 0 && r < ny && c >= 0 && c < nx; };
  auto fluid = [&](int r, int c) {
    return inside(r, c) && (solid.empty() || !solid[static_cast<std::size_t>(r) * nx + c]);
  };
  std::vector<Rule> rules;
  for (int r = r0; r < r1; ++r)
    for (int c = 0; c < nx; ++c) {
      if (!fluid(r, c)) continue;
      const std::uint32_t x = static_cast<std::uint32_t>(idx(r, c));
      for (int a = 1; a < 9; ++a) {
        int sr = r - kEy[a], sc = c - kEx[a];
        if (fluid(sr, sc) || sr < s0 || sr >= s1) continue;
        Rule rule{};
        rule.a = static_cast<std::uint8_t>(a);
        rule.x = x;
        rule.s = static_cast<std::uint32_t>(idx(sr, sc));
        rule.dst = static_cast<std::uint32_t>(a * plane_ + rule.s);
        rule.up = kNone;
        rule.kind = 0;
        const std::uint32_t bounce = static_cast<std::uint32_t>(kOpp[a] * plane_ + x);
        rule.src = bounce;
        if (!inside(sr, sc)) {
          // Wrap periodic directions first.
          if ((sc < 0 || sc >= nx) && p_.left == LbmSide::periodic) sc = (sc + nx) % nx;
          if ((sr < 0 || sr >= ny) && p_.bottom == LbmSide::periodic) sr = (sr + ny) % ny;
          const bool xo = sc < 0 || sc >= nx, yo = sr < 0 || sr >= ny;
          if (!xo && !yo) {
            if (fluid(sr, sc)) {
              rule.src = static_cast<std::uint32_t>(a * plane_ + idx(sr, sc));
              rule.up = static_cast<std::uint32_t>(idx(sr, sc));
            }
          } else {
            // A corner ghost belongs to the inflow / outflow side if there is one, else it bounces.
            const int xside = sc < 0 ? 0 : 1;
            const bool open_x = xo && (sides[xside] == LbmSide::inflow || sides[xside] == LbmSide::outflow);
            if (xo && yo && !open_x) {
              rules.push_back(rule);
              continue;
            }
            const int side = xo ? xside : (sr < 0 ? 2 : 3);
            const LbmSide kind = sides[side];
            if (kind == LbmSide::slip) {
              const int mr = xo ? sr : sr + kEy[a], mc = xo ? sc + kEx[a] : sc;
              const int b = xo ? kMirrorX[a] : kMirrorY[a];
              if (fluid(mr, mc)) {
                rule.src = static_cast<std::uint32_t>(b * plane_ + idx(mr, mc));
                rule.up = static_cast<std::uint32_t>(idx(mr, mc));  // the link it really travelled
              }
            } else if (kind == LbmSide::inflow) {
              rule.kind = 1;
              rule.src = x;
            } else if (kind == LbmSide::outflow) {
              if (p_.outflow_depth_m > 0) {
                rule.kind = 2;
                rule.src = x;
              } else {
                const int mc = sc < 0 ? 0 : nx - 1;
                if (fluid(sr, mc)) {
                  rule.src = static_cast<std::uint32_t>(a * plane_ + idx(sr, mc));
                  rule.up = static_cast<std::uint32_t>(idx(sr, mc));
                }
              }
            }
          }
        }
        rules.push_back(rule);
      }
    }
  std::stable_partition(rules.begin(), rules.end(), [](const Rule& r) { return r.kind == 0; });
  return rules;
}

void LbmShallow::set_ghost_depths() {
  // A ghost takes the depth of the cell whose populations it carries (periodic image, mirror,
  // zero-gradient copy) or of the cell it feeds (Zou-He), so the wet/dry rule sees the real face;
  // wall and obstacle ghosts are marked -1 (their value, the bounce-back, passes unchanged).
  float* h = ha_.data();
  for (const Rule& r : ranks_ > 1 ? depth_rules_ : rules_)
    h[r.s] = r.up != kNone ? h[r.up] : r.kind != 0 ? h[r.x] : -1.0f;
}

void LbmShallow::fill_ghosts(bool wet_dry) {
  float* f = fa_.data();
  const float* h = ha_.data();
  const float* z = z_.data();
  const bool comp = has_bed_ && p_.bed_force == LbmBedForce::centred;
  const float hmin = hmin_;
  // the wet/dry pass adds the bed term on wet-wet faces only
  auto wet = [&](std::uint32_t a, std::uint32_t b) { return !wet_dry || (h[a] >= hmin && h[b] >= hmin); };
  const double q = p_.inflow_discharge_m2s * p_.dt_s / p_.cell_m;  // h u_lat (unit: m)
  for (const Rule& r : rules_) {  // copies first, then inflow/outflow (they read the copies)
    float v;
    if (r.kind == 0) {
      v = f[r.src];
    } else {
      // Zou-He for shallow water: the unknown populations of x are set from the ones x pulls
      // this step so that h u_x = q (inflow) or h = h_out (outflow) and h u_y is unchanged.
      // On shifted populations the formulas are the same (opposite links share their shift).
      const std::ptrdiff_t S = static_cast<std::ptrdiff_t>(stride_);
      auto pulled = [&](int b) { return static_cast<double>(f[b * plane_ + r.x - (kEy[b] * S + kEx[b])]); };
      const double ns = 0.5 * (pulled(4) - pulled(2));  // (f_S - f_N) / 2
      double m;
      if (r.kind == 1) {
        m = q;
        v = static_cast<float>(r.a == 1   ? pulled(3) + 2.0 * m / 3.0
                               : r.a == 5 ? pulled(7) + m / 6.0 + ns
                                          : pulled(6) + m / 6.0 - ns);
      } else {
        const double known = pulled(0) + pulled(2) + pulled(4) + 2.0 * (pulled(1) + pulled(5) + pulled(8));
        m = known + href_ - p_.outflow_depth_m;  // h u = K - h_out
        v = static_cast<float>(r.a == 3   ? pulled(1) - 2.0 * m / 3.0
                               : r.a == 6 ? pulled(8) - m / 6.0 + ns
                                          : pulled(5) - m / 6.0 - ns);
      }
    }
    if (comp) {
      const float k = static_cast<float>(kLambda[r.a]) * g_ * (1.0f / 6.0f);
      if (wet(r.x, r.s)) v -= -k * (h[r.x] + h[r.s]) * (z[r.x] - z[r.s]);  // the kernel adds this back
      if (r.up != kNone && wet(r.x, r.up)) v += -k * (h[r.x] + h[r.up]) * (z[r.x] - z[r.up]);
    }
    f[r.dst] = v;
  }
}

namespace {

// The nine populations of one cell (shifted by the still-water equilibrium, unit: m).
struct Cell9 {
  float f0, f1, f2, f3, f4, f5, f6, f7, f8;
};

// Centred bed term added to the pulled populations, k1 = g/6, k5 = g/24 (lattice units):
//   S_a = -lambda_a g (h(x) + h(x - e_a)) (z(x) - z(x - e_a)) / 6
[[gnu::always_inline]] inline void add_centred_bed(Cell9& f, const float* __restrict h, const float* __restrict z,
                                                   std::ptrdiff_t c, std::ptrdiff_t S, float k1, float k5) {
  const float hc = h[c], zc = z[c];
  f.f1 -= k1 * (hc + h[c - 1]) * (zc - z[c - 1]);
  f.f2 -= k1 * (hc + h[c - S]) * (zc - z[c - S]);
  f.f3 -= k1 * (hc + h[c + 1]) * (zc - z[c + 1]);
  f.f4 -= k1 * (hc + h[c + S]) * (zc - z[c + S]);
  f.f5 -= k5 * (hc + h[c - S - 1]) * (zc - z[c - S - 1]);
  f.f6 -= k5 * (hc + h[c - S + 1]) * (zc - z[c - S + 1]);
  f.f7 -= k5 * (hc + h[c + S + 1]) * (zc - z[c + S + 1]);
  f.f8 -= k5 * (hc + h[c + S - 1]) * (zc - z[c + S - 1]);
}

// Naive bed term: F = -g h(x) grad z_b (central difference at x); S_a = lambda_a e_a.F / 3.
[[gnu::always_inline]] inline void add_naive_bed(Cell9& f, const float* __restrict h, const float* __restrict z,
                                                 std::ptrdiff_t c, std::ptrdiff_t S, float g) {
  const float gh = -0.5f * g * h[c];
  const float fx = gh * (z[c + 1] - z[c - 1]), fy = gh * (z[c + S] - z[c - S]);
  f.f1 += fx * (1.0f / 3.0f);
  f.f3 -= fx * (1.0f / 3.0f);
  f.f2 += fy * (1.0f / 3.0f);
  f.f4 -= fy * (1.0f / 3.0f);
  f.f5 += (fx + fy) * (1.0f / 12.0f);
  f.f7 -= (fx + fy) * (1.0f / 12.0f);
  f.f6 += (fy - fx) * (1.0f / 12.0f);
  f.f8 -= (fy - fx) * (1.0f / 12.0f);
}

// Constants of the collision: omega = 1/tau, g_lat (1/m), the force a dt^2/dx, H and h_min (m).
struct Collision {
  float w, g, ax, ay, hmin, href, umax2 = 0.0f;
};

// BGK collision (paper 002 eq. 1) of a cell's pulled populations f: moments (eq. 3-4) and the
// equilibrium (eq. 2), both minus the shift, plus the force lambda_a h (e_a . a) / 3 (Force; with
// a = 0 the force adds exact zeros: the force-free form gives the same floats, up to the sign of a
// zero). Writes the new depth h; `bad` counts h < h_min (also NaN).
template <bool Cap = false, bool Force = true>
[[gnu::always_inline]] inline Cell9 collide(const Cell9& f, const Collision& k, float& h, float& bad) {
  const float f0 = f.f0, f1 = f.f1, f2 = f.f2, f3 = f.f3, f4 = f.f4, f5 = f.f5, f6 = f.f6, f7 = f.f7, f8 = f.f8;
  // moments of the shifted populations: dh = h - H exactly as precise as the wave
  const float dh = ((f0 + f1) + (f2 + f3)) + ((f4 + f5) + (f6 + f7)) + f8;
  h = k.href + dh;
  const float mx = (f1 + f5 + f8) - (f3 + f6 + f7);
  const float my = (f2 + f5 + f6) - (f4 + f7 + f8);
  const float ih = h > k.hmin ? 1.0f / h : 0.0f;
  bad += h >= k.hmin ? 0.0f : 1.0f;
  float ux = mx * ih, uy = my * ih;
  float w = k.w;
  if constexpr (Cap) {  // |u| <= u_max (wet/dry pass: the thin layer at a front)
    const float u2 = ux * ux + uy * uy;
    const float r = u2 > k.umax2 ? std::sqrt(k.umax2 / u2) : 1.0f;
    ux *= r;
    uy *= r;
    w = r < 1.0f ? 1.0f : w;
  }
  // equilibrium minus the shift: axis base g (h^2 - H^2)/6 - h u.u/6;
  // rest = dh - sum of the others (so the shifted equilibria sum to dh: mass exact)
  const float usq = ux * ux + uy * uy;
  const float base = (k.g * dh * (h + k.href) - h * usq) * (1.0f / 6.0f);
  const float hh = 0.5f * h, h3 = h * (1.0f / 3.0f);
  const float q1 = base + hh * ux * ux, q2 = base + hh * uy * uy;
  const float e1 = q1 + h3 * ux, e3 = q1 - h3 * ux;
  const float e2 = q2 + h3 * uy, e4 = q2 - h3 * uy;
  const float s5 = ux + uy, s6 = uy - ux;
  const float q5 = 0.25f * (base + hh * s5 * s5), q6 = 0.25f * (base + hh * s6 * s6);
  const float e5 = q5 + 0.25f * h3 * s5, e7 = q5 - 0.25f * h3 * s5;
  const float e6 = q6 + 0.25f * h3 * s6, e8 = q6 - 0.25f * h3 * s6;
  const float e0 = dh - (((e1 + e2) + (e3 + e4)) + ((e5 + e6) + (e7 + e8)));
  if constexpr (!Force)
    return {f0 + w * (e0 - f0), f1 + w * (e1 - f1), f2 + w * (e2 - f2), f3 + w * (e3 - f3), f4 + w * (e4 - f4),
            f5 + w * (e5 - f5), f6 + w * (e6 - f6), f7 + w * (e7 - f7), f8 + w * (e8 - f8)};
  const float gx = h3 * k.ax, gy = h3 * k.ay;
  const float g5 = 0.25f * (gx + gy), g6 = 0.25f * (gy - gx);
  return {f0 + w * (e0 - f0),      f1 + w * (e1 - f1) + gx, f2 + w * (e2 - f2) + gy,
          f3 + w * (e3 - f3) - gx, f4 + w * (e4 - f4) - gy, f5 + w * (e5 - f5) + g5,
          f6 + w * (e6 - f6) + g6, f7 + w * (e7 - f7) - g5, f8 + w * (e8 - f8) - g6};
}

// The face between c and n = c - e_a in the wet/dry pass (see the header comment): p1 = f*_a(n)
// pulled, p2 = f*_abar(c) its own (shifted values). Returns what c receives unlimited (p1 plus the
// centred bed term on a wet-wet face, k = lambda_a g / 6; p2 on a closed face; on an open wet-dry
// face the wet cell's mirror mc, the dry cell the rest p1 + p2 - mn) and sets the net flux into c,
// F = v - p2. n computes the same face from the same floats with the roles of p1 and p2 swapped and
// the bed term negated, so the face exchanges water and makes none. A ghost neighbour streams
// (its image decides the same way); a wall ghost (hn < 0) passes its bounce-back.
[[gnu::always_inline]] inline float wet_dry_face(float p1, float p2, float hc, float zc, float hn, float zn, float k,
                                                 float hmin, bool ghost, float mc, float mn, float& flux,
                                                 double& exact) {
  const bool wc = hc >= hmin, wn = hn >= hmin;
  const bool closed = (wc != wn) & (wc ? hc + zc <= zn + hmin : hn + zn <= zc + hmin);
  const float bed = (wc & wn) ? -k * (hc + hn) * (zc - zn) : 0.0f;
  const bool stream = (wc == wn) | ghost;
  const float open = stream ? p1 + bed : wc ? mc : p1 + p2 - mn;
  const float v = ghost & (hn < 0.0f) ? p1 : closed ? p2 : open;  // hn < 0: a wall ghost
  // the same value before rounding: n's share is then exactly p1 + p2 minus it (mass accounting)
  const double dopen = stream ? double(p1) + bed : wc ? double(mc) : double(p1) + p2 - mn;
  exact = ghost & (hn < 0.0f) ? double(p1) : closed ? double(p2) : dopen;
  flux = v - p2;
  return v;
}

// What a wet cell (depth h, lattice velocity u) receives on link a from a dry neighbour: its own
// equilibrium population of that link without the pressure part lambda_a g h^2 / 6, i.e. an empty
// neighbour moving with it (shifted by ks). The dry cell receives the rest of the pair.
[[gnu::always_inline]] inline float dry_mirror(int a, float h, float ux, float uy, float ks) {
  const float eu = static_cast<float>(kEx[a]) * ux + static_cast<float>(kEy[a]) * uy;
  return static_cast<float>(kLambda[a]) * h *
             (eu * (1.0f / 3.0f) + 0.5f * eu * eu - (ux * ux + uy * uy) * (1.0f / 6.0f)) -
         ks;
}

// Lattice velocity of cell c from its post-collision populations (shifted: the shifts carry no
// momentum), 0 when dry.
[[gnu::always_inline]] inline void cell_velocity(const float* src, std::ptrdiff_t P, std::ptrdiff_t c, float h,
                                                 float hmin, float& ux, float& uy) {
  const float f1 = src[P + c], f2 = src[2 * P + c], f3 = src[3 * P + c], f4 = src[4 * P + c];
  const float f5 = src[5 * P + c], f6 = src[6 * P + c], f7 = src[7 * P + c], f8 = src[8 * P + c];
  const float ih = h >= hmin ? 1.0f / h : 0.0f;
  ux = ((f1 + f5 + f8) - (f3 + f6 + f7)) * ih;
  uy = ((f2 + f5 + f6) - (f4 + f7 + f8)) * ih;
}

// A dry cell (h < h_min) puts all its water at rest: f*_a = 0 (stored -ks_a) and the rest population
// gains what arrived on the moving links, f*_0 = f_0 + sum (f_a + ks_a): a dry cell nothing reached
// keeps its populations bit for bit (recomputing f*_0 from h would add a rounding every step).
[[gnu::always_inline]] inline Cell9 rest_if_dry(const Cell9& f, const Cell9& o, float h, float hmin, const Cell9& ks) {
  const bool dry = h < hmin;
  const float r0 = f.f0 + ((((f.f1 + ks.f1) + (f.f2 + ks.f2)) + ((f.f3 + ks.f3) + (f.f4 + ks.f4))) +
                           (((f.f5 + ks.f5) + (f.f6 + ks.f6)) + ((f.f7 + ks.f7) + (f.f8 + ks.f8))));
  return {dry ? r0 : o.f0,     dry ? -ks.f1 : o.f1, dry ? -ks.f2 : o.f2, dry ? -ks.f3 : o.f3, dry ? -ks.f4 : o.f4,
          dry ? -ks.f5 : o.f5, dry ? -ks.f6 : o.f6, dry ? -ks.f7 : o.f7, dry ? -ks.f8 : o.f8};
}

// Froude number above which a wet cell's faces take the HLL flux in the wet/dry pass: a D2Q9
// lattice relaxes to the equilibrium through the speeds -1, 0, +1, and the relaxation is
// dissipative only while the wave speeds u - c and u + c interlace with them (Liu's
// subcharacteristic condition: u - c <= 0 <= u + c), i.e. only subcritical flow. At u = c the
// BGK lattice holds an entropy-violating expansion jump, beyond it (a dry-bed dam break from the
// dam to the front) it is anti-diffusive (docs/lbm.md).
constexpr float kFvFroude = 0.8f;

// A cell's state as the HLL link flux sees it: depth, surface h + z_b (m), lattice velocity.
struct LinkState {
  float h, eta, ux, uy;
};

// The LBM equilibrium fluxes of link pair a (a, abar) of a uniform state: mass m = f_a - f_abar =
// (2/3) lambda_a h (e_a.u) along e_a and momentum pi = f_a + f_abar = 2 lambda_a h (g h/6 +
// (e_a.u)^2/2 - u.u/6) (lattice units), what streaming a uniform equilibrium exchanges.
[[gnu::always_inline]] inline void link_flux(int a, const LinkState& s, float g, float& m, float& pi) {
  const float eu = static_cast<float>(kEx[a]) * s.ux + static_cast<float>(kEy[a]) * s.uy;
  const float lam = static_cast<float>(kLambda[a]);
  m = lam * (2.0f / 3.0f) * s.h * eu;
  pi = 2.0f * lam * s.h * (g * s.h * (1.0f / 6.0f) + 0.5f * eu * eu - (s.ux * s.ux + s.uy * s.uy) * (1.0f / 6.0f));
}

// HLL flux (Harten, Lax and van Leer 1983; the wave speeds of Davis 1988, min / max of u -+ c over
// both sides; the dry-bed speeds u +- 2c of Toro 2001) of link pair a from L = x - e_a to R = x, in the link's own 1D
// problem: speeds in link lengths per step, (e_a.u)/|e_a|^2 +- c/|e_a|, conserved link variables kappa_a (eta, e_a.J)
// with kappa_a = (2/3) lambda_a |e_a|^2, so a uniform state gets exactly the LBM exchange (link_flux) and a 1D flow the
// physical flux split 2/3, 1/6, 1/6 over the three links that cross a face. The mass dissipation acts on the surface
// eta (still water over a bed exchanges nothing). Returns the mass into R and the momentum flux along e_a. Not inlined:
// both cells of a face call it with the same arguments, so they get the same floats (mass is exchanged).
[[gnu::noinline]] void hll_link(int a, LinkState L, LinkState R, float g, float hmin, float& m, float& pi) {
  const bool diag = a >= 5;
  const float e2 = diag ? 2.0f : 1.0f, ie = diag ? 0.70710678f : 1.0f, kap = diag ? 1.0f / 3.0f : 2.0f / 3.0f;
  const float ex = static_cast<float>(kEx[a]), ey = static_cast<float>(kEy[a]);
  const float sl = (ex * L.ux + ey * L.uy) / e2, sr = (ex * R.ux + ey * R.uy) / e2;
  const float cl = std::sqrt(g * L.h) * ie, cr = std::sqrt(g * R.h) * ie;
  float lo = std::min(sl - cl, sr - cr), hi = std::max(sl + cl, sr + cr);
  if (R.h < hmin) lo = sl - cl, hi = sl + 2.0f * cl;
  if (L.h < hmin) lo = sr - 2.0f * cr, hi = sr + cr;
  float ml, pl, mr, pr;
  link_flux(a, L, g, ml, pl);
  link_flux(a, R, g, mr, pr);
  if (lo >= 0.0f) {
    m = ml, pi = pl;
  } else if (hi <= 0.0f) {
    m = mr, pi = pr;
  } else {
    const float d = 1.0f / (hi - lo), ss = lo * hi * kap;
    const float ql = L.h * (ex * L.ux + ey * L.uy), qr = R.h * (ex * R.ux + ey * R.uy);
    m = (hi * ml - lo * mr + ss * (R.eta - L.eta)) * d;
    pi = (hi * pl - lo * pr + ss * (qr - ql)) * d;
  }
}

// minmod slope limiter (Roe 1986): the smaller one-sided difference, 0 at an extremum.
[[gnu::always_inline]] inline float minmod(float l, float r) {
  return l * r <= 0.0f ? 0.0f : std::abs(l) < std::abs(r) ? l : r;
}

// The face value of cell s on its +e_a side (side = +1) or -e_a side (-1), second order in space
// and time (MUSCL-Hancock, van Leer 1979; Toro 2001 sec. 14.4): minmod slopes of surface and
// velocity from the neighbours behind (prev, at -e_a) and ahead (next), then half a step of the
// link's own 1D equations, d(kappa h)/dt = -dm/ds, d(kappa e_a.J)/dt = -dpi/ds. The depth follows
// the surface (still water stays still); a dry or missing neighbour gives first order.
LinkState reconstruct(int a, const LinkState& s, const LinkState* prev, const LinkState* next, float side, float g,
                      float hmin) {
  if (prev == nullptr || next == nullptr || prev->h < hmin || next->h < hmin) return s;
  const float de = 0.5f * minmod(s.eta - prev->eta, next->eta - s.eta);
  const float dx = 0.5f * minmod(s.ux - prev->ux, next->ux - s.ux);
  const float dy = 0.5f * minmod(s.uy - prev->uy, next->uy - s.uy);
  LinkState p{std::max(0.0f, s.h + de), s.eta + de, s.ux + dx, s.uy + dy};
  LinkState q{std::max(0.0f, s.h - de), s.eta - de, s.ux - dx, s.uy - dy};
  float mp, pp, mq, pq;
  link_flux(a, p, g, mp, pp);
  link_flux(a, q, g, mq, pq);
  const bool diag = a >= 5;
  const float ik = diag ? 3.0f : 1.5f, ie2 = diag ? 0.5f : 1.0f;  // 1 / kappa_a, 1 / |e_a|^2
  LinkState o = side > 0.0f ? p : q;
  const float ex = static_cast<float>(kEx[a]), ey = static_cast<float>(kEy[a]);
  const float q0 = o.h * (ex * o.ux + ey * o.uy);
  const float h1 = o.h - 0.5f * ik * (mp - mq), q1 = q0 - 0.5f * ik * (pp - pq);
  if (!(h1 > hmin)) return o;
  const float du = (q1 / h1 - q0 / std::max(o.h, hmin)) * ie2;  // change of e_a.u, along e_a
  return {h1, o.eta + (h1 - o.h), o.ux + du * ex, o.uy + du * ey};
}

// Second-order (MUSCL-Hancock) HLL flux of link a between L and R, with LL behind L and RR
// ahead of R (nullptr: none); first order on a face with a dry side. Not inlined (see hll_link).
[[gnu::noinline]] void muscl_link(int a, const LinkState* LL, LinkState L, LinkState R, const LinkState* RR, float g,
                                  float hmin, float& m, float& pi) {
  if (L.h >= hmin && R.h >= hmin) {
    const LinkState l = reconstruct(a, L, LL, &R, 1.0f, g, hmin), r = reconstruct(a, R, &L, RR, -1.0f, g, hmin);
    L = l;
    R = r;
  }
  hll_link(a, L, R, g, hmin, m, pi);
}

// The limiter plane packs a cell's theta (0..1) and its flag (Froude above kFvFroude) as theta + 2.
[[gnu::always_inline]] inline bool fv_flag(float packed) { return packed >= 2.0f; }
[[gnu::always_inline]] inline float fv_theta(float packed) { return packed >= 2.0f ? packed - 2.0f : packed; }

// One face of the wet/dry pass as cell c sees it on link a: what c receives unlimited (v, LBM
// faces), c's own outgoing population p2, the net mass into c (flux) and, on an HLL face, the
// momentum flux along e_a including c's bed term (pi); img is the real cell behind the face.
struct WdFace {
  float v, p2, flux, pi;
  double vx;  // v before rounding (LBM faces)
  std::ptrdiff_t img;
  bool fv;
};

// Pointers and constants of the fused pass (stream_collide).
struct KernelArgs {
  const float* src;     // populations of this step (9 planes)
  float* dst;           // post-collision populations (9 planes)
  const float* hold;    // depth of this step
  float* hnew;          // new depth
  const float* z;       // bed
  std::ptrdiff_t S, P;  // row stride and plane size (floats)
  Collision k;
  float k1, k5;  // centred bed term constants g/6, g/24
};

// One fluid row span [b, e) of the fused pull stream-collide pass (pull, bed term, collide, store).
// Mode 0: flat bed; 1: well-balanced centred bed term; 2: naive bed term. Force: a nonzero
// external acceleration (without it the force terms are left out of the collision). Returns the
// number of cells below h_min (also NaN).
template <int Mode, bool Force>
[[gnu::always_inline]] inline float span_body(const KernelArgs& a, std::ptrdiff_t b, std::ptrdiff_t e) {
  const std::ptrdiff_t S = a.S, P = a.P;
  const float* __restrict hold = a.hold;
  float* __restrict hnew = a.hnew;
  const float* __restrict z = a.z;
  // f_a(x) pulls f*_a(x - e_a): pa[c] = plane a at c - (ey S + ex).
  const float* __restrict p0 = a.src;
  const float* __restrict p1 = a.src + 1 * P - 1;
  const float* __restrict p2 = a.src + 2 * P - S;
  const float* __restrict p3 = a.src + 3 * P + 1;
  const float* __restrict p4 = a.src + 4 * P + S;
  const float* __restrict p5 = a.src + 5 * P - S - 1;
  const float* __restrict p6 = a.src + 6 * P - S + 1;
  const float* __restrict p7 = a.src + 7 * P + S + 1;
  const float* __restrict p8 = a.src + 8 * P + S - 1;
  float* __restrict d0 = a.dst;
  float* __restrict d1 = a.dst + 1 * P;
  float* __restrict d2 = a.dst + 2 * P;
  float* __restrict d3 = a.dst + 3 * P;
  float* __restrict d4 = a.dst + 4 * P;
  float* __restrict d5 = a.dst + 5 * P;
  float* __restrict d6 = a.dst + 6 * P;
  float* __restrict d7 = a.dst + 7 * P;
  float* __restrict d8 = a.dst + 8 * P;
  float bad = 0.0f;
#pragma omp simd reduction(+ : bad)
  for (std::ptrdiff_t c = b; c < e; ++c) {
    Cell9 f{p0[c], p1[c], p2[c], p3[c], p4[c], p5[c], p6[c], p7[c], p8[c]};
    if constexpr (Mode == 1) add_centred_bed(f, hold, z, c, S, a.k1, a.k5);
    if constexpr (Mode == 2) add_naive_bed(f, hold, z, c, S, a.k.g);
    float h;
    const Cell9 o = collide<false, Force>(f, a.k, h, bad);
    d0[c] = o.f0;
    d1[c] = o.f1;
    d2[c] = o.f2;
    d3[c] = o.f3;
    d4[c] = o.f4;
    d5[c] = o.f5;
    d6[c] = o.f6;
    d7[c] = o.f7;
    d8[c] = o.f8;
    hnew[c] = h;
  }
  return bad;
}

// The span loop compiled for the build's instruction set ...
template <int Mode, bool Force>
float span_kernel(const KernelArgs& a, std::ptrdiff_t b, std::ptrdiff_t e) {
  return span_body<Mode, Force>(a, b, e);
}

#if HUYGENS_LBM_WIDE_CLONE
// ... and once more for x86-64-v4 (AVX-512: 16 floats a vector, 32 vector registers) when the build
// is below it: the same operations lane by lane (the results are bitwise the same), half the
// vector instructions and no register spills, which the bed kernel needs to keep up with the
// memory (docs/lbm.md, "Speed"). Chosen at run time by lbm_kernel_isa().
template <int Mode, bool Force>
[[gnu::target("avx512f,avx512bw,avx512dq,avx512vl,avx512cd,prefer-vector-width=512")]] float span_kernel_wide(
    const KernelArgs& a, std::ptrdiff_t b, std::ptrdiff_t e) {
  return span_body<Mode, Force>(a, b, e);
}
#endif

bool wide_kernel_allowed = true;  // lbm_allow_wide_kernel

bool cpu_has_wide_kernel() {
#if HUYGENS_LBM_WIDE_CLONE
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512cd");
#else
  return false;
#endif
}

bool use_wide_kernel() {
  static const bool has = cpu_has_wide_kernel();
  return has && wide_kernel_allowed;
}

}  // namespace

const char* lbm_kernel_isa() { return use_wide_kernel() ? "x86-64-v4 copy (AVX-512, chosen at run time)" : "build's"; }

void lbm_allow_wide_kernel(bool allowed) { wide_kernel_allowed = allowed; }

// The fused pull stream-collide pass over the fluid row spans, OpenMP over spans.
template <int Mode, bool Force>
void LbmShallow::stream_collide(int& flagged) {
  const KernelArgs a{fa_.data(),
                     fb_.data(),
                     ha_.data(),
                     hb_.data(),
                     z_.data(),
                     static_cast<std::ptrdiff_t>(stride_),
                     static_cast<std::ptrdiff_t>(plane_),
                     Collision{omega_, g_, ax_, ay_, hmin_, href_},
                     g_ / 6.0f,
                     g_ / 24.0f};
  float (*span)(const KernelArgs&, std::ptrdiff_t, std::ptrdiff_t) = span_kernel<Mode, Force>;
#if HUYGENS_LBM_WIDE_CLONE
  if (use_wide_kernel()) span = span_kernel_wide<Mode, Force>;
#endif
  const Span* spans = spans_.data();
  const int nspans = static_cast<int>(spans_.size());
  int total = 0;
  const bool par = ncells_ >= 16384;  // small lattices: a thread team costs more than it saves
#pragma omp parallel for schedule(static) reduction(+ : total) if (par)
  for (int s = 0; s < nspans; ++s) total += static_cast<int>(span(a, spans[s].begin, spans[s].end));
  flagged = total;
}

// Pointers and constants of the wet/dry pass; face() evaluates one face the same way for the
// limiter and the update, so both cells of a face and both passes agree.
struct LbmShallow::WetDryView {
  const float* src;
  const float* h;
  const float* z;
  const float* flags;  // >= 2: the cell's faces take the HLL flux
  const std::uint8_t* solid;
  const float* shift;
  std::ptrdiff_t P, S, pad;
  std::ptrdiff_t off[9];
  float kb[9];
  float g, hmin;
  int nx, ny;
  bool px, py;
  std::ptrdiff_t first_row, image_slot;  // global row of lattice row 0; lattice row of the image row

  // The real cell behind n: n if fluid, the periodic image of a ghost, else -1 (walls, obstacles,
  // mirror and open sides keep their ghost rules).
  std::ptrdiff_t image(std::ptrdiff_t n) const {
    if (!solid[n]) return n;
    if (h[n] < 0.0f || !(px || py)) return -1;
    std::ptrdiff_t row = row_of(n), col = n % S - pad;
    if (px) col = (col + nx) % nx;
    if (py) row = (row + ny) % ny;
    if (row < 0 || row >= ny || col < 0 || col >= nx) return -1;
    const std::ptrdiff_t m = at(row, col);
    return solid[m] ? -1 : m;
  }
  // The real cell k links along e_a from the fluid cell at (r0, c0) (periodic sides wrap), else -1.
  std::ptrdiff_t along(std::ptrdiff_t r0, std::ptrdiff_t c0, int a, int k) const {
    std::ptrdiff_t row = r0 + k * kEy[a], col = c0 + k * kEx[a];
    if (px) col = (col % nx + nx) % nx;
    if (py) row = (row % ny + ny) % ny;
    if (row < 0 || row >= ny || col < 0 || col >= nx) return -1;
    const std::ptrdiff_t m = at(row, col);
    return solid[m] ? -1 : m;
  }
  // Global row of lattice index n (not the image row) and the lattice index of (global row, col):
  // lattice row 0 is global row first_row (row0 - halo); a row beyond the halo is the image row.
  std::ptrdiff_t row_of(std::ptrdiff_t n) const { return n / S + first_row; }
  std::ptrdiff_t at(std::ptrdiff_t row, std::ptrdiff_t col) const {
    std::ptrdiff_t lr = row - first_row;
    if (lr < 0 || lr >= image_slot) lr = image_slot;
    return lr * S + pad + col;
  }
  LinkState state(std::ptrdiff_t x) const {
    float ux, uy;
    cell_velocity(src, P, x, h[x], hmin, ux, uy);
    return {h[x], h[x] + z[x], ux, uy};
  }
  float mirror(int a, std::ptrdiff_t w) const {  // only used when w is wet and its neighbour dry
    float ux, uy;
    cell_velocity(src, P, w, h[w], hmin, ux, uy);
    return dry_mirror(a, h[w], ux, uy, shift[a]);
  }
  // The faces of cell c (row, col known), a = 1..8: HLL on an open face with a dry side or a
  // flagged cell (canonical orientation: links 1, 2, 5, 6 from the neighbour, so both cells call
  // muscl_link with the same arguments), no exchange between dry cells, else the LBM rules. Each
  // neighbour's state is computed once.
  void faces(std::ptrdiff_t c, std::ptrdiff_t row, std::ptrdiff_t col, WdFace* out) const {
    std::ptrdiff_t img[9];
    for (int a = 1; a < 9; ++a) img[a] = image(c - off[a]);
    StateCache st{this, c, img, {}, {}};
    for (int a = 1; a < 9; ++a) out[a] = face(c, a, row, col, img, st);
  }
  // States of cell c (slot 0) and of its neighbours' real cells, computed when a face needs them.
  struct StateCache {
    const WetDryView* v;
    std::ptrdiff_t c;
    const std::ptrdiff_t* img;
    LinkState s[9];
    bool have[9] = {};
    const LinkState& get(int a) {
      if (!have[a]) s[a] = v->state(a == 0 ? c : img[a]), have[a] = true;
      return s[a];
    }
  };
  WdFace face(std::ptrdiff_t c, int a, std::ptrdiff_t row, std::ptrdiff_t col, const std::ptrdiff_t* img,
              StateCache& st) const {
    const std::ptrdiff_t n = c - off[a];
    const int b = kOpp[a];
    WdFace f{0.0f, src[b * P + c], 0.0f, 0.0f, 0.0, img[a], false};
    const float hc = h[c], zc = z[c], hn = h[n], zn = z[n];
    const bool wc = hc >= hmin, wn = hn >= hmin;
    if (f.img >= 0 && !wc && !wn) {  // dry land: no exchange (a film below h_min stays put)
      f.fv = true;
      return f;
    }
    if (f.img >= 0) {
      const float zi = z[f.img];
      const bool closed = (wc != wn) && (wc ? hc + zc <= zi + hmin : hn + zi <= zc + hmin);
      if (!closed && (wc != wn || fv_flag(flags[c]) || fv_flag(flags[f.img]))) {
        const std::ptrdiff_t behind = wc && wn ? along(row, col, a, -2) : -1;
        const LinkState sc = st.get(0), sn = st.get(a);
        const LinkState sb = behind >= 0 ? state(behind) : sc;
        const LinkState sa = img[b] >= 0 ? st.get(b) : sc;  // the cell ahead, c + e_a
        const LinkState* pa = img[b] >= 0 ? &sa : nullptr;
        const LinkState* pb = behind >= 0 ? &sb : nullptr;
        float m;
        if (a == 1 || a == 2 || a == 5 || a == 6) {
          muscl_link(a, pb, sn, sc, pa, g, hmin, m, f.pi);
          f.flux = m;
        } else {
          muscl_link(b, pa, sc, sn, pb, g, hmin, m, f.pi);
          f.flux = -m;
        }
        if (wc && wn) f.pi += -kb[a] * (hc + hn) * (zc - zi);
        f.fv = true;
        return f;
      }
    }
    const bool mixed = !solid[n] && wc != wn;
    f.v = wet_dry_face(src[a * P + n], f.p2, hc, zc, hn, zn, kb[a], hmin, solid[n] != 0, mixed ? mirror(a, c) : 0.0f,
                       mixed ? mirror(b, n) : 0.0f, f.flux, f.vx);
    return f;
  }
};

LbmShallow::WetDryView LbmShallow::wet_dry_view(const float* flags) const {
  const std::ptrdiff_t S = static_cast<std::ptrdiff_t>(stride_);
  WetDryView w{fa_.data(),
               ha_.data(),
               z_.data(),
               flags,
               solid_.data(),
               shift_f_.data(),
               static_cast<std::ptrdiff_t>(plane_),
               S,
               static_cast<std::ptrdiff_t>(kPad),
               {0, 1, S, -1, -S, S + 1, S - 1, -S - 1, -S + 1},
               {},
               g_,
               hmin_,
               p_.cols,
               p_.rows,
               p_.left == LbmSide::periodic,
               p_.bottom == LbmSide::periodic,
               row0_ - halo_,
               rows_ + 2 * halo_};
  for (int a = 1; a < 9; ++a) w.kb[a] = a < 5 ? g_ / 6 : g_ / 24;
  return w;
}

// Flags (into the next-depth plane, free until the update writes it) the wet cells whose Froude
// number exceeds kFvFroude: their faces take the HLL flux.
void LbmShallow::flag_supercritical() {
  const std::ptrdiff_t P = static_cast<std::ptrdiff_t>(plane_);
  const float* src = fa_.data();
  const float* hold = ha_.data();
  float* flags = hb_.data();
  const float hmin = hmin_, f2 = kFvFroude * kFvFroude * g_;
  auto flag = [&](std::ptrdiff_t c) {
    float ux, uy;
    cell_velocity(src, P, c, hold[c], hmin, ux, uy);
    flags[c] = hold[c] >= hmin && ux * ux + uy * uy > f2 * hold[c] ? 2.0f : 0.0f;
  };
  const Span* spans = spans_.data();
  const int nspans = static_cast<int>(spans_.size());
#pragma omp parallel for schedule(static) if (ncells_ >= 16384)
  for (int s = 0; s < nspans; ++s)
    for (std::ptrdiff_t c = spans[s].begin; c < spans[s].end; ++c) flag(c);
  // several ranks: the first halo rows and the image row too (their faces with this rank's cells)
  for (const Span& sp : halo_spans_)
    for (std::ptrdiff_t c = sp.begin; c < sp.end; ++c) flag(c);
}

// Net outflow limiter of the wet/dry pass: theta_c = min(1, h_c / O_c), O_c the sum of c's
// outgoing face fluxes; a face's flux is scaled by the theta of the cell it drains, so no depth
// goes negative (h_new >= h_c - theta_c O_c >= 0). Stored as theta + 2 for a flagged cell; ghosts
// take their image's value.
void LbmShallow::outflow_limiter() {
  const WetDryView view = wet_dry_view(hb_.data());
  float* theta = theta_.data();
  const float keep = hmin_ / 16.0f;
  const Span* spans = spans_.data();
  const int nspans = static_cast<int>(spans_.size());
#pragma omp parallel for schedule(static) if (ncells_ >= 16384)
  for (int s = 0; s < nspans; ++s)
    for (std::ptrdiff_t c = spans[s].begin; c < spans[s].end; ++c) {
      WdFace fc[9];
      view.faces(c, view.row_of(c), c % view.S - view.pad, fc);
      float out = 0.0f;
      for (int a = 1; a < 9; ++a) out += fc[a].flux < 0.0f ? -fc[a].flux : 0.0f;
      const float avail = view.h[c] - keep;  // a film h_min/16 stays: float rounding never crosses 0
      const float th = out <= avail ? 1.0f : avail > 0.0f ? avail / out : 0.0f;
      theta[c] = th + (fv_flag(view.flags[c]) ? 2.0f : 0.0f);
    }
  exchange_theta();  // the halo rows' theta (several ranks; halo.cpp)
  for (const Rule& r : rules_) theta[r.s] = r.up != kNone ? theta[r.up] : 1.0f;
}

namespace {

// Makes the nine floats sum to `mass` (double) as closely as floats allow: the rounding left by
// the collision goes into the rest population, what that rounds off into the opposite pairs of
// links in equal halves (no momentum: still water stays still). Returns what the floats could not
// take, mass - sum op (under half a float ulp of the cell's smallest population touched), which
// the caller carries to the cell's next step (compensated storage, Kahan 1965; docs/lbm.md).
double keep_mass(double mass, float* op) {
  double sum = 0.0;
  for (int a = 0; a < 9; ++a) sum += op[a];
  double r = mass - sum;
  const float n0 = static_cast<float>(op[0] + r);
  r -= double(n0) - double(op[0]);
  op[0] = n0;
  for (int a = 1; a < 9 && r != 0.0; a += a == 2 || a == 6 ? 3 : 1) {  // pairs (1,3) (2,4) (5,7) (6,8)
    const int b = kOpp[a];
    const float na = static_cast<float>(op[a] + 0.5 * r), nb = static_cast<float>(op[b] + 0.5 * r);
    r -= (double(na) - double(op[a])) + (double(nb) - double(op[b]));
    op[a] = na;
    op[b] = nb;
  }
  return r;
}

// The post-collision state of a cell the HLL update reached: the shifted equilibrium of depth h
// and momentum (jx, jy) (lattice units, speed capped at sqrt(umax2); a film below h_min keeps its
// momentum too, so water entering dry land arrives moving) plus the force lambda_a h (e_a . a)/3,
// the rest population taking h - H minus the others so the populations sum to the depth.
Cell9 equilibrium_cell(float h, float jx, float jy, const Collision& k, const float* ks) {
  const float ih = h > 0.0f ? 1.0f / h : 0.0f;
  float ux = jx * ih, uy = jy * ih;
  const float u2 = ux * ux + uy * uy, r = u2 > k.umax2 ? std::sqrt(k.umax2 / u2) : 1.0f;
  ux *= r;
  uy *= r;
  const float gx = h * (1.0f / 3.0f) * k.ax, gy = h * (1.0f / 3.0f) * k.ay;
  const float force[9] = {
      0, gx, gy, -gx, -gy, 0.25f * (gx + gy), 0.25f * (gy - gx), -0.25f * (gx + gy), -0.25f * (gy - gx)};
  float f[9], rest = h - k.href;
  for (int a = 1; a < 9; ++a) {
    const float eu = static_cast<float>(kEx[a]) * ux + static_cast<float>(kEy[a]) * uy;
    f[a] = static_cast<float>(kLambda[a]) * h *
               (k.g * h * (1.0f / 6.0f) + eu * (1.0f / 3.0f) + 0.5f * eu * eu - (ux * ux + uy * uy) * (1.0f / 6.0f)) -
           ks[a];
    rest -= f[a];
    f[a] += force[a];
  }
  return {rest, f[1], f[2], f[3], f[4], f[5], f[6], f[7], f[8]};
}

}  // namespace

// One cell of the wet/dry pass. Without an HLL face: limited exchanges, collision with |u| <= u_max.
// With one: the finite-volume update h += sum M_a, J += sum e_a Pi_a over its faces (an LBM face
// exchanges M = v - p2, Pi = v + p2, what streaming moves), then the equilibrium of (h, J) is
// collided. Dry cells to rest. Returns the new depth.
float LbmShallow::wet_dry_cell(const WetDryView& view, std::ptrdiff_t c, float* dst, float* carry) const {
  const std::ptrdiff_t P = view.P;
  const float* theta = theta_.data();
  const float* src = view.src;
  const Collision k{omega_, g_, ax_, ay_, hmin_, href_, umax_ * umax_};
  const float* shp = view.shift;
  const Cell9 ks{shp[0], shp[1], shp[2], shp[3], shp[4], shp[5], shp[6], shp[7], shp[8]};
  WdFace fc[9];
  view.faces(c, view.row_of(c), c % view.S - view.pad, fc);
  bool any = false;
  for (int a = 1; a < 9; ++a) any = any || fc[a].fv;
  float fp[9] = {src[c]};
  bool fed = false;  // water arrived over an HLL face
  float hs = src[c] + shp[0], jx = 0.0f, jy = 0.0f;
  // the stored (shifted) populations' new sum, exact to double rounding, plus what the cell's
  // floats could not hold last step (the carry plane, when there is one)
  double mass = double(src[c]) + (carry != nullptr ? double(carry[c]) : 0.0);
  for (int a = 1; a < 9; ++a) {
    const float own = src[a * P + c];
    mass += own;
    hs += own + shp[a];
    jx += static_cast<float>(kEx[a]) * own;
    jy += static_cast<float>(kEy[a]) * own;
  }
  for (int a = 1; a < 9; ++a) {
    const WdFace& f = fc[a];
    const std::ptrdiff_t other = f.fv ? f.img : c - view.off[a];
    // the drained cell's theta, chosen by the sign of the unrounded exchange (both cells see it)
    const double fx = f.fv ? double(f.flux) : f.vx - double(f.p2);
    const float th = fv_theta(fx < 0.0 ? theta[c] : theta[other]);
    const float v = th >= 1.0f ? f.v : f.p2 + th * f.flux;
    fp[a] = v;
    const float m = f.fv ? th * f.flux : v - f.p2, pi = f.fv ? th * f.pi : v + f.p2;
    fed = fed || (f.fv && m > 0.0f);
    mass += f.fv ? double(th) * f.flux : double(th) * (f.vx - f.p2);  // -(the neighbour's) exactly
    hs += m;
    jx += static_cast<float>(kEx[a]) * pi;
    jy += static_cast<float>(kEy[a]) * pi;
  }
  float h = hs, unused = 0.0f;
  const Cell9 f{fp[0], fp[1], fp[2], fp[3], fp[4], fp[5], fp[6], fp[7], fp[8]};
  Cell9 o;
  if (!any)
    o = rest_if_dry(f, collide<true>(f, k, h, unused), h, hmin_, ks);
  else if (hs >= hmin_ || fed)
    o = equilibrium_cell(hs, jx, jy, k, shp);
  else  // dry and nothing arrived: at rest
    o = Cell9{hs - href_ + (((ks.f1 + ks.f2) + (ks.f3 + ks.f4)) + ((ks.f5 + ks.f6) + (ks.f7 + ks.f8))),
              -ks.f1,
              -ks.f2,
              -ks.f3,
              -ks.f4,
              -ks.f5,
              -ks.f6,
              -ks.f7,
              -ks.f8};
  float op[9] = {o.f0, o.f1, o.f2, o.f3, o.f4, o.f5, o.f6, o.f7, o.f8};
  const double left = keep_mass(mass, op);
  if (carry != nullptr) carry[c] = static_cast<float>(left);
  for (int a = 0; a < 9; ++a) dst[a * P + c] = op[a];
  return any ? static_cast<float>(mass + href_) : h;
}

// The wet/dry pass (while a cell is dry): flags, limiter, then every cell by wet_dry_cell.
// `dry` counts h < h_min, `bad` counts h < 0 or NaN.
void LbmShallow::stream_collide_wet_dry(int& dry, int& bad) {
  exchange_second_rows();  // several ranks: the MUSCL slopes read two rows beyond the slab (halo.cpp)
  flag_supercritical();
  outflow_limiter();
  const WetDryView view = wet_dry_view(theta_.data());
  float* dst = fb_.data();
  float* hnew = hb_.data();
  float* carry = carry_.size() != 0 ? carry_.data() : nullptr;
  const float hmin = hmin_;
  const Span* spans = spans_.data();
  const int nspans = static_cast<int>(spans_.size());
  int ndry = 0, nbad = 0;
#pragma omp parallel for schedule(static) reduction(+ : ndry, nbad) if (ncells_ >= 16384)
  for (int s = 0; s < nspans; ++s)
    for (std::ptrdiff_t c = spans[s].begin; c < spans[s].end; ++c) {
      const float h = wet_dry_cell(view, c, dst, carry);
      ndry += h < hmin ? 1 : 0;
      nbad += h >= 0.0f ? 0 : 1;
      hnew[c] = h;
    }
  dry = ndry;
  bad = nbad;
}

void LbmShallow::step() {
  const bool wet_dry = dry_ > 0;
  if (wet_dry && ranks_ > 1 && image_row_ >= 0) throw_periodic_wet_dry();
  int flagged = 0, bad = 0;
  // several ranks, all wet: the halo exchange overlaps the inner rows' update (halo.cpp)
  const bool overlap = ranks_ > 1 && !wet_dry;
  if (overlap) all_wet_overlapped(flagged);
  if (ranks_ > 1 && !overlap) exchange_halos();  // the neighbours' rows this step reads (halo.cpp)
  if (!overlap) {
    StageTimer t(stats_[st_fill_]);
    if (wet_dry) set_ghost_depths();
    fill_ghosts(wet_dry);
  }
  {
    StageTimer t(stats_[st_kernel_]);
    if (wet_dry)
      stream_collide_wet_dry(flagged, bad);
    else if (!overlap)
      all_wet_kernel(flagged);
    agree(flagged, bad);  // several ranks: the counts of all ranks
    if (!wet_dry && flagged) {
      // A cell fell below h_min (or went negative) in the all-wet pass: the populations it read
      // are intact (pull scheme), so the step is redone by the wet/dry pass. The naive bed term
      // has no wet/dry form: that run stops.
      if (p_.bed_force == LbmBedForce::naive && has_bed_) {
        bad = 1;
      } else {
        if (image_row_ >= 0) throw_periodic_wet_dry();
        ++redone_;
        unshift();
        set_ghost_depths();
        fill_ghosts(true);
        stream_collide_wet_dry(flagged, bad);
        agree(flagged, bad);
      }
    }
  }
  std::swap(fa_, fb_);
  std::swap(ha_, hb_);
  ++steps_;
  if (bad) throw_bad_cell();
  dry_ = static_cast<std::size_t>(flagged);
}

// The all-wet pass: flat bed, well-balanced centred bed term or the naive one; with or without an
// external force.
void LbmShallow::all_wet_kernel(int& flagged) {
  const int mode = !has_bed_ ? 0 : p_.bed_force == LbmBedForce::centred ? 1 : 2;
  const bool force = ax_ != 0.0f || ay_ != 0.0f;
  switch (mode * 2 + (force ? 1 : 0)) {
    case 0:
      return stream_collide<0, false>(flagged);
    case 1:
      return stream_collide<0, true>(flagged);
    case 2:
      return stream_collide<1, false>(flagged);
    case 3:
      return stream_collide<1, true>(flagged);
    case 4:
      return stream_collide<2, false>(flagged);
    default:
      return stream_collide<2, true>(flagged);
  }
}

void LbmShallow::unshift() {
  // h - H of a cell near dry has the float resolution of H, coarser than a thin film: once a cell
  // dries, populations are stored unshifted (a dry cell's zero populations and depth are exact).
  if (href_ == 0.0f) return;
  for (const auto* spans : {&spans_, &halo_spans_})  // halo rows: as their owners do
    for (const Span& sp : *spans)
      for (int a = 0; a < 9; ++a) {
        float* f = fa_.data() + static_cast<std::size_t>(a) * plane_;
        for (std::uint32_t c = sp.begin; c < sp.end; ++c) f[c] += shift_f_[a];
      }
  shift_ = {};
  shift_f_ = {};
  href_ = 0.0f;
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

double LbmShallow::volume_m3() const {
  // From the populations (h = H + sum of shifted populations), in double.
  double sum = 0;
  std::size_t cells = 0;
  for (const Span& sp : spans_) {
    for (int a = 0; a < 9; ++a) {
      const float* f = fa_.data() + a * plane_;
      for (std::uint32_t c = sp.begin; c < sp.end; ++c) sum += f[c];
    }
    cells += sp.end - sp.begin;
  }
  return (sum + static_cast<double>(href_) * static_cast<double>(cells)) * p_.cell_m * p_.cell_m;
}

void LbmShallow::depth(std::span<float> out) const {
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < p_.cols; ++c) out[static_cast<std::size_t>(r) * p_.cols + c] = depth_at(row0_ + r, c);
}

float LbmShallow::depth_at(int row, int col) const {
  const std::size_t k = idx(row, col);
  return solid_[k] ? 0.0f : ha_[k];
}

std::array<float, 2> LbmShallow::velocity_at(int row, int col) const {
  const std::size_t k = idx(row, col);
  if (solid_[k] || ha_[k] < hmin_) return {0.0f, 0.0f};  // dry cells are at rest
  double h = href_, mx = 0, my = 0;
  for (int a = 0; a < 9; ++a) {
    const double f = fa_[a * plane_ + k];  // shifted populations
    h += f;
    mx += kEx[a] * f;
    my += kEy[a] * f;
  }
  // Post-collision momentum includes the external force h a: remove it to get u of the step.
  const double e = lat_.speed_mps;
  return {static_cast<float>((mx / h - ax_) * e), static_cast<float>((my / h - ay_) * e)};
}

void LbmShallow::velocity(std::span<float> out) const {
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < p_.cols; ++c) {
      const auto u = velocity_at(row0_ + r, c);
      const std::size_t i = 2 * (static_cast<std::size_t>(r) * p_.cols + c);
      out[i] = u[0];
      out[i + 1] = u[1];
    }
}

void LbmShallow::bed(std::span<float> out) const {
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < p_.cols; ++c) out[static_cast<std::size_t>(r) * p_.cols + c] = z_[idx(row0_ + r, c)];
}

int LbmShallow::bytes_per_cell() const {
  // 9 populations read and written, the new depth written; a bed adds z and the old depth.
  return has_bed_ ? 21 * 4 : 19 * 4;
}

}  // namespace huygens
