#include "huygens/validation/reference/kelvin.hpp"

#include <algorithm>
#include <complex>
#include <numbers>
#include <vector>

#include "huygens/common/fft.hpp"
#include "huygens/spectral/cutoff.hpp"
#include "huygens/spectral/propagator.hpp"

namespace huygens {

namespace {

constexpr double kPi = std::numbers::pi;
using cd = std::complex<double>;

// Bilinear sample of a complex field; false outside the grid.
bool sample(const std::vector<cfloat>& a, const WakeGrid& g, double x, double y, cd& out) {
  const double fx = (x - g.x0_m) / g.dx_m, fy = (y - g.y0_m) / g.dx_m;
  if (fx < 0 || fy < 0 || fx > g.cols - 1 || fy > g.rows - 1) return false;
  const int c = std::min(static_cast<int>(fx), g.cols - 2), r = std::min(static_cast<int>(fy), g.rows - 2);
  const double u = fx - c, v = fy - r;
  auto at = [&](int rr, int cc) { return cd(a[static_cast<std::size_t>(rr) * g.cols + cc]); };
  out = (1 - v) * ((1 - u) * at(r, c) + u * at(r, c + 1)) + v * ((1 - u) * at(r + 1, c) + u * at(r + 1, c + 1));
  return true;
}

// Least-squares slope and intercept of y against x.
void fit_line(const std::vector<double>& x, const std::vector<double>& y, double& slope, double& icpt) {
  const double m = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  icpt = (sy - slope * sx) / m;
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

double kelvin_transverse_wavelength(const Water& water, double speed_mps) {
  // gravity branch: phase speed decreases with k up to k_m; solve c(k) = U by bisection
  const double km = water.surface_tension_npm > 0 ? min_phase_speed_wavenumber(water) : 1e12;
  if (phase_speed(water, km) > speed_mps) return std::numeric_limits<double>::quiet_NaN();
  double lo = 1e-9, hi = km;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (phase_speed(water, mid) > speed_mps ? lo : hi) = mid;
  }
  return 2.0 * kPi / std::sqrt(lo * hi);
}

double kelvin_cusp_angle(const Water& water, double speed_mps) {
  const double km = water.surface_tension_npm > 0 ? min_phase_speed_wavenumber(water) : 1e12;
  double best = std::numeric_limits<double>::quiet_NaN();
  for (int i = 1; i < 20000; ++i) {
    const double th = 0.5 * kPi * i / 20000.0, c = speed_mps * std::cos(th);
    // gravity branch: phase speed decreasing in k on (0, km)
    if (phase_speed(water, km) > c) break;
    if (!water.deep() && c >= std::sqrt(water.gravity_mps2 * water.depth_m)) continue;
    double lo = 1e-9, hi = km;
    for (int j = 0; j < 100; ++j) {
      const double mid = std::sqrt(lo * hi);
      (phase_speed(water, mid) > c ? lo : hi) = mid;
    }
    const double k = std::sqrt(lo * hi), n = group_speed(water, k) / phase_speed(water, k);
    const double t = std::tan(th);
    const double psi = std::atan(n * t / (1.0 - n + t * t)) * 180.0 / kPi;
    if (!(psi <= best)) best = psi;
  }
  return best;
}

namespace {

// The analytic signal of the field (paper 004 eq. 2 wake, method in kelvin.hpp): its spectrum
// kept on the half-plane k.d > 0 (doubled, k.d = 0 once), d the direction of motion, and, when
// opt.lowpass_k0 > 0, the same weighted by 1 / (1 + (k / k_c)^8), k_c = lowpass_k0 g / U^2.
struct AnalyticSignal {
  std::vector<cfloat> full, low;
  /// The signal the envelope and the track phase read: the low-passed one when there is one.
  const std::vector<cfloat>& envelope() const { return low.empty() ? full : low; }
};

AnalyticSignal analytic_signal(const float* eta, const WakeGrid& g, const WakeTrack& tr, const WakeOptions& opt) {
  const std::size_t total = static_cast<std::size_t>(g.rows) * g.cols;
  AlignedBuffer<cfloat> buf(total);
  for (std::size_t i = 0; i < total; ++i) buf[i] = cfloat(eta[i], 0.0f);
  {
    Fft2D fwd(g.rows, g.cols, buf.data(), buf.data(), Fft2D::forward, PlanEffort::estimate);
    fwd.execute();
  }
  const double dxh = std::cos(tr.heading_rad), dyh = std::sin(tr.heading_rad);
  const double kc = opt.lowpass_k0 * opt.gravity_mps2 / (tr.speed_mps * tr.speed_mps);
  AlignedBuffer<cfloat> low(opt.lowpass_k0 > 0 ? total : 0);
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      const double kx = fft_wavenumber(c, g.cols, g.cols * g.dx_m), ky = fft_wavenumber(r, g.rows, g.rows * g.dx_m);
      const double kd = kx * dxh + ky * dyh;
      const float f = kd > 0 ? 2.0f : (kd == 0 ? 1.0f : 0.0f);
      const std::size_t m = static_cast<std::size_t>(r) * g.cols + c;
      buf[m] *= f / static_cast<float>(total);
      if (low.size()) {
        const double q = (kx * kx + ky * ky) / (kc * kc);
        low[m] = buf[m] * static_cast<float>(1.0 / (1.0 + q * q * q * q));
      }
    }
  AnalyticSignal out;
  for (AlignedBuffer<cfloat>* b : {&buf, &low}) {
    if (!b->size()) continue;
    Fft2D inv(g.rows, g.cols, b->data(), b->data(), Fft2D::backward, PlanEffort::estimate);
    inv.execute();
    (b == &buf ? out.full : out.low).assign(b->data(), b->data() + total);
  }
  return out;
}

// What the scan behind the ship collects; index 0 is the side left of the track, 1 the right.
struct WakeSamples {
  std::vector<double> caustic_s[2], caustic_n[2];  ///< caustic points: distance behind, lateral offset (m)
  std::vector<double> max_angle[2];                ///< angle of the largest |a| seen from the hull (rad)
  std::vector<double> track_s, track_phase;        ///< phase of the envelope signal along the track (m, rad)
  double last_s = 0;                               ///< last distance whose profiles were complete (m)
};

// |a| every dn from (bx, by) along (nx, ny) out to n_max: of the envelope signal in `prof` and,
// with a low-pass, of the full one in `full`. False when the profile leaves the grid or holds
// fewer than 8 points.
bool lateral_profile(const AnalyticSignal& a, const WakeGrid& g, double bx, double by, double nx, double ny,
                     double n_max, double dn, std::vector<double>& prof, std::vector<double>& full) {
  cd v;
  for (double n = 0; n <= n_max; n += dn) {
    if (!sample(a.envelope(), g, bx + n * nx, by + n * ny, v)) return false;
    prof.push_back(std::abs(v));
    if (!a.low.empty() && sample(a.full, g, bx + n * nx, by + n * ny, v)) full.push_back(std::abs(v));
  }
  return prof.size() >= 8;
}

// Lateral offset of the caustic line on one profile (method step 2 in kelvin.hpp): on the outer
// flank of the outermost local maximum >= lobe_fraction of the profile's largest value, where
// |a| falls to `level` of that maximum (linear between samples). False when there is none.
bool caustic_offset(const std::vector<double>& prof, double dn, const WakeOptions& opt, double& n_c) {
  const double top = *std::max_element(prof.begin(), prof.end());
  if (!(top > 0)) return false;
  int lobe = -1;
  for (int i = static_cast<int>(prof.size()) - 2; i >= 1; --i)
    if (prof[i] >= prof[i - 1] && prof[i] >= prof[i + 1] && prof[i] >= opt.lobe_fraction * top) {
      lobe = i;
      break;
    }
  if (lobe < 0) return false;
  const double target = opt.level * prof[lobe];
  for (std::size_t i = static_cast<std::size_t>(lobe) + 1; i < prof.size(); ++i)
    if (prof[i] < target) {
      const double f = (prof[i - 1] - target) / (prof[i - 1] - prof[i]);
      n_c = (static_cast<double>(i - 1) + f) * dn;
      return true;
    }
  return false;
}

// The station at distance s behind the hull: on each side the max-amplitude angle and the
// caustic point, then the track phase. False when the track point or a profile leaves the grid
// (the scan ends there; a first side's samples are kept).
bool scan_station(const AnalyticSignal& a, const WakeGrid& g, const WakeTrack& tr, const WakeOptions& opt, double s,
                  WakeSamples& out) {
  const double dxh = std::cos(tr.heading_rad), dyh = std::sin(tr.heading_rad);
  const double dn = 0.5 * g.dx_m, n_max = s * std::tan(opt.search_angle_deg * kPi / 180.0);
  const double bx = tr.x_m - s * dxh, by = tr.y_m - s * dyh;  // point on the track
  cd v;
  if (!sample(a.envelope(), g, bx, by, v)) return false;
  for (int side = 0; side < 2; ++side) {
    const double sg = side == 0 ? 1.0 : -1.0;
    const double nx = -dyh * sg, ny = dxh * sg;  // lateral unit vector
    std::vector<double> prof, full;
    if (!lateral_profile(a, g, bx, by, nx, ny, n_max, dn, prof, full)) return false;
    // the angle of maximum amplitude from the full field
    const std::vector<double>& pm = a.low.empty() ? prof : full;
    const auto fmax = std::max_element(pm.begin(), pm.end());
    if (*fmax > 0) out.max_angle[side].push_back(std::atan2(static_cast<double>(fmax - pm.begin()) * dn, s));
    double n_c;
    if (caustic_offset(prof, dn, opt, n_c)) {
      out.caustic_s[side].push_back(s);
      out.caustic_n[side].push_back(n_c);
    }
  }
  out.track_s.push_back(s);
  out.track_phase.push_back(std::arg(v));
  return true;
}

// Method steps 2-4 of kelvin.hpp from the collected samples.
void fit_wake(WakeSamples& w, WakeMeasurement& res) {
  res.profiles = static_cast<int>(std::min(w.caustic_s[0].size(), w.caustic_s[1].size()));
  if (w.caustic_s[0].size() >= 3 && w.caustic_s[1].size() >= 3) {
    double m0, b0, m1, b1;
    fit_line(w.caustic_s[0], w.caustic_n[0], m0, b0);
    fit_line(w.caustic_s[1], w.caustic_n[1], m1, b1);
    res.envelope_angle_deg = std::atan(0.5 * (m0 + m1)) * 180.0 / kPi;
  }
  if (!w.max_angle[0].empty() && !w.max_angle[1].empty())
    res.max_amplitude_angle_deg = 0.5 * (median(w.max_angle[0]) + median(w.max_angle[1])) * 180.0 / kPi;
  std::vector<double>& ph = w.track_phase;
  if (w.track_s.size() >= 4) {
    for (std::size_t i = 1; i < ph.size(); ++i) {  // unwrap
      double d = ph[i] - ph[i - 1];
      d -= 2.0 * kPi * std::round(d / (2.0 * kPi));
      ph[i] = ph[i - 1] + d;
    }
    double m, b;
    fit_line(w.track_s, ph, m, b);
    res.transverse_wavelength_m = 2.0 * kPi / std::abs(m);
  }
}

}  // namespace

WakeMeasurement measure_kelvin_wake(const float* eta, const WakeGrid& g, const WakeTrack& tr, const WakeOptions& opt) {
  const AnalyticSignal a = analytic_signal(eta, g, tr, opt);
  const double lam = 2.0 * kPi * tr.speed_mps * tr.speed_mps / opt.gravity_mps2;
  WakeMeasurement res;
  res.s_min_m = opt.s_min_m >= 0 ? opt.s_min_m : 3.0 * lam;
  const double s_max = opt.s_max_m >= 0 ? opt.s_max_m : 1e30;
  WakeSamples w;
  w.last_s = res.s_min_m;
  for (double s = res.s_min_m; s <= s_max; s += g.dx_m) {
    if (!scan_station(a, g, tr, opt, s, w)) break;
    w.last_s = s;
  }
  res.s_max_m = w.last_s;
  fit_wake(w, res);
  return res;
}

void steady_wake(const Water& water, const HullParams& hull, const WakeGrid& g, const WakeTrack& tr, double mu,
                 float* eta) {
  const std::size_t total = static_cast<std::size_t>(g.rows) * g.cols;
  AlignedBuffer<cfloat> buf(total);
  const double vx = tr.speed_mps * std::cos(tr.heading_rad), vy = tr.speed_mps * std::sin(tr.heading_rad);
  const double px = tr.x_m - g.x0_m, py = tr.y_m - g.y0_m;
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      const double kx = fft_wavenumber(c, g.cols, g.cols * g.dx_m), ky = fft_wavenumber(r, g.rows, g.rows * g.dx_m);
      const double k = std::hypot(kx, ky);
      cd e = 0;
      if (k > 0) {
        const double om = omega(water, k);
        const cd w(kx * vx + ky * vy, mu);
        e = -w * w / (om * om - w * w) * hull_spectrum(hull, kx, ky, tr.heading_rad) *
            std::exp(cd(0, -(kx * px + ky * py))) / (g.dx_m * g.dx_m * static_cast<double>(total));
      }
      buf[static_cast<std::size_t>(r) * g.cols + c] = cfloat(e);
    }
  Fft2D inv(g.rows, g.cols, buf.data(), buf.data(), Fft2D::backward, PlanEffort::estimate);
  inv.execute();
  for (std::size_t i = 0; i < total; ++i) eta[i] = buf[i].real();
}

