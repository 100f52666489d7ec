// Validation cases of the Huygens solver. The propagator (paper 004 section 3): FFT round trip
// and Parseval, phase speed, Cauchy-Poisson ring, group velocity, energy conservation and
// absorption by the margin. Ships, Stokes height, wind and time interpolation (paper 004 eq. 2,
// eq. 3): Kelvin wake, Froude trend, capillary threshold, ship step consistency, Stokes profile,
// interpolation order. `huygens validate` prints these rows and
// tests/validation/validation_huygens_test.cpp asserts them.
#include "huygens/validation/huygens_cases.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "huygens/common/report.hpp"
#include "huygens/spectral/cutoff.hpp"
#include "huygens/spectral/propagator.hpp"
#include "huygens/spectral/spectral_solver.hpp"
#include "huygens/validation/reference/cauchy_poisson.hpp"
#include "huygens/validation/reference/kelvin.hpp"
#include "huygens/validation/validation.hpp"

namespace huygens {

namespace {

constexpr double kPi = std::numbers::pi;

HuygensParams periodic(int n, double length, double dt) {
  HuygensParams p;
  p.n = n;
  p.length_m = length;
  p.margin = 0;
  p.dt_s = dt;
  p.absorber = Absorber::off;
  p.effort = PlanEffort::estimate;
  return p;
}

// ---- 1. FFT round trip and Parseval -------------------------------------------------------------
std::vector<ValidationRow> fft_case() {
  const int n = 256;
  const std::size_t nn = static_cast<std::size_t>(n) * n;
  AlignedBuffer<cfloat> x(nn), y(nn), z(nn);
  std::mt19937 rng(7);
  std::normal_distribution<float> nd(0.0f, 1.0f);
  for (std::size_t i = 0; i < nn; ++i) x[i] = cfloat(nd(rng), nd(rng));
  Fft2D fwd(n, n, x.data(), y.data(), Fft2D::forward, PlanEffort::estimate);
  Fft2D inv(n, n, y.data(), z.data(), Fft2D::backward, PlanEffort::estimate);
  fwd.execute();
  inv.execute();
  double e2 = 0, x2 = 0, y2 = 0;
  for (std::size_t i = 0; i < nn; ++i) {
    const std::complex<double> a = x[i], b = std::complex<double>(z[i]) / static_cast<double>(nn);
    e2 += std::norm(b - a);
    x2 += std::norm(a);
    y2 += std::norm(std::complex<double>(y[i]));
  }
  const double rt = std::sqrt(e2 / x2);
  const double pars = y2 / static_cast<double>(nn);  // sum |X|^2 / N^2 = sum |x|^2
  // float epsilon 6e-8; FFTW's rms error grows like eps sqrt(log N): 1e-6 is ~17 eps
  return {check("fft", "round trip rms error / rms (256^2, float)", rt, 0, rt, 1e-6),
          check("fft", "Parseval sum|X|^2/N^2 / sum|x|^2 - 1", pars / x2, 1.0, std::abs(pars / x2 - 1.0), 1e-6)};
}

// ---- 2. phase speed ---------------------------------------------------------------------------
struct PhaseResult {
  double c_measured, c_exact, phase_rel_err, amp_change;
};

// A plane wave on grid mode (5, 3) of a periodic 64^2 grid after `steps` steps: the projection
// a = 2/N^2 sum eta e^{-i k.x} should be A e^{-i omega t}.
PhaseResult plane_wave_phase(double wavelength, Water w, int steps, double dt) {
  const int n = 64, mx = 5, my = 3;
  const double len = wavelength * std::hypot(mx, my);
  HuygensParams p = periodic(n, len, dt);
  p.water = w;
  HuygensPropagator prop(p);
  const double amp = 1e-3;
  const double dir = std::atan2(my, mx) * 180.0 / kPi;
  prop.add_plane_wave(wavelength, amp, dir);
  prop.height();
  for (int s = 0; s < steps; ++s) prop.step();
  const double k = 2.0 * kPi / wavelength, kx = 2.0 * kPi * mx / len, ky = 2.0 * kPi * my / len;
  const double dx = prop.dx();
  std::complex<double> a = 0;
  const auto eta = prop.eta();
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      a +=
          static_cast<double>(eta[static_cast<std::size_t>(r) * n + c]) * std::polar(1.0, -(kx * c * dx + ky * r * dx));
  a *= 2.0 / (static_cast<double>(n) * n);
  const double om = omega(w, k), t = prop.time();
  // phase lag against the exact -omega t, wrapped to (-pi, pi]
  const double dphi = std::remainder(std::arg(a) + om * t, 2.0 * kPi);
  const double om_measured = om - dphi / t;
  return {om_measured / k, om / k, std::abs(dphi) / (om * t), std::abs(std::abs(a) / amp - 1.0)};
}

std::vector<ValidationRow> phase_case() {
  std::vector<ValidationRow> rows;
  Water deep;  // the full gravity-capillary dispersion relation in every case
  struct Setup {
    const char* name;
    double wavelength;
    Water water;
  };
  Water shallow = deep;
  shallow.depth_m = 0.5 / (2.0 * kPi / 1.0);  // k h = 0.5 for lambda = 1 m
  const std::vector<Setup> setups = {{"gravity lambda=1 m", 1.0, deep},
                                     {"capillary lambda=5 mm", 0.005, deep},
                                     {"mixed lambda=1.71 cm", 0.0171, deep},
                                     {"finite depth kh=0.5 lambda=1 m", 1.0, shallow}};
  for (const auto& s : setups) {
    const PhaseResult r = plane_wave_phase(s.wavelength, s.water, 1000, 1.0 / 60.0);
    rows.push_back(check("phase_speed", std::string(s.name) + ": phase speed (m/s), rel. phase error", r.c_measured,
                         r.c_exact, r.phase_rel_err, 1e-5));
    rows.push_back(check("phase_speed", std::string(s.name) + ": amplitude change after 1000 steps", 1.0 + r.amp_change,
                         1.0, r.amp_change, 1e-4));
  }
  return rows;
}

// ---- 3. Cauchy-Poisson ring -------------------------------------------------------------------
// The 15 m / 512 / margin 64 grid with the paper's cutoff, dt = 1/60 s, Gaussian sigma 0.1 m,
// A = 1 cm at the centre (a grid node, so r^2 = (i^2 + j^2) dx^2 and the exact solution is
// needed only at the distinct i^2 + j^2).
// The grid of the ring cases: 15 m, 512^2, margin 64, dt = 1/60 s.
HuygensParams ring_grid() {
  HuygensParams p;
  p.n = 512;
  p.length_m = 15.0;
  p.margin = 64;
  p.dt_s = 1.0 / 60.0;
  p.effort = PlanEffort::estimate;  // deterministic (Fft2D's row-column form): the same bits in any run
  return p;
}

std::vector<ValidationRow> cauchy_poisson_case() {
  const HuygensParams p = ring_grid();
  HuygensPropagator prop(p);
  const double amp = 0.01, sigma = 0.1, x0 = 7.5;
  prop.add_gaussian(x0, x0, sigma, amp);
  prop.height();
  CauchyPoissonGaussian g;
  g.water = p.water;
  g.sigma_m = sigma;
  g.amplitude_m = amp;
  const int n = p.n, m = p.margin, v = prop.visible_size();
  const int ic = static_cast<int>(std::lround(x0 / prop.dx()));
  const double dx = prop.dx(), rmax = 3.0;
  std::vector<ValidationRow> rows;
  for (const int target : {30, 60, 120}) {
    while (prop.steps() < target) prop.step();
    const double t = prop.time();
    // the exact solution at every distinct i^2 + j^2 inside r < 3 m (in parallel)
    std::vector<long> keys;
    for (int r = 0; r < v; ++r)
      for (int c = 0; c < v; ++c) {
        const long di = r + m - ic, dj = c + m - ic;
        if (static_cast<double>(di * di + dj * dj) * dx * dx < rmax * rmax) keys.push_back(di * di + dj * dj);
      }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<double> vals(keys.size());
#pragma omp parallel for schedule(dynamic, 16)
    for (long i = 0; i < static_cast<long>(keys.size()); ++i)
      vals[static_cast<std::size_t>(i)] =
          cauchy_poisson_eta(g, std::sqrt(static_cast<double>(keys[static_cast<std::size_t>(i)])) * dx, t);
    double err = 0;
    const auto eta = prop.eta();
    for (int r = 0; r < v; ++r)
      for (int c = 0; c < v; ++c) {
        const long di = r + m - ic, dj = c + m - ic;
        const long d2 = di * di + dj * dj;
        if (static_cast<double>(d2) * dx * dx >= rmax * rmax) continue;
        const double ex = vals[static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), d2) - keys.begin())];
        err = std::max(err, std::abs(eta[static_cast<std::size_t>(r) * v + c] - ex));
      }
    (void)n;
    rows.push_back(
        check("cauchy_poisson", fmt("t=%.1f s: max |eta - exact| over r<3 m / A", t), err / amp, 0, err / amp, 3e-3));
  }
  return rows;
}

