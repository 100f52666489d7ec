#include "huygens/validation/reference/kelvin.hpp"

#include <algorithm>
#include <complex>
#include <numbers>
#include <vector>

#include "huygens/common/fft.hpp"
#include "huygens/huygens/propagator.hpp"

namespace huygens {

namespace {

constexpr double kPi = std::numbers::pi;
using cd = std::complex<double>;

double wavenumber(int i, int n, double len) { return 2.0 * kPi / len * (i < n / 2 ? i : i - n); }

// Bilinear sample of a complex field; false outside the grid.
bool sample(const std::vector<cfloat>& a, const WakeGrid& g, double x, double y, cd& out) {
  const double fx = (x - g.x0_m) / g.dx, fy = (y - g.y0_m) / g.dx;
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
  const double km = water.surface_tension > 0 ? min_phase_speed_wavenumber(water) : 1e12;
  if (phase_speed(water, km) > speed_mps) return std::numeric_limits<double>::quiet_NaN();
  double lo = 1e-9, hi = km;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (phase_speed(water, mid) > speed_mps ? lo : hi) = mid;
  }
  return 2.0 * kPi / std::sqrt(lo * hi);
}

double kelvin_cusp_angle(const Water& water, double speed_mps) {
  const double km = water.surface_tension > 0 ? min_phase_speed_wavenumber(water) : 1e12;
  double best = std::numeric_limits<double>::quiet_NaN();
  for (int i = 1; i < 20000; ++i) {
    const double th = 0.5 * kPi * i / 20000.0, c = speed_mps * std::cos(th);
    // gravity branch: phase speed decreasing in k on (0, km)
    if (phase_speed(water, km) > c) break;
    if (!water.deep() && c >= std::sqrt(water.gravity * water.depth_m)) continue;
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

WakeMeasurement measure_kelvin_wake(const float* eta, const WakeGrid& g, const WakeTrack& tr, const WakeOptions& opt) {
  WakeMeasurement res;
  const std::size_t total = static_cast<std::size_t>(g.rows) * g.cols;
  // analytic signal: keep k.d > 0 (doubled), k.d = 0 once
  AlignedBuffer<cfloat> buf(total);
  for (std::size_t i = 0; i < total; ++i) buf[i] = cfloat(eta[i], 0.0f);
  {
    Fft2D fwd(g.rows, g.cols, buf.data(), buf.data(), Fft2D::forward, PlanEffort::estimate);
    fwd.execute();
  }
  const double dxh = std::cos(tr.heading_rad), dyh = std::sin(tr.heading_rad);
  // optional low-passed copy of the spectrum for the envelope and the transverse wavelength
  const double kc = opt.lowpass_k0 * opt.gravity / (tr.speed_mps * tr.speed_mps);
  AlignedBuffer<cfloat> low(opt.lowpass_k0 > 0 ? total : 0);
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      const double kx = wavenumber(c, g.cols, g.cols * g.dx), ky = wavenumber(r, g.rows, g.rows * g.dx);
      const double kd = kx * dxh + ky * dyh;
      const float f = kd > 0 ? 2.0f : (kd == 0 ? 1.0f : 0.0f);
      const std::size_t m = static_cast<std::size_t>(r) * g.cols + c;
      buf[m] *= f / static_cast<float>(total);
      if (low.size()) {
        const double q = (kx * kx + ky * ky) / (kc * kc);
        low[m] = buf[m] * static_cast<float>(1.0 / (1.0 + q * q * q * q));
      }
    }
  std::vector<cfloat> a, al;
  for (AlignedBuffer<cfloat>* b : {&buf, &low}) {
    if (!b->size()) continue;
    Fft2D inv(g.rows, g.cols, b->data(), b->data(), Fft2D::backward, PlanEffort::estimate);
    inv.execute();
    (b == &buf ? a : al).assign(b->data(), b->data() + total);
  }
  // the envelope and the phase along the track from the low-passed signal when asked
  const std::vector<cfloat>& ae = al.empty() ? a : al;

  const double lam = 2.0 * kPi * tr.speed_mps * tr.speed_mps / opt.gravity;
  const double s_min = opt.s_min_m >= 0 ? opt.s_min_m : 3.0 * lam;
  const double s_max = opt.s_max_m >= 0 ? opt.s_max_m : 1e30;
  const double ds = g.dx, dn = 0.5 * g.dx;
  const double tan_wide = std::tan(opt.search_angle_deg * kPi / 180.0);
  std::vector<double> cs[2], cn[2], angmax[2];
  std::vector<double> ts, tphase;
  double last_s = s_min;
  for (double s = s_min; s <= s_max; s += ds) {
    const double bx = tr.x_m - s * dxh, by = tr.y_m - s * dyh;  // point on the track
    cd v;
    if (!sample(ae, g, bx, by, v)) break;
    ts.push_back(s);
    tphase.push_back(std::arg(v));
    bool complete = true;
    for (int side = 0; side < 2; ++side) {
      const double sg = side == 0 ? 1.0 : -1.0;
      const double nx = -dyh * sg, ny = dxh * sg;  // lateral unit vector
      std::vector<double> prof, full;
      for (double n = 0; n <= s * tan_wide; n += dn) {
        if (!sample(ae, g, bx + n * nx, by + n * ny, v)) {
          complete = false;
          break;
        }
        prof.push_back(std::abs(v));
        if (!al.empty() && sample(a, g, bx + n * nx, by + n * ny, v)) full.push_back(std::abs(v));
      }
      if (!complete || prof.size() < 8) {
        complete = false;
        break;
      }
      // the angle of maximum amplitude from the full field
      const std::vector<double>& pm = al.empty() ? prof : full;
      const auto fmax = std::max_element(pm.begin(), pm.end());
      if (*fmax > 0) angmax[side].push_back(std::atan2(static_cast<double>(fmax - pm.begin()) * dn, s));
      const double top = *std::max_element(prof.begin(), prof.end());
      if (!(top > 0)) continue;
      // outermost local maximum of at least lobe_fraction * top
      int lobe = -1;
      for (int i = static_cast<int>(prof.size()) - 2; i >= 1; --i)
        if (prof[i] >= prof[i - 1] && prof[i] >= prof[i + 1] && prof[i] >= opt.lobe_fraction * top) {
          lobe = i;
          break;
        }
      if (lobe < 0) continue;
      const double target = opt.level * prof[lobe];
      for (std::size_t i = static_cast<std::size_t>(lobe) + 1; i < prof.size(); ++i)
        if (prof[i] < target) {
          const double f = (prof[i - 1] - target) / (prof[i - 1] - prof[i]);
          cs[side].push_back(s);
          cn[side].push_back((static_cast<double>(i - 1) + f) * dn);
          break;
        }
    }
    if (!complete) {
      ts.pop_back();
      tphase.pop_back();
      break;
    }
    last_s = s;
  }
  res.s_min_m = s_min;
  res.s_max_m = last_s;
  res.profiles = static_cast<int>(std::min(cs[0].size(), cs[1].size()));
  if (cs[0].size() >= 3 && cs[1].size() >= 3) {
    double m0, b0, m1, b1;
    fit_line(cs[0], cn[0], m0, b0);
    fit_line(cs[1], cn[1], m1, b1);
    res.envelope_angle_deg = std::atan(0.5 * (m0 + m1)) * 180.0 / kPi;
  }
  if (!angmax[0].empty() && !angmax[1].empty())
    res.max_amplitude_angle_deg = 0.5 * (median(angmax[0]) + median(angmax[1])) * 180.0 / kPi;
  if (ts.size() >= 4) {
    for (std::size_t i = 1; i < tphase.size(); ++i) {
      double d = tphase[i] - tphase[i - 1];
      d -= 2.0 * kPi * std::round(d / (2.0 * kPi));
      tphase[i] = tphase[i - 1] + d;
    }
    double m, b;
    fit_line(ts, tphase, m, b);
    res.transverse_wavelength_m = 2.0 * kPi / std::abs(m);
  }
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
      const double kx = wavenumber(c, g.cols, g.cols * g.dx), ky = wavenumber(r, g.rows, g.rows * g.dx);
      const double k = std::hypot(kx, ky);
      cd e = 0;
      if (k > 0) {
        const double om = omega(water, k);
        const cd w(kx * vx + ky * vy, mu);
        e = -w * w / (om * om - w * w) * hull_spectrum(hull, kx, ky, tr.heading_rad) *
            std::exp(cd(0, -(kx * px + ky * py))) / (g.dx * g.dx * static_cast<double>(total));
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
  p.dt = std::min(kc.dt, kc.max_cells_per_step * dx / u);
  p.water = kc.water;
  p.effort = PlanEffort::estimate;
  p.spatial = true;
  p.check_every = 0;
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
  ships.check_step(p.dt);
  res.steps = static_cast<int>(std::floor(t_end / p.dt));
  for (int i = 0; i < res.steps; ++i) {
    prop.propagate();
    prop.cutoff();
    ships.add(prop.field().data(), i * p.dt, p.dt);
    prop.spectrum();
    prop.height();
    prop.end_step();
  }
  double sx, sy;
  ship.path.position(res.steps * p.dt, sx, sy);
  res.travelled_m = sx - x0;
  const int v = prop.visible_size();
  res.eta.assign(prop.eta().begin(), prop.eta().end());
  res.grid.rows = res.grid.cols = v;
  res.grid.dx = dx;
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
  o.gravity = kc.water.gravity;
  res.wake = measure_kelvin_wake(res.eta.data(), res.grid, res.track, o);
  return res;
}

}  // namespace huygens
