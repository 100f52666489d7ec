// Section "accuracy": run time against error for the Huygens core next to the two baselines a
// user would otherwise pick, on the same problems, in the same run, on one thread each:
//   huygens         the propagator (paper 004 eq. 1, periodic: spectral rotation + height
//                   transform) stepping at dt = display_per_step / 60 s, the frames between steps
//                   made by the cubic Hermite interpolant (docs/design.md 3.5), 60 frames per second;
//   fd-leapfrog     eta_tt = c^2 lap eta, explicit (baseline_fd.hpp), at its CFL limit;
//   fd-kass-miller  the same equation with Kass and Miller's implicit ADI scheme (1990);
//   iwave           Tessendorf's 13 x 13 kernel for sqrt(-lap) (baseline_iwave.hpp).
// Problems (deep water, g = 9.81, surface tension 0.072 N/m, rho = 1000):
//   ring       Gaussian hump sigma 0.1 m, A 1 cm, released from rest at the centre of a periodic
//              16 m square; reference: the exact Cauchy-Poisson solution (cauchy_poisson.hpp) at
//              t = 1.6 s on the axis and diagonal rays through the centre, r < 3 m, every L/128;
//   plane      progressive plane wave lambda 1 m, A 1 cm, on a periodic 4 m square, t = 8 s
//              (10 periods); reference A cos(k x - omega t) at every cell;
//   capillary  the same at lambda 1 cm on a 4 cm square, t = 32/60 s (13 periods).
// Error: max |eta - reference| / A over the frames of the last step (Huygens: the interpolated
// frames too; the baselines' frames are their steps). Time: wall seconds per simulated second,
// median of 3 runs (1 when a run takes over 0.3 s), producing 60 frames per simulated second.
// FD's single speed c is the exact phase speed of the plane waves (the most generous choice a
// user could make) and, for the ring, the phase speed at k = 1/sigma (no single c fits a
// dispersive ring: this is where FD breaks). iWave is gravity-only (breaks on capillary waves).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "baseline_fd.hpp"
#include "baseline_iwave.hpp"
#include "bench.hpp"
#include "huygens/common/dispersion.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/common/time_interp.hpp"
#include "huygens/spectral/propagator.hpp"
#include "huygens/validation/reference/cauchy_poisson.hpp"

namespace huygens::bench {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFrameDt = 1.0 / 60.0;
constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Kind { ring, plane };

struct Problem {
  std::string name;
  Kind kind = Kind::ring;
  /// Side of the periodic square (unit: m) and simulated duration (unit: s).
  double length_m = 16.0, duration_s = 1.6;
  Water water;
  /// Ring: Gaussian sigma (unit: m); plane: wavelength (unit: m); both: amplitude (unit: m).
  double sigma_m = 0.1, wavelength_m = 1.0, amplitude_m = 0.01;
  /// Ring: spacing of the sample points on the rays (unit: m); n must be a multiple of L / sample_m.
  double sample_m = 0.0625;
  /// Speed the FD baseline uses (unit: m/s) and why.
  double fd_speed = 1.0;
  std::string fd_speed_note;
};

struct Result {
  std::string problem, method;
  int n = 0;
  std::string knob;
  double dt = 0, tps = kInf, err = kInf;
  std::string note;
};

// ---- the reference ---------------------------------------------------------------------------
class Reference {
 public:
  explicit Reference(const Problem& pb) : pb_(pb) {
    if (pb.kind == Kind::ring) {
      rays_ = static_cast<int>(std::lround(pb.length_m / pb.sample_m));
      const double h = pb.length_m / rays_;
      for (int a = 0; a * h < 3.0; ++a) pts_.push_back({a, 0});
      for (int a = 1; a * h * std::sqrt(2.0) < 3.0; ++a) pts_.push_back({a, a});
    }
  }
  /// Largest |reference| / A seen at the sample points (the size of what is being compared).
  double reference_max() const { return ref_max_; }