// ---- 4. group velocity ------------------------------------------------------------------------
// A progressive Gaussian packet exp(-(x - x0)^2 / (2 s^2)) e^{i k0 x} (uniform in y): its energy
// centroid (density eta^2 + etadot^2 / omega0^2) moves at c_g(k0).
ValidationRow group_case(const char* name, double wavelength, double duration) {
  const int n = 256, cycles = 40;
  const double len = wavelength * cycles;
  Water w;
  const double k0 = 2.0 * kPi / wavelength, om0 = omega(w, k0), cg = group_speed(w, k0);
  const int steps = 200;
  HuygensParams p = periodic(n, len, duration / steps);
  p.water = w;
  HuygensPropagator prop(p);
  const double s = 0.075 * len, x0 = 0.3 * len, amp = 1e-3;
  std::vector<cfloat> z(static_cast<std::size_t>(n) * n);
  const double dx = prop.dx();
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const double x = c * dx;
      const std::complex<double> v = std::complex<double>(0, -om0 / k0 * amp) *
                                     std::exp(-0.5 * (x - x0) * (x - x0) / (s * s)) * std::polar(1.0, k0 * x);
      z[static_cast<std::size_t>(r) * n + c] = cfloat(static_cast<float>(v.real()), static_cast<float>(v.imag()));
    }
  prop.set_field(z);
  auto centroid = [&]() {
    double sw = 0, sx = 0;
    const auto e = prop.eta();
    const auto d = prop.etadot();
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const std::size_t i = static_cast<std::size_t>(r) * n + c;
        const double wgt = double(e[i]) * e[i] + double(d[i]) * d[i] / (om0 * om0);
        sw += wgt;
        sx += wgt * c * dx;
      }
    return sx / sw;
  };
  const double xa = centroid();
  for (int i = 0; i < steps; ++i) prop.step();
  const double speed = (centroid() - xa) / prop.time();
  return check("group_velocity", std::string(name) + ": centroid speed (m/s), rel. error", speed, cg,
               std::abs(speed / cg - 1.0), 1e-2);
}