KelvinRunResult run_kelvin_case(const KelvinCase& kc, const WakeOptions& opt) {
  KelvinRunResult res;
  const double dx = kc.dx_m, len = kc.n * dx, u = kc.speed_mps;
  HuygensParams p;
  p.n = kc.n;
  p.length_m = len;
  p.margin = kc.margin;
  p.dt_s = std::min(kc.dt_s, kc.max_cells_per_step * dx / u);
  p.water = kc.water;
  p.effort = PlanEffort::estimate;
  p.spatial = true;
  p.check_every = 0;
  p.round_trip_every = kc.round_trip_every > 0 ? kc.round_trip_every : auto_round_trip_every(p);
  HuygensPropagator prop(p);
  const double m = kc.margin * dx, hl = kc.hull.length_m;
  const double x0 = m + 2.0 * hl, x1 = len - m - 2.0 * hl, yc = 0.5 * len;
  // path: x = x0 + u t^2 / (2 ramp) during the ramp, then uniform speed
  std::vector<PathPoint> pts;
  const double ramp = kc.ramp_s;
  if (ramp > 0)
    for (int i = 0; i <= 40; ++i) {
      const double t = ramp * i / 40.0;
      pts.push_back({t, x0 + u * t * t / (2.0 * ramp), yc});
    }
  else
    pts.push_back({0.0, x0, yc});
  const double t_end = (x1 - x0) / u + 0.5 * ramp;
  pts.push_back({t_end, x1, yc});
  Ship ship;
  ship.hull = kc.hull;
  ship.path = ShipPath(pts);
  int patch = 2 * kc.margin;
  while (0.25 * patch * dx < 0.5 * std::max(hl, kc.hull.beam_m) + 3.0 * kc.hull.blur()) patch += 2;
  patch = std::min(patch, kc.n);
  ShipWaves ships(kc.water, kc.n, len, patch, {ship}, PlanEffort::estimate);
  ships.check_step(p.dt_s);
  ships.reserve_gather(prop.round_trip_every());
  res.steps = static_cast<int>(std::floor(t_end / p.dt_s));
  for (int i = 0; i < res.steps; ++i) {
    prop.propagate();
    prop.cutoff();
    // as HuygensSolver::add_ships: each step's patch enters at the next round trip
    ships.gather(i * p.dt_s, p.dt_s, prop.steps_to_round_trip());
    if (prop.round_trip_now()) ships.scatter_rows(prop.field().data(), 0, prop.n());
    prop.spectrum();
    prop.height();
    prop.end_step();
  }
  double sx, sy;
  ship.path.position(res.steps * p.dt_s, sx, sy);
  res.travelled_m = sx - x0;
  const int v = prop.visible_size();
  res.eta.assign(prop.eta().begin(), prop.eta().end());
  res.grid.rows = res.grid.cols = v;
  res.grid.dx_m = dx;
  res.grid.x0_m = res.grid.y0_m = m;
  res.track.x_m = sx;
  res.track.y_m = sy;
  res.track.speed_mps = u;
  for (int r = 0; r < v; ++r)
    for (int c = 0; c < v; ++c) {
      const double d = std::hypot(m + c * dx - sx, m + r * dx - sy);
      const double e = std::abs(res.eta[static_cast<std::size_t>(r) * v + c]);
      (d > kc.far_radius_m ? res.far_max_m : res.near_max_m) =
          std::max(d > kc.far_radius_m ? res.far_max_m : res.near_max_m, e);
    }
  WakeOptions o = opt;
  if (o.s_max_m < 0) o.s_max_m = 0.5 * res.travelled_m;
  o.gravity_mps2 = kc.water.gravity_mps2;
  res.wake = measure_kelvin_wake(res.eta.data(), res.grid, res.track, o);
  return res;
}

}  // namespace huygens