  /// max |eta - exact| / A over the sample points at frame f (t = f / 60 s).
  double error(std::span<const float> eta, int n, long frame) {
    const double t = frame * kFrameDt, amp = pb_.amplitude_m;
    double err = 0;
    if (pb_.kind == Kind::plane) {
      const double k = 2 * kPi / pb_.wavelength_m, om = omega(pb_.water, k), dx = pb_.length_m / n;
      std::vector<double> ex(static_cast<std::size_t>(n));
      for (int c = 0; c < n; ++c) ex[static_cast<std::size_t>(c)] = amp * std::cos(k * c * dx - om * t);
      ref_max_ = 1.0;
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
          err = std::max(err, std::abs(eta[static_cast<std::size_t>(r) * n + c] - ex[static_cast<std::size_t>(c)]));
      return std::isfinite(err) ? err / amp : kInf;
    }
    const int step = n / rays_, ic = n / 2;
    std::vector<double> ex(pts_.size());
    // the exact values at this frame (cached: shared by every method and grid)
    std::vector<std::size_t> todo;
    for (std::size_t i = 0; i < pts_.size(); ++i) {
      auto it = cache_.find({frame, key(pts_[i])});
      if (it == cache_.end())
        todo.push_back(i);
      else
        ex[i] = it->second;
    }
    CauchyPoissonGaussian g;
    g.water = pb_.water;
    g.sigma_m = pb_.sigma_m;
    g.amplitude_m = amp;
    g.rel_tolerance = 1e-9;
    const double h = pb_.length_m / rays_;
#pragma omp parallel for schedule(dynamic, 1) num_threads(omp_get_num_procs())
    for (long j = 0; j < static_cast<long>(todo.size()); ++j) {
      const auto& p = pts_[todo[static_cast<std::size_t>(j)]];
      ex[todo[static_cast<std::size_t>(j)]] = cauchy_poisson_eta(g, h * std::sqrt(double(key(p))), t);
    }
    for (std::size_t i : todo) cache_[{frame, key(pts_[i])}] = ex[i];
    for (std::size_t i = 0; i < pts_.size(); ++i) {
      ref_max_ = std::max(ref_max_, std::abs(ex[i]) / amp);
      const int r = ic + pts_[i].second * step, c = ic + pts_[i].first * step;
      err = std::max(err, std::abs(eta[static_cast<std::size_t>(r) * n + c] - ex[i]));
    }
    return std::isfinite(err) ? err / amp : kInf;
  }

  /// eta(0) and eta_t(0) sampled on an n x n grid (for the baselines).
  void initial(int n, std::vector<float>& eta0, std::vector<float>& etadot0) const {
    const double dx = pb_.length_m / n, L = pb_.length_m, amp = pb_.amplitude_m;
    eta0.assign(static_cast<std::size_t>(n) * n, 0.0f);
    etadot0.assign(eta0.size(), 0.0f);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const std::size_t i = static_cast<std::size_t>(r) * n + c;
        if (pb_.kind == Kind::ring) {
          // nearest periodic image of the centre
          const double x = std::remainder(c * dx - 0.5 * L, L), y = std::remainder(r * dx - 0.5 * L, L);
          eta0[i] = static_cast<float>(amp * std::exp(-(x * x + y * y) / (2 * pb_.sigma_m * pb_.sigma_m)));
        } else {
          const double k = 2 * kPi / pb_.wavelength_m, om = omega(pb_.water, k);
          eta0[i] = static_cast<float>(amp * std::cos(k * c * dx));
          etadot0[i] = static_cast<float>(amp * om * std::sin(k * c * dx));
        }
      }
  }

 private:
  static int key(const std::pair<int, int>& p) { return p.first * p.first + p.second * p.second; }
  const Problem& pb_;
  std::vector<std::pair<int, int>> pts_;  // (x, y) offsets from the centre in units of L / rays_
  int rays_ = 1;
  double ref_max_ = 0;
  std::map<std::pair<long, int>, double> cache_;
};

long frames_of(const Problem& pb) { return std::lround(pb.duration_s / kFrameDt); }