std::vector<ValidationRow> group_cases() {
  return {group_case("gravity lambda=1 m", 1.0, 16.0), group_case("capillary lambda=1 cm", 0.01, 0.4)};
}

// ---- 5a. energy -------------------------------------------------------------------------------
ValidationRow energy_case(double dt, Rotation rot, int steps) {
  HuygensParams p = periodic(64, 4.0, dt);
  p.rotation = rot;
  HuygensPropagator prop(p);
  prop.add_gaussian(2.0, 2.0, 0.15, 0.01);
  prop.add_gaussian(1.0, 3.1, 0.05, -0.005);
  prop.add_plane_wave(0.5, 0.002, 0.0);
  prop.height();
  const double e0 = prop.energy();
  double worst = 0;
  for (int s = 1; s <= steps; ++s) {
    prop.step();
    if (s % 100 == 0) worst = std::max(worst, std::abs(prop.energy() / e0 - 1.0));
  }
  return check("energy", fmt("dt=%g s, %d steps, cutoff off: max |E/E0 - 1|", dt, steps), prop.energy() / e0, 1.0,
               worst, 1e-5);
}

std::vector<ValidationRow> energy_cases() {
  return {energy_case(1.0 / 60.0, Rotation::lifting, 10000), energy_case(1.0, Rotation::lifting, 10000)};
}

// ---- 5b. absorption ---------------------------------------------------------------------------
// The ring of case 3 on the 15 m grid with the cutoff against the same ring on a 60 m grid of the
// same dx without it (periodic; its images are 60 m away). The 60 m run is one exact step of
// dt = t (the propagator is exact in time for any dt), so it costs three transforms per time.
// The 15 m run takes the round trip every K = auto_round_trip_every steps, as a scene of this
// grid and step does (K = 8 at dt = 1/60 s: the cutoff (h h)^(K dt/tau) every K steps).
std::vector<ValidationRow> absorption_case(double cutoff_time_s) {
  HuygensParams p = ring_grid();
  p.cutoff_time_s = cutoff_time_s;
  p.round_trip_every = auto_round_trip_every(p);
  HuygensPropagator prop(p);
  const double amp = 0.01, sigma = 0.1;
  prop.add_gaussian(7.5, 7.5, sigma, amp);
  prop.height();
  const int v = prop.visible_size();
  const int big = 2048, off = (big - p.n) / 2 + p.margin;
  std::vector<ValidationRow> rows;
  const double tol[3] = {1e-3, 2e-3, 5e-3};
  // the reference steps exactly by 2 s: 1, 2 and 4 steps give t = 2, 4, 8 s
  HuygensParams q = periodic(big, 60.0, 2.0);
  HuygensPropagator ref(q);
  ref.add_gaussian(30.0, 30.0, sigma, amp);
  int i = 0;
  for (const double t : {2.0, 4.0, 8.0}) {
    const long target = std::lround(t / p.dt_s);
    while (prop.steps() < target) prop.step();
    while (ref.time() < t - 1e-9) ref.step();
    const auto a = prop.eta();
    const auto b = ref.eta();
    double err = 0;
    for (int r = 0; r < v; ++r)
      for (int c = 0; c < v; ++c)
        err = std::max(err, std::abs(double(a[static_cast<std::size_t>(r) * v + c]) -
                                     b[static_cast<std::size_t>(r + off) * big + c + off]));
    const std::string which =
        (cutoff_time_s > 0 ? fmt("tau=%g s cutoff", cutoff_time_s) : std::string("paper cutoff")) +
        fmt(" every %d steps", p.round_trip_every);
    rows.push_back(check(cutoff_time_s > 0 ? "absorption_tau" : "absorption",
                         fmt("t=%.0f s: max |eta_15m - eta_60m| visible / A, %s", t, which.c_str()), err / amp, 0,
                         err / amp, tol[i++]));
  }
  return rows;
}

// ==== ships, Stokes height, wind and time interpolation (paper 004 eq. 2, eq. 3) ==============

// Kelvin runs: a 1 m x 0.3 m x 0.05 m hull at Fr = U / sqrt(g L) on an n x n grid of
// dx = min(lambda_t, L_hull) / cells (lambda_t = 2 pi U^2 / g), gravity only (surface tension 0:
// the theory is the deep gravity-wave one), started from rest at full speed, measured by
// kelvin.hpp (analytic signal; the outer Airy lobe's 0.6628 level on lateral profiles, line fit
// = outer half-angle; median angle of the largest envelope = max-amplitude angle; phase slope
// along the track = transverse wavelength) between 3 wavelengths and half the distance travelled.
// `dx_m` > 0 replaces that cell size; `lowpass_k0` > 0 measures the envelope and the transverse
// wavelength on the field low-passed at lowpass_k0 g/U^2 (WakeOptions::lowpass_k0); the step is
// min(dt, max_cells U / dx).
KelvinRunResult kelvin_run(double froude, int n, double cells, double dx_m = 0.0, double lowpass_k0 = 0.0,
                           double dt = 0.05, double max_cells = 1.0) {
  KelvinCase c;
  c.water.surface_tension_npm = 0.0;
  c.speed_mps = froude * std::sqrt(c.water.gravity_mps2 * c.hull.length_m);
  const double lam = kelvin_transverse_wavelength(c.water, c.speed_mps);
  c.n = n;
  c.dx_m = dx_m > 0 ? dx_m : std::min(lam, c.hull.length_m) / cells;
  c.margin = n / 10;
  c.dt_s = dt;
  c.max_cells_per_step = max_cells;
  WakeOptions o;
  o.lowpass_k0 = lowpass_k0;
  // the default nearest distance is 3 transverse wavelengths; at Fr >= 1 that is beyond half the
  // distance travelled (the steady part), so measure between a quarter and half of it
  const double travelled = (c.n - 2 * c.margin) * c.dx_m - 4 * c.hull.length_m;
  if (3 * lam > 0.25 * travelled) o.s_min_m = 0.25 * travelled;
  return run_kelvin_case(c, o);
}

constexpr double kKelvinDeg = 19.471220634490691;  // arcsin(1/3)

std::vector<ValidationRow> kelvin_rows(const std::string& name, int n, double cells, std::vector<double> froudes) {
  std::vector<ValidationRow> rows;
  for (double fr : froudes) {
    const KelvinRunResult r = kelvin_run(fr, n, cells);
    const double u = fr * std::sqrt(9.81);
    const double lam = 2 * kPi * u * u / 9.81;
    rows.push_back(check(name, fmt("Fr %.1f n=%d: outer envelope half-angle (deg), |error| deg", fr, n),
                         r.wake.envelope_angle_deg, kKelvinDeg, std::abs(r.wake.envelope_angle_deg - kKelvinDeg), 0.5));
    rows.push_back(check(name, fmt("Fr %.1f n=%d: transverse wavelength (m), rel. error vs 2 pi U^2/g", fr, n),
                         r.wake.transverse_wavelength_m, lam, std::abs(r.wake.transverse_wavelength_m / lam - 1),
                         0.02));
  }
  return rows;
}