// Median of up to 3 timed runs; `run` returns its wall time and leaves the error for the last.
template <class Fn>
double timed(Fn&& run) {
  std::vector<double> t{run()};
  if (t[0] < 0.3) {
    t.push_back(run());
    t.push_back(run());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// ---- the runners -----------------------------------------------------------------------------
Result run_huygens(const Problem& pb, Reference& ref, int n, int dps) {
  Result res{pb.name, "huygens", n, "display_per_step=" + std::to_string(dps), dps * kFrameDt, kInf, kInf, ""};
  const long frames = frames_of(pb);
  if (frames % dps != 0) return res;
  HuygensParams p;
  p.n = n;
  p.length_m = pb.length_m;
  p.margin = 0;
  p.absorber = Absorber::off;
  p.dt_s = dps * kFrameDt;
  p.water = pb.water;
  p.effort = PlanEffort::measure;
  const long steps = frames / dps;
  const std::size_t nn = static_cast<std::size_t>(n) * n;
  AlignedBuffer<float> e0(nn), d0(nn), out(nn);
  std::unique_ptr<HuygensPropagator> prop;
  const double wall = timed([&] {
    prop = std::make_unique<HuygensPropagator>(p);
    if (pb.kind == Kind::ring)
      prop->add_gaussian(0.5 * pb.length_m, 0.5 * pb.length_m, pb.sigma_m, pb.amplitude_m);
    else
      prop->add_plane_wave(pb.wavelength_m, pb.amplitude_m, 0.0);
    prop->height();
    const auto t0 = std::chrono::steady_clock::now();
    for (long s = 0; s < steps; ++s) {
      if (dps > 1) {
        std::memcpy(e0.data(), prop->eta().data(), nn * sizeof(float));
        std::memcpy(d0.data(), prop->etadot().data(), nn * sizeof(float));
      }
      prop->step();
      for (int j = 1; j < dps; ++j)
        hermite_interpolate(e0.data(), d0.data(), prop->eta().data(), prop->etadot().data(), nn,
                            hermite_weights(j, dps), p.dt_s, out.data());
    }
    return seconds_since(t0);
  });
  res.tps = wall / pb.duration_s;
  // error over the frames of the last step (e0, d0 hold its start)
  double err = ref.error(prop->eta(), n, frames);
  for (int j = 1; j < dps; ++j) {
    hermite_interpolate(e0.data(), d0.data(), prop->eta().data(), prop->etadot().data(), nn, hermite_weights(j, dps),
                        p.dt_s, out.data());
    err = std::max(err, ref.error(out.span(), n, frames - dps + j));
  }
  res.err = err;
  return res;
}

Result run_fd(const Problem& pb, Reference& ref, int n, FdScheme scheme, int substeps_factor) {
  Result res{pb.name, scheme == FdScheme::leapfrog ? "fd-leapfrog" : "fd-kass-miller", n, "", 0, kInf, kInf, ""};
  FdParams p;
  p.n = n;
  p.length_m = pb.length_m;
  p.speed_mps = pb.fd_speed;
  p.scheme = scheme;
  int sub = substeps_factor;
  if (scheme == FdScheme::leapfrog) sub *= static_cast<int>(std::ceil(kFrameDt / fd_leapfrog_max_dt(p) - 1e-9));
  p.dt = kFrameDt / sub;
  res.dt = p.dt;
  res.knob = "substeps=" + std::to_string(sub);
  res.note = fmt("c=%.4g m/s, C=%.3g", p.speed_mps, p.speed_mps * p.dt / (p.length_m / n));
  const long steps = frames_of(pb) * sub;
  std::vector<float> e0, d0;
  ref.initial(n, e0, d0);
  std::unique_ptr<FdWave> fd;
  const double wall = timed([&] {
    fd = std::make_unique<FdWave>(p);
    fd->init(e0, d0);
    const auto t0 = std::chrono::steady_clock::now();
    for (long s = 0; s < steps; ++s) fd->step();
    return seconds_since(t0);
  });
  res.tps = wall / pb.duration_s;
  res.err = ref.error(fd->eta(), n, frames_of(pb));
  return res;
}

Result run_iwave(const Problem& pb, Reference& ref, int n, int substeps_factor) {
  Result res{pb.name, "iwave", n, "", 0, kInf, kInf, ""};
  IwaveParams p;
  p.n = n;
  p.length_m = pb.length_m;
  p.gravity = pb.water.gravity_mps2;
  int sub = 1;
  for (p.dt = kFrameDt; !iwave_params_error(p).empty() && sub < 4096; p.dt = kFrameDt / ++sub) {
  }
  sub *= substeps_factor;
  p.dt = kFrameDt / sub;
  res.dt = p.dt;
  res.knob = "substeps=" + std::to_string(sub);
  res.note = "gravity only, 13x13";
  const long steps = frames_of(pb) * sub;
  std::vector<float> e0, d0;
  ref.initial(n, e0, d0);
  std::unique_ptr<IwaveSolver> iw;
  const double wall = timed([&] {
    iw = std::make_unique<IwaveSolver>(p);
    iw->init(e0, d0);
    const auto t0 = std::chrono::steady_clock::now();
    for (long s = 0; s < steps; ++s) iw->step();
    return seconds_since(t0);
  });
  res.tps = wall / pb.duration_s;
  res.err = ref.error(iw->eta(), n, frames_of(pb));
  return res;
}

std::string err_str(double e) { return std::isfinite(e) ? num(e, 3) : "inf"; }
std::string time_str(double t) { return std::isfinite(t) ? num(t, 3) : "-"; }

const std::vector<std::string> kMethods = {"huygens", "fd-leapfrog", "fd-kass-miller", "iwave"};

// ---- the cases: each problem and the configurations swept on it ------------------------------
// Grid sizes per method (huygens: times display_per_step; Kass-Miller and iWave: times the
// substep factor).
struct Sweep {
  std::vector<int> huygens_n, fd_n, km_n, iw_n;
  std::vector<int> dps = {1, 4, 16}, km_sub = {1, 4}, iw_sub = {1, 4};
};

struct AccuracyCase {
  Problem pb;
  Sweep quick, full;
};

// Deep water, gravity-capillary (g = 9.81, 0.072 N/m, 1000 kg/m^3).
std::vector<AccuracyCase> accuracy_cases() {
  const Water w;
  const Problem ring{.name = "ring",
                     .water = w,
                     .fd_speed = phase_speed(w, 1.0 / Problem{}.sigma_m),
                     .fd_speed_note = "phase speed at k = 1/sigma"};
  const Problem plane{.name = "plane",
                      .kind = Kind::plane,
                      .length_m = 4.0,
                      .duration_s = 8.0,
                      .water = w,
                      .wavelength_m = 1.0,
                      .fd_speed = phase_speed(w, 2 * kPi / 1.0),
                      .fd_speed_note = "exact phase speed of the wave"};
  Problem cap = plane;
  cap.name = "capillary";
  cap.length_m = 0.04;
  cap.duration_s = 32 * kFrameDt;
  cap.wavelength_m = 0.01;
  cap.fd_speed = phase_speed(w, 2 * kPi / cap.wavelength_m);
  return {
      {ring,
       {.huygens_n = {256, 512}, .fd_n = {256, 512}, .km_n = {256}, .iw_n = {256}},
       {.huygens_n = {256, 512, 1024}, .fd_n = {256, 512, 1024}, .km_n = {256, 512}, .iw_n = {256, 512}}},
      {plane,
       {.huygens_n = {16, 64}, .fd_n = {64, 128, 256}, .km_n = {64, 128}, .iw_n = {64, 128}, .km_sub = {1, 16}},
       {.huygens_n = {16, 64, 256},
        .fd_n = {64, 128, 256, 512, 1024},
        .km_n = {64, 128, 256, 512},
        .iw_n = {64, 128, 256, 512},
        .km_sub = {1, 4, 16}}},
      {cap,
       {.huygens_n = {16, 64}, .fd_n = {64, 128}, .km_n = {64, 128}, .iw_n = {64, 128}, .iw_sub = {1}},
       {.huygens_n = {16, 64}, .fd_n = {64, 128, 256}, .km_n = {64, 128}, .iw_n = {64, 128}, .iw_sub = {1}}},
  };
}

// Every run of a sweep, in table order: huygens, fd-leapfrog, fd-kass-miller, iwave.
std::vector<Result> run_sweep(const Problem& pb, const Sweep& sw, Reference& ref) {
  std::vector<std::function<Result()>> runs;
  for (int n : sw.huygens_n)
    for (int d : sw.dps) runs.push_back([&, n, d] { return run_huygens(pb, ref, n, d); });
  for (int n : sw.fd_n) runs.push_back([&, n] { return run_fd(pb, ref, n, FdScheme::leapfrog, 1); });
  for (int n : sw.km_n)
    for (int s : sw.km_sub) runs.push_back([&, n, s] { return run_fd(pb, ref, n, FdScheme::kass_miller, s); });
  for (int n : sw.iw_n)
    for (int s : sw.iw_sub) runs.push_back([&, n, s] { return run_iwave(pb, ref, n, s); });
  Progress bar("accuracy " + pb.name, static_cast<long>(runs.size()));
  std::vector<Result> rs;
  for (const auto& run : runs) {
    rs.push_back(run());
    bar.update(static_cast<long>(rs.size()));
  }
  return rs;
}

// Every result of every problem, and each problem's largest |reference| / A.
struct Runs {
  std::vector<Result> all;
  std::map<std::string, double> ref_max;
  /// The cheapest run of method m on problem pbn with error <= target (time/sim s), or inf.
  double cheapest(const std::string& pbn, const std::string& m, double target) const {
    double best = kInf;
    for (const auto& r : all)
      if (r.problem == pbn && r.method == m && r.err <= target) best = std::min(best, r.tps);
    return best;
  }
};

// The accuracy checks: a table row each, a failure counted by the context.
struct Checks {
  Context& ctx;
  Table rows{{"check", "measured", "tolerance", "result"}};
  void operator()(bool ok, const std::string& what, double measured, const std::string& tol) {
    rows.add({what, err_str(measured), tol, ok ? "pass" : "FAIL"});
    ctx.expect(ok, "accuracy: " + what);
  }
};

void report_problem(Context& ctx, const Problem& pb, const std::vector<Result>& rs) {
  std::vector<double> ts, es;
  for (const auto& r : rs) {
    ts.push_back(r.tps);
    es.push_back(r.err);
  }
  const auto front = pareto_front(ts, es);
  Table t({"problem", "method", "n", "knob", "dt s", "time/sim s", "error", "pareto", "note"});
  for (std::size_t i = 0; i < rs.size(); ++i) {
    const auto& r = rs[i];
    t.add({r.problem, r.method, std::to_string(r.n), r.knob, num(r.dt, 4), time_str(r.tps), err_str(r.err),
           front[i] ? "*" : "", r.note});
  }
  std::string title = "run time against error, " + pb.name + " (";
  if (pb.kind == Kind::ring)
    title +=
        fmt("Cauchy-Poisson ring sigma %.2g m, %.0f m periodic, t = %.1f s", pb.sigma_m, pb.length_m, pb.duration_s);
  else
    title += fmt("plane wave lambda %.3g m, %.3g m periodic, t = %.1f s", pb.wavelength_m, pb.length_m, pb.duration_s);
  title += fmt("; FD c = %.4g m/s, %s; one thread; * = Pareto front)", pb.fd_speed, pb.fd_speed_note.c_str());
  ctx.report("accuracy", title, t);
}

// The Huygens core at display_per_step = 1 within the tolerance of `huygens validate` (1e-4 of
// A); the FD leapfrog a correct second-order scheme where its physics holds (plane waves).
void check_problem(Checks& check, const Problem& pb, const std::vector<Result>& rs) {
  for (const auto& r : rs) {
    if (r.method != "huygens" || r.knob != "display_per_step=1") continue;
    if (pb.kind == Kind::ring)
      check(r.err <= 1e-4, fmt("huygens ring n=%d dps=1: max error / A (exact Cauchy-Poisson)", r.n), r.err, "1e-4");
    else
      check(r.err <= 1e-4,
            fmt("huygens %s n=%d dps=1: max error / A after %.0f periods", pb.name.c_str(), r.n,
                pb.duration_s * omega(pb.water, 2 * kPi / pb.wavelength_m) / (2 * kPi)),
            r.err, "1e-4");
  }
  if (pb.name != "plane") return;
  std::vector<const Result*> lf;
  for (const auto& r : rs)
    if (r.method == "fd-leapfrog") lf.push_back(&r);
  for (std::size_t i = 1; i < lf.size(); ++i)
    if (lf[i - 1]->err > 1e-3)
      check(lf[i]->err < 0.5 * lf[i - 1]->err,
            fmt("fd-leapfrog plane converges: error n=%d / error n=%d", lf[i]->n, lf[i - 1]->n),
            lf[i]->err / lf[i - 1]->err, "< 0.5");
}

std::string reached(double t) { return std::isfinite(t) ? num(t, 3) : "not reached"; }
std::string ratio_str(double a, double b) { return std::isfinite(a) && std::isfinite(b) ? num(a / b, 3) : "-"; }

// Equal error: the cheapest configuration of each method that reaches a target.
void report_equal_error(Context& ctx, const std::vector<AccuracyCase>& cases, const Runs& runs) {
  Table eq({"problem", "target error", "huygens time/sim s", "fd-leapfrog", "fd-kass-miller", "iwave",
            "fd-leapfrog / huygens", "iwave / huygens"});
  for (const auto& c : cases)
    for (double target : {0.3, 0.1, 0.03, 0.01, 0.003, 0.001}) {
      const std::string& p = c.pb.name;
      if (target >= 0.5 * runs.ref_max.at(p)) continue;  // an error half the signal is no solution
      const double h = runs.cheapest(p, "huygens", target), f = runs.cheapest(p, "fd-leapfrog", target),
                   k = runs.cheapest(p, "fd-kass-miller", target), w = runs.cheapest(p, "iwave", target);
      eq.add({p, num(target, 2), time_str(h), reached(f), reached(k), reached(w), ratio_str(f, h), ratio_str(w, h)});
    }
  ctx.report("accuracy",
             "equal error: wall seconds per simulated second of the cheapest configuration reaching the target "
             "(targets below half the signal)",
             eq);
}

// The headline: the smallest error the FD leapfrog reached, and the cheapest Huygens run at or
// below it; an error as large as the signal itself is no solution (no ratio then).
void report_headline(Context& ctx, const std::vector<AccuracyCase>& cases, const Runs& runs) {
  Table hl({"problem", "error reached by both", "fd-leapfrog time/sim s", "huygens time/sim s", "fd / huygens"});
  for (const auto& c : cases) {
    const std::string& p = c.pb.name;
    double fd_best = kInf, fd_time = kInf;
    for (const auto& r : runs.all)
      if (r.problem == p && r.method == "fd-leapfrog" && r.err < fd_best) {
        fd_best = r.err;
        fd_time = r.tps;
      }
    const double h = runs.cheapest(p, "huygens", fd_best), ref = runs.ref_max.at(p);
    const std::string ratio =
        fd_best >= 0.5 * ref ? fmt("FD does not converge (its best error is %.0f%% of the signal)", 100 * fd_best / ref)
                             : ratio_str(fd_time, h);
    hl.add({p, err_str(fd_best), time_str(fd_time), time_str(h), ratio});
  }
  ctx.report("accuracy", "headline: Huygens vs finite differences at equal error (FD's best error; one thread each)",
             hl);
}

// Equal wall time: the smallest error each method reaches within 1, 10 and 100 times the
// cheapest Huygens run.
void report_equal_time(Context& ctx, const std::vector<AccuracyCase>& cases, const Runs& runs) {
  Table et({"problem", "budget time/sim s", "huygens error", "fd-leapfrog", "fd-kass-miller", "iwave"});
  for (const auto& c : cases) {
    const double hmin = runs.cheapest(c.pb.name, "huygens", kInf);
    for (double mult : {1.0, 10.0, 100.0}) {
      const double budget = hmin * mult;
      std::vector<std::string> row{c.pb.name, num(budget, 3)};
      for (const auto& m : kMethods) {
        double best = kInf;
        for (const auto& r : runs.all)
          if (r.problem == c.pb.name && r.method == m && r.tps <= budget) best = std::min(best, r.err);
        row.push_back(std::isfinite(best) ? num(best, 3) : "none that fast");
      }
      et.add(row);
    }
  }
  ctx.report("accuracy", "equal wall time: the smallest error each method reaches within the budget", et);
}

// Why a method stops improving on a problem.
std::string why_it_breaks(const std::string& m, const Problem& pb) {
  if (m == "huygens") return "exact dispersion; error = float rounding + interpolation";
  if (m.rfind("fd", 0) == 0)
    return pb.kind == Kind::ring ? "one speed c: a dispersive ring cannot be represented"
                                 : "c tuned to this wave; numerical dispersion O((k dx)^2)";
  return pb.name == "capillary" ? "gravity only: omega^2 = g k misses sigma k^3 / rho"
                                : "kernel taper exp(-k^2 dx^2) and truncation to 13 x 13";
}

// Where each breaks: the best error each method reaches on each problem.
void report_breaks(Context& ctx, const std::vector<AccuracyCase>& cases, const Runs& runs) {
  Table br({"problem", "max |reference| / A", "method", "best error", "at n", "knob", "time/sim s", "why"});
  for (const auto& c : cases)
    for (const auto& m : kMethods) {
      const Result* best = nullptr;
      for (const auto& r : runs.all)
        if (r.problem == c.pb.name && r.method == m && (!best || r.err < best->err)) best = &r;
      if (!best) continue;
      br.add({c.pb.name, num(runs.ref_max.at(c.pb.name), 3), m, err_str(best->err), std::to_string(best->n), best->knob,
              time_str(best->tps), why_it_breaks(m, c.pb)});
    }
  ctx.report("accuracy", "where each breaks: the best error each method reached on each problem", br);
}

// The iWave kernel's symbol along x against the exact operator k (Tessendorf's kernel and the
// same with the zero-sum change).
void report_iwave_symbol(Context& ctx) {
  IwaveParams ip;
  const auto g = iwave_kernel(ip);
  IwaveParams raw = ip;
  raw.zero_sum = true;
  const auto g_raw = iwave_kernel(raw);
  double sum_raw = 0;
  for (double v : g) sum_raw += v;
  Table ks(
      {"cells per wavelength", "k dx", "G^(k) / (k dx) (Tessendorf)", "with the zero-sum change", "omega error (%)"});
  for (double cpw : {64.0, 32.0, 16.0, 8.0, 4.0}) {
    const double kd = 2 * kPi / cpw;
    const double s = iwave_symbol(g, ip.half, kd), s_raw = iwave_symbol(g_raw, ip.half, kd);
    ks.add({num(cpw, 3), num(kd, 4), num(s / kd, 4), num(s_raw / kd, 4), num(100 * (std::sqrt(s / kd) - 1), 3)});
  }
  ctx.report("accuracy",
             fmt("iWave kernel symbol along x vs the exact k (sum of the 13x13 kernel = %.4f / cell)", sum_raw), ks);
}

}  // namespace

void bench_accuracy(Context& ctx) {
  // one thread for every method: the comparison is per core (FFTW plans made after this call)
  const int threads_before = omp_get_max_threads();
  fft_set_threads(1);
  omp_set_num_threads(1);
  const std::vector<AccuracyCase> cases = accuracy_cases();
  Runs runs;
  Checks check{ctx};
  for (const auto& c : cases) {
    Reference ref(c.pb);
    const std::vector<Result> rs = run_sweep(c.pb, ctx.quick ? c.quick : c.full, ref);
    report_problem(ctx, c.pb, rs);
    runs.ref_max[c.pb.name] = ref.reference_max();
    runs.all.insert(runs.all.end(), rs.begin(), rs.end());
    check_problem(check, c.pb, rs);
  }
  report_equal_error(ctx, cases, runs);
  report_headline(ctx, cases, runs);
  report_equal_time(ctx, cases, runs);
  report_breaks(ctx, cases, runs);
  report_iwave_symbol(ctx);
  ctx.report("accuracy", "accuracy checks", check.rows);
  fft_set_threads(threads_before);
  omp_set_num_threads(threads_before);
}

}  // namespace huygens::bench