std::vector<ValidationRow> kelvin_case() { return kelvin_rows("kelvin", 512, 10, {0.3, 0.4, 0.5}); }

// Froude trend (Rabaud and Moisy 2013): for Fr >= 1 the angle of maximum amplitude falls as 1/Fr
// (checked as Fr * angle against the Fr = 1 value, within 15 %), while the outer envelope stays
// at 19.47 deg. The two angles live at different scales, so each is measured where it is resolved:
//  * max-amplitude angle: the short divergent waves (k ~ 1/L_hull) -- the run of 10 cells per
//    min(lambda, hull length) (dx = 0.1 m for Fr >= 1), as at Fr 0.3 to 1;
//  * outer envelope: the long cusp waves (k = 1.5 g/U^2) need >= 8 transverse wavelengths on the
//    grid (Fr 1 reads 19.87 deg on n = 512 with 8.2 wavelengths, 16.6 deg on n = 256 with 4.1).
//    When the fine grid is shorter (Fr 2: lambda = 25 m, Fr 3: 57 m against 51 m at n = 512), the
//    envelope run uses n cells of dx = 8.15 lambda / n (Fr 2: 0.40 m, Fr 3: 0.90 m at n = 512):
//    coarse against the 1 m hull, which only the short waves feel -- the envelope does not move
//    with dx (Fr 2: 19.463 deg at dx 0.2 m, 19.474 at 0.4 m; Fr 3: 19.463 at 0.44 m, 19.457 at
//    0.9 m, all at 8.15 wavelengths). The envelope run takes steps of 0.2 s (at most 2 cells of
//    hull motion): the ship kernels are exact for steady motion (ship_steps case), and Fr 1 reads
//    19.873, 19.862, 19.862 deg at dt = 0.032, 0.1, 0.2 s. For Fr >= 1 the envelope is read on
//    the field low-passed at 3 g/U^2 (kelvin.hpp WakeOptions::lowpass_k0): the short divergent
//    waves near the track carry the largest amplitude there and hide the cusp lobe (unfiltered,
//    Fr 2 reads 10.6 deg).
// At Fr >= 1 the profiles lie between a quarter and half of the distance travelled (1.6 to 3.2
// transverse wavelengths). Caveat, measured: at that range the method reads the exact steady wake
// (kelvin_test, Fr 2) at 18.6 deg, and 19.25 deg only at 5-20 wavelengths; the started ship's
// field reads higher (19.47 here, 19.01 at 3-6.4 wavelengths on a 16-wavelength grid), so part of
// the agreement at Fr 2 and 3 is the start transient offsetting that bias (docs/ocean.md,
// "Froude trend at Fr 2 and 3").
std::vector<ValidationRow> froude_rows(int n, std::vector<double> froudes) {
  std::vector<ValidationRow> rows;
  double ref = 0;
  constexpr double kLowpass = 3.0, kWavelengths = 8.15;
  for (double fr : froudes) {
    const double lowpass = fr >= 1.0 ? kLowpass : 0.0;
    const KelvinRunResult r = kelvin_run(fr, n, 10, 0.0, lowpass);
    const double amax = r.wake.max_amplitude_angle_deg;
    const double lam = 2 * kPi * fr * fr;
    const double dx_fine = r.grid.dx_m;
    double env = r.wake.envelope_angle_deg, dx_env = dx_fine;
    if (n * dx_fine < 8.0 * lam) {
      dx_env = kWavelengths * lam / n;
      env = kelvin_run(fr, n, 10, dx_env, lowpass, 0.2, 2.0).wake.envelope_angle_deg;
    }
    rows.push_back(check("froude_trend",
                         fmt("Fr %.1f: outer envelope half-angle (deg), |error| deg (n=%d, dx %.2f m = %.1f lambda%s)",
                             fr, n, dx_env, n * dx_env / lam, lowpass > 0 ? ", low-pass 3 g/U^2" : ""),
                         env, kKelvinDeg, std::abs(env - kKelvinDeg), 0.5));
    if (fr < 1.0) {
      rows.push_back(check("froude_trend", fmt("Fr %.1f: max-amplitude angle (deg), below the envelope", fr), amax,
                           kKelvinDeg, amax < kKelvinDeg ? 0.0 : amax - kKelvinDeg, 0.0));
    } else if (fr == 1.0) {
      ref = amax;
      rows.push_back(check("froude_trend",
                           fmt("Fr 1.0: max-amplitude angle (deg), below the envelope (dx %.2f m)", dx_fine), amax,
                           kKelvinDeg, amax < kKelvinDeg ? 0.0 : amax - kKelvinDeg, 0.0));
    } else {
      rows.push_back(
          check("froude_trend",
                fmt("Fr %.1f: Fr * max-amplitude angle (deg) vs Fr 1 value, rel. (1/Fr trend; dx %.2f m)", fr, dx_fine),
                fr * amax, ref, std::abs(fr * amax / ref - 1), 0.15));
    }
  }
  return rows;
}

std::vector<ValidationRow> froude_case() { return froude_rows(512, {0.3, 0.5, 1.0, 2.0, 3.0}); }

// Capillary-gravity threshold: a 1 cm x 1 cm x 1 mm source on a 1 mm grid (n = 512) brought to
// speed with a 0.5 s linear ramp; far-field (> 3 cm from the source) max |eta| at 0.20 m/s
// (below c_min = 0.231 m/s) over the same at 0.35 m/s. An abrupt start gives 0.092 (the start
// transient radiates), so the ramp is part of the case.
KelvinRunResult capillary_run(double speed, int n) {
  KelvinCase c;
  c.hull.length_m = 0.01;
  c.hull.beam_m = 0.01;
  c.hull.draft_m = 0.001;
  c.speed_mps = speed;
  c.n = n;
  c.dx_m = 0.001;
  c.margin = n / 10;
  c.dt_s = 0.05;
  c.ramp_s = 0.5;
  c.far_radius_m = 0.03;
  return run_kelvin_case(c);
}

std::vector<ValidationRow> capillary_rows(int n) {
  const KelvinRunResult slow = capillary_run(0.20, n), fast = capillary_run(0.35, n);
  const double ratio = slow.far_max_m / fast.far_max_m;
  return {check("capillary",
                fmt("n=%d: far max|eta| at 0.20 m/s / at 0.35 m/s (0.5 s ramp; %.3g / %.3g m)", n, slow.far_max_m,
                    fast.far_max_m),
                ratio, 0, ratio, 0.05)};
}

std::vector<ValidationRow> capillary_case() { return capillary_rows(512); }

// Ship steps through the integrated solver (HuygensSolver): the default hull at 1.2 m/s on a
// 32 m periodic grid; 8 steps of dt = 0.1 s against 16 of dt/2: relative L2 of the heights.
// A stationary hull: the wave energy after 40 steps relative to the moving hull's (float
// rounding only), and its spread over the run (bounded and constant).
std::string ship_scene(double dt, double x1, double t1, bool stokes) {
  return fmt(R"({"solver": "huygens", "grid": {"n": 256, "length_m": 32.0, "margin": 0, "cutoff": false},
  "time": {"dt_s": %.17g}, "stokes": %s,
  "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
             "path": [{"t_s": 0, "x_m": 6.0, "y_m": 16.2}, {"t_s": %.17g, "x_m": %.17g, "y_m": 16.2}]}]})",
             dt, stokes ? "true" : "false", t1, x1);
}

std::unique_ptr<HuygensSolver> solver_from(const std::string& text) {
  RunOptions o;
  o.measure_plans = false;
  return std::make_unique<HuygensSolver>(parse_huygens_scene(parse_scene_text(text), o));
}

std::vector<ValidationRow> ship_steps_case() {
  std::vector<ValidationRow> rows;
  const double dt = 0.1;
  auto a = solver_from(ship_scene(dt, 6.0 + 1.2 * 20, 20, false));
  auto b = solver_from(ship_scene(dt / 2, 6.0 + 1.2 * 20, 20, false));
  for (int s = 0; s < 8; ++s) {
    a->step();
    b->step();
    b->step();
  }
  double d2 = 0, r2 = 0;
  const auto ea = a->height(), eb = b->height();
  for (std::size_t i = 0; i < ea.size(); ++i) {
    d2 += double(ea[i] - eb[i]) * (ea[i] - eb[i]);
    r2 += double(ea[i]) * ea[i];
  }
  rows.push_back(check("ship_steps", "8 steps of dt=0.1 s vs 16 of dt/2 (solver, 1.2 m/s): rel. L2 of eta",
                       std::sqrt(d2 / r2), 0, std::sqrt(d2 / r2), 0.01));
  // stationary: a path with one point; moving reference as above
  auto still = solver_from(ship_scene(dt, 6.0, 20, false));
  auto moving = solver_from(ship_scene(dt, 6.0 + 1.2 * 20, 20, false));
  double emin = 1e300, emax = 0;
  for (int s = 0; s < 40; ++s) {
    still->step();
    moving->step();
    const double e = still->propagator().energy();
    emin = std::min(emin, e), emax = std::max(emax, e);
  }
  const double em = moving->propagator().energy();
  rows.push_back(
      check("ship_steps", "stationary hull, 40 steps: max wave energy / moving hull's", emax / em, 0, emax / em, 1e-8));
  rows.push_back(check("ship_steps", "stationary hull: (max - min) energy / moving hull's (constant)",
                       (emax - emin) / em, 0, (emax - emin) / em, 1e-8));
  return rows;
}

// Stokes through the solver: a plane wave k a = 0.1 (lambda = 1 m, on grid mode 8 of an 8 m
// periodic grid), 30 steps of dt = 0.05 s. Crest a(1 + ka/2), trough a(1 - ka/2) and the second
// harmonic k a^2 / 2 (the DFT of each row at 2 k0) within 2 %; first order symmetric.
std::vector<ValidationRow> stokes_case() {
  std::vector<ValidationRow> rows;
  const double lam = 1.0, k = 2 * kPi / lam, ka = 0.1, a = ka / k;
  for (bool stokes : {true, false}) {
    auto s = solver_from(fmt(R"({"solver": "huygens", "grid": {"n": 64, "length_m": 8.0, "margin": 0, "cutoff": false},
      "time": {"dt_s": 0.05}, "stokes": %s,
      "initial": [{"type": "plane_wave", "wavelength_m": 1.0, "amplitude_m": %.17g, "direction_deg": 0}]})",
                             stokes ? "true" : "false", a));
    for (int i = 0; i < 30; ++i) s->step();
    const auto e = s->height();
    const int n = 64;
    double hi = -1e9, lo = 1e9, h2 = 0;
    for (float v : e) hi = std::max(hi, double(v)), lo = std::min(lo, double(v));
    for (int r = 0; r < n; ++r) {
      std::complex<double> acc = 0;
      for (int c = 0; c < n; ++c)
        acc += double(e[static_cast<std::size_t>(r) * n + c]) * std::polar(1.0, -2 * kPi * 16 * c / n);
      h2 += 2 * std::abs(acc) / n / n;
    }
    if (stokes) {
      rows.push_back(check("stokes", "ka=0.1 (stokes on): crest height / a, rel. vs 1 + ka/2", hi / a, 1 + ka / 2,
                           std::abs(hi / a / (1 + ka / 2) - 1), 0.02));
      rows.push_back(check("stokes", "ka=0.1 (stokes on): trough depth / a, rel. vs 1 - ka/2", -lo / a, 1 - ka / 2,
                           std::abs(-lo / a / (1 - ka / 2) - 1), 0.02));
      rows.push_back(check("stokes", "ka=0.1 (stokes on): 2nd harmonic (m), rel. vs k a^2/2", h2, k * a * a / 2,
                           std::abs(h2 / (k * a * a / 2) - 1), 0.02));
    } else {
      rows.push_back(check("stokes", "stokes off: |crest - trough| / a (symmetric)", std::abs(hi + lo) / a, 0,
                           std::abs(hi + lo) / a, 1e-4));
      rows.push_back(
          check("stokes", "stokes off: 2nd harmonic / (k a^2/2)", h2 / (k * a * a / 2), 0, h2 / (k * a * a / 2), 1e-3));
    }
  }
  return rows;
}

// Interpolation through the solver: a wind sea (JONSWAP, 5 m/s, seed 1, 30 m, n = 64, Stokes on).
// Displayed frames j = 1, 2 of D = 3 after one full step of dt against a solver stepping dt/3;
// RMS error over the sweep dt = 0.16, 0.08, 0.04, 0.02 s, least-squares slope of log error vs
// log dt in [3.5, 4.5]; at the default dt = 3/60 s the RMS error is below 1 % of the RMS height.
std::string wind_scene(double dt, int per_step) {
  return fmt(R"({"solver": "huygens", "grid": {"n": 64, "length_m": 30.0, "margin": 0, "cutoff": false},
    "time": {"dt_s": %.17g, "display_per_step": %d}, "stokes": true,
    "wind": {"speed_mps": 5.0, "direction_deg": 0.0, "seed": 1}})",
             dt, per_step);
}

double interp_error(double dt, double& rms) {
  auto a = solver_from(wind_scene(dt, 3));
  auto b = solver_from(wind_scene(dt / 3, 1));
  a->step();
  double e2 = 0, h2 = 0;
  std::size_t cnt = 0;
  for (int j = 1; j <= 2; ++j) {
    b->step();
    const auto f = a->display_outputs(j);
    const auto t = b->height();
    for (std::size_t i = 0; i < t.size(); ++i) {
      e2 += double(f[0].data[i] - t[i]) * (f[0].data[i] - t[i]);
      h2 += double(t[i]) * t[i];
    }
    cnt += t.size();
  }
  rms = std::sqrt(h2 / cnt);
  return std::sqrt(e2 / cnt);
}

std::vector<ValidationRow> interpolation_case() {
  std::vector<ValidationRow> rows;
  std::vector<double> dts = {0.16, 0.08, 0.04, 0.02}, errs;
  double rms = 0;
  for (double dt : dts) errs.push_back(interp_error(dt, rms));
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < dts.size(); ++i) {
    const double x = std::log(dts[i]), y = std::log(errs[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double m = double(dts.size());
  const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  rows.push_back(check("interpolation",
                       fmt("wind sea: slope of log rms error vs log dt (dt 0.16..0.02 s; errors %.2g..%.2g m)",
                           errs.front(), errs.back()),
                       slope, 4.0, std::abs(slope - 4.0), 0.5));
  const double e = interp_error(0.05, rms);
  rows.push_back(
      check("interpolation", "wind sea, dt=0.05 s (3 x 1/60): rms error / rms height", e / rms, 0, e / rms, 0.01));
  return rows;
}

}  // namespace

std::vector<ValidationRow> kelvin_validation_rows(int n, double cells) {
  return kelvin_rows("kelvin", n, cells, {0.4});
}
std::vector<ValidationRow> capillary_validation_rows(int n) { return capillary_rows(n); }
std::vector<ValidationRow> froude_validation_rows(int n) { return froude_rows(n, {1.0, 2.0, 3.0}); }

std::vector<ValidationCase> huygens_validation_cases() {
  return {
      {"fft", "huygens", "FFT round trip and Parseval to float precision (256^2)", fft_case},
      {"phase_speed", "huygens", "plane waves after 1000 steps: phase speed and amplitude vs omega(k)/k", phase_case},
      {"cauchy_poisson", "huygens", "Gaussian ring wave vs the exact Hankel-transform solution (15 m, 512, M=64)",
       cauchy_poisson_case},
      {"group_velocity", "huygens", "packet energy centroid moves at c_g(k0)", group_cases},
      {"energy", "huygens", "discrete wave energy conserved with the cutoff off, 1e4 steps, dt 1/60 s and 1 s",
       energy_cases},
      {"absorption", "huygens", "15 m grid with the paper's cutoff vs a 60 m grid without (same dx)",
       [] { return absorption_case(0.0); }},
      {"absorption_tau", "huygens", "the same with the cutoff applied as (h h)^(dt/tau), tau = 1 s (dt-independent)",
       [] { return absorption_case(1.0); }},
      {"kelvin", "huygens", "Kelvin wake, Fr 0.3/0.4/0.5 (n=512): outer half-angle 19.47 deg, transverse 2 pi U^2/g",
       kelvin_case},
      {"froude_trend", "huygens", "Fr 0.3, 0.5, 1, 2, 3: envelope and max-amplitude angles; max angle ~ 1/Fr",
       froude_case},
      {"capillary", "huygens", "1 cm source below c_min (0.20 m/s) vs 0.35 m/s: far-field ratio < 5 %", capillary_case},
      {"ship_steps", "huygens", "ship: one step of dt = two of dt/2 (solver); stationary hull makes no waves",
       ship_steps_case},
      {"stokes", "huygens", "plane wave ka = 0.1 through the solver: Stokes crest, trough, 2nd harmonic", stokes_case},
      {"interpolation", "huygens", "wind sea: interpolated frames vs true steps, error ~ dt^4, < 1 % at dt 0.05 s",
       interpolation_case},
  };
}

}  // namespace huygens
