// Section "ships": the full step of issue 3 (propagate, cutoff, ship, spectrum, wind, height
// with second-order Stokes) against the raw FFTW transforms it performs, and its stages in
// units of one raw N x N transform; cost per displayed frame at display_per_step = 3.
//
// How the ratio is measured (docs/design.md 7), so that it can be trusted on a shared machine:
// * the baseline is a "raw twin": a second propagator and height stage of the same size and
//   parameters, whose plans are the step's own plans (same sizes, directions, in-/out-of-place,
//   alignment, flags and thread count: FFTW's in-process wisdom returns the same algorithm),
//   executing exactly the transforms the step performs and nothing else;
// * step and raw transforms alternate in short blocks (see paired()), so load changes on the
//   machine hit both alike while each runs in its own cache steady state; the reported ratio is
//   the median of the per-block ratios (its quartiles say how noisy the run was), next to the
//   ratio of the medians;
// * wall time (steady_clock) is the headline; process CPU time (all threads) is printed too;
// * "in-step" ratio: the step's wall time over the FFTW executions timed inside that same step
//   (same buffers, same cache state) -- a second, independent estimate of the same quantity;
// * the same thread count for every plan and pass of a row, set before any plan is made; one
//   row per thread count of --threads (default 1 and the machine's cores). With 2 threads on a
//   loaded 2-core machine every parallel region waits for its slowest thread, which hurts the
//   step (several regions) more than FFTW: the 1-thread rows are the less noisy ones there.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <ctime>
#include <functional>
#include <memory>
#include <numbers>
#include <vector>

#include "bench.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/huygens/propagator.hpp"
#include "huygens/huygens/solver.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/huygens/ship_waves.hpp"
#include "huygens/huygens/stokes.hpp"
#include "huygens/pipeline/time_interp.hpp"
#include "huygens/huygens/wind.hpp"

namespace huygens::bench {

namespace {

double cpu_now() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double x = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(x);
  const double f = x - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}
double median(const std::vector<double>& v) { return quantile(v, 0.5); }

// Wall and process CPU seconds of a and b, measured in alternating blocks: `block` calls of a,
// then `block` calls of b, `reps` times, after `warm` calls of each. The first call of each
// block lets the caches settle into that function's steady state (it is not counted); the
// block's time per call is the mean of the others. Each function is thus timed as it runs in
// a loop on its own (the raw transforms with their own buffers cached, as FFTW's back-to-back
// executions would be), while load changes on the machine still hit both alike.
struct Paired {
  std::vector<double> wa, wb, ca, cb;
  std::vector<double> ratios() const {
    std::vector<double> r(wa.size());
    for (std::size_t i = 0; i < r.size(); ++i) r[i] = wa[i] / wb[i];
    return r;
  }
  double ratio() const { return median(ratios()); }  // median of the per-block wall ratios a / b
  double ratio_q(double q) const { return quantile(ratios(), q); }
};
Paired paired(int warm, int reps, const std::function<void()>& a, const std::function<void()>& b, int block = 4) {
  for (int i = 0; i < warm; ++i) {
    a();
    b();
  }
  Paired p;
  for (int i = 0; i < reps; ++i) {
    for (int k = 0; k < 2; ++k) {
      const auto& fn = k == 0 ? a : b;
      fn();
      const double c0 = cpu_now();
      const auto t0 = std::chrono::steady_clock::now();
      for (int j = 1; j < block; ++j) fn();
      const double w = seconds_since(t0) / (block - 1), c = (cpu_now() - c0) / (block - 1);
      (k == 0 ? p.wa : p.wb).push_back(w);
      (k == 0 ? p.ca : p.cb).push_back(c);
    }
  }
  return p;
}

// ---- the previous implementation (HEAD before the speed work), kept as an in-run baseline ----
// A verbatim copy of the former StokesHeight::compute (full N x N tables, one pass for X and a
// second loop for chi/chidot per row, each row and its mirror read separately) and of the former
// WindSea::advance (a separate pass over the whole sea with a full N x N step table), so that
// "before" and "after" are timed in the same run on the same machine state.
struct HeadHeight {
  HeadHeight(const Water& water, int n, double length_m, bool second_order, int margin)
      : n_(n),
        m0_(margin),
        second(second_order),
        k(static_cast<std::size_t>(n) * n),
        kw(static_cast<std::size_t>(n) * n),
        sq(second_order ? static_cast<std::size_t>(n) * n : 0),
        x(static_cast<std::size_t>(n) * n),
        chi(second_order ? static_cast<std::size_t>(n) * n : 0),
        chid(second_order ? static_cast<std::size_t>(n) * n : 0),
        inverse(n, n, x.data(), x.data(), Fft2D::backward, PlanEffort::measure) {
    const double dk = 2.0 * std::numbers::pi / length_m;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const double kx = dk * (c < n / 2 ? c : c - n), ky = dk * (r < n / 2 ? r : r - n);
        const double kk = std::hypot(kx, ky);
        const std::size_t m = static_cast<std::size_t>(r) * n + c;
        const double om = omega(water, kk);
        k[m] = static_cast<float>(kk);
        kw[m] = kk > 0.0 ? static_cast<float>(kk / om) : 0.0f;
        if (second) sq[m] = static_cast<float>(std::sqrt(0.5 * kk));
      }
  }
  bool compute(const cfloat* zhat, float zscale, const cfloat* extra, float* eta, float* etadot) {
    const int n = n_;
    cfloat* X = x.data();
    cfloat* C = chi.data();
    cfloat* D = chid.data();
    const float* K = k.data();
    const float* KW = kw.data();
    const float* SQ = sq.data();
    const bool sec = second;
    const int m0 = m0_, v = n - 2 * m0_;

    // spectra: X = H[i k/omega Y] + i H[k Y]; chi^ = i (k/omega) sqrt(k/2) Y; chidot^ = k sqrt(k/2) Y.
    // With y = Y(k) = (a, b) and w = Y(-k) = (c, d) on interleaved floats:
    //   X = (-(m (b + d) + k (b - d)) / 2, (m (a - c) + k (a + c)) / 2),  m = k/omega,
    //   chi^ = m s (-b, a),  chidot^ = k s (a, b),  s = sqrt(k/2).
    const float* zf = reinterpret_cast<const float*>(zhat);
    const float* ef = reinterpret_cast<const float*>(extra);
    float* xf = reinterpret_cast<float*>(X);
    float* cf = reinterpret_cast<float*>(C);
    float* df = reinterpret_cast<float*>(D);
    const float zs = zscale;
    const bool has_extra = extra != nullptr;
#pragma omp parallel for schedule(static) if (n >= 256)
    for (int r = 0; r < n; ++r) {
      const int mr = (n - r) % n;
      const std::size_t o = static_cast<std::size_t>(r) * n, mo = static_cast<std::size_t>(mr) * n;
      const float* zu = zf + 2 * o;
      const float* zw = zf + 2 * mo;
      const float* eu = has_extra ? ef + 2 * o : nullptr;
      const float* ew = has_extra ? ef + 2 * mo : nullptr;
      float* xo = xf + 2 * o;
      const float* kk = K + o;
      const float* mm = KW + o;
      // column 0 is its own mirror; columns 1..n-1 mirror to n - c (a reversed run GCC vectorises)
      auto one = [&](int c, int cn) {
        float a = zs * zu[2 * c], b = zs * zu[2 * c + 1], cc = zs * zw[2 * cn], d = zs * zw[2 * cn + 1];
        if (has_extra) {
          a += eu[2 * c];
          b += eu[2 * c + 1];
          cc += ew[2 * cn];
          d += ew[2 * cn + 1];
        }
        const float m = mm[c], k = kk[c];
        xo[2 * c] = -0.5f * (m * (b + d) + k * (b - d));
        xo[2 * c + 1] = 0.5f * (m * (a - cc) + k * (a + cc));
      };
      one(0, 0);
      if (has_extra) {
#pragma omp simd
        for (int c = 1; c < n; ++c) {
          const int cn = n - c;
          const float a = zs * zu[2 * c] + eu[2 * c], b = zs * zu[2 * c + 1] + eu[2 * c + 1];
          const float cc = zs * zw[2 * cn] + ew[2 * cn], d = zs * zw[2 * cn + 1] + ew[2 * cn + 1];
          const float m = mm[c], k = kk[c];
          xo[2 * c] = -0.5f * (m * (b + d) + k * (b - d));
          xo[2 * c + 1] = 0.5f * (m * (a - cc) + k * (a + cc));
        }
      } else {
#pragma omp simd
        for (int c = 1; c < n; ++c) {
          const int cn = n - c;
          const float a = zs * zu[2 * c], b = zs * zu[2 * c + 1], cc = zs * zw[2 * cn], d = zs * zw[2 * cn + 1];
          const float m = mm[c], k = kk[c];
          xo[2 * c] = -0.5f * (m * (b + d) + k * (b - d));
          xo[2 * c + 1] = 0.5f * (m * (a - cc) + k * (a + cc));
        }
      }
      if (sec) {
        const float* sq = SQ + o;
        float* co = cf + 2 * o;
        float* dq = df + 2 * o;
#pragma omp simd
        for (int c = 0; c < n; ++c) {
          float a = zs * zu[2 * c], b = zs * zu[2 * c + 1];
          if (has_extra) {
            a += eu[2 * c];
            b += eu[2 * c + 1];
          }
          const float ms = mm[c] * sq[c], ks = kk[c] * sq[c];
          co[2 * c] = -ms * b;
          co[2 * c + 1] = ms * a;
          dq[2 * c] = ks * a;
          dq[2 * c + 1] = ks * b;
        }
      }
    }
    inverse.execute();
    // outputs with a fused non-finite test (x - x is non-zero only for NaN or inf)
    float acc = 0.0f;
    if (!sec) {
#pragma omp parallel for schedule(static) if (n >= 256) reduction(+ : acc)
      for (int r = 0; r < v; ++r) {
        const std::size_t o = static_cast<std::size_t>(r + m0) * n + m0, q = static_cast<std::size_t>(r) * v;
        const float* xs = reinterpret_cast<const float*>(X + o);
#pragma omp simd reduction(+ : acc)
        for (int c = 0; c < v; ++c) {
          eta[q + c] = xs[2 * c];
          etadot[q + c] = xs[2 * c + 1];
          acc += (xs[2 * c] - xs[2 * c]) + (xs[2 * c + 1] - xs[2 * c + 1]);
        }
      }
      return acc == 0.0f;
    }
    inverse.execute(C, C);
    inverse.execute(D, D);
#pragma omp parallel for schedule(static) if (n >= 256) reduction(+ : acc)
    for (int r = 0; r < v; ++r) {
      const std::size_t o = static_cast<std::size_t>(r + m0) * n + m0, q = static_cast<std::size_t>(r) * v;
      const float* xs = reinterpret_cast<const float*>(X + o);
      const float* cs = reinterpret_cast<const float*>(C + o);
      const float* ds = reinterpret_cast<const float*>(D + o);
#pragma omp simd reduction(+ : acc)
      for (int c = 0; c < v; ++c) {
        const float cr = cs[2 * c], ci = cs[2 * c + 1], dr = ds[2 * c], di = ds[2 * c + 1];
        const float e = xs[2 * c] + cr * cr - ci * ci, d = xs[2 * c + 1] + 2.0f * (cr * dr - ci * di);
        eta[q + c] = e;
        etadot[q + c] = d;
        acc += (e - e) + (d - d);
      }
    }
    return acc == 0.0f;
  }
  int n_, m0_;
  bool second;
  AlignedBuffer<float> k, kw, sq;
  AlignedBuffer<cfloat> x, chi, chid;
  Fft2D inverse;
};

struct HeadWind {
  HeadWind(const WindSea& sea, const Water& water, int n, double length_m, double dt)
      : sea_(sea), cur(static_cast<std::size_t>(n) * n), step(static_cast<std::size_t>(n) * n) {
    const double dk = 2.0 * std::numbers::pi / length_m;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const double om = omega(water, std::hypot(dk * (c < n / 2 ? c : c - n), dk * (r < n / 2 ? r : r - n)));
        step[static_cast<std::size_t>(r) * n + c] = cfloat(std::exp(std::complex<double>(0.0, -om * dt)));
      }
    sea.spectrum_at(0.0, cur.data());
    dt_ = dt;
  }
  void advance() {
    ++steps_;
    if (steps_ % 256 == 0) {
      sea_.spectrum_at(static_cast<double>(steps_) * dt_, cur.data());
      return;
    }
    const std::size_t total = cur.size();
    float* c = reinterpret_cast<float*>(cur.data());
    const float* st = reinterpret_cast<const float*>(step.data());
#pragma omp parallel for simd schedule(static) if (total > 65536)
    for (std::size_t m = 0; m < total; ++m) {
      const float a = c[2 * m], b = c[2 * m + 1], cc = st[2 * m], d = st[2 * m + 1];
      c[2 * m] = a * cc - b * d;
      c[2 * m + 1] = a * d + b * cc;
    }
  }
  const WindSea& sea_;
  AlignedBuffer<cfloat> cur, step;
  double dt_ = 0.0;
  long long steps_ = 0;
};

Ship bench_ship(double length_m) {
  Ship s;
  s.path = ShipPath({{0.0, 0.3 * length_m, 0.5 * length_m}, {1e4, 0.3 * length_m + 1.2e4, 0.5 * length_m}});
  return s;
}

// The solver's step wired by hand on the public stages (the order of HuygensSolver::step).
struct Pipeline {
  Pipeline(const HuygensParams& hp, bool second, const WindParams& wp, int patch, bool head_stages = false)
      : prop(hp),
        st(hp.water, hp.n, hp.length_m, second, PlanEffort::measure, hp.margin),
        sw(hp.water, hp.n, hp.length_m, patch, {bench_ship(hp.length_m)}, PlanEffort::measure),
        sea(wp, hp.water, hp.n, hp.length_m, hp.dt),
        eta(static_cast<std::size_t>(prop.visible_size()) * prop.visible_size()),
        etad(eta.size()),
        dt(hp.dt) {
    if (head_stages) {
      head = std::make_unique<HeadHeight>(hp.water, hp.n, hp.length_m, second, hp.margin);
      head_wind = std::make_unique<HeadWind>(sea, hp.water, hp.n, hp.length_m, hp.dt);
    }
  }
  void step() {
    const float inv = 1.0f / (static_cast<float>(prop.n()) * static_cast<float>(prop.n()));
    prop.propagate();
    prop.cutoff();
    sw.add(prop.field().data(), t, dt);
    prop.spectrum();
    if (head) {
      head_wind->advance();
      head->compute(prop.spectrum_view().data(), inv, head_wind->cur.data(), eta.data(), etad.data());
    } else {
      sea.advance();
      st.compute(prop.spectrum_view().data(), inv, sea, eta.data(), etad.data());  // as HuygensSolver
    }
    prop.end_step();
    t += dt;
  }
  // exactly the N x N transforms step() performs (on this object's buffers)
  void raw() {
    prop.raw_transforms();
    st.raw_transforms();
  }
  std::uint64_t fft_ns() const { return prop.fft_ns() + st.fft_ns(); }
  int transforms() const { return prop.transforms_per_step() + st.transforms_per_call(); }

  HuygensPropagator prop;
  StokesHeight st;
  ShipWaves sw;
  WindSea sea;
  AlignedBuffer<float> eta, etad;
  double dt, t = 0.0;
  std::unique_ptr<HeadHeight> head;  // the previous height and wind stages (in-run baseline)
  std::unique_ptr<HeadWind> head_wind;
};

}  // namespace

void bench_ships(Context& ctx) {
  const std::vector<int> sizes = ctx.quick ? std::vector<int>{256, 512} : std::vector<int>{256, 512, 1024};
  const std::vector<int> thread_counts = ctx.threads.empty() ? std::vector<int>{omp_get_max_threads()} : ctx.threads;
  const double dt = 3.0 / 60.0;
  Water water;
  WindParams wp;
  wp.speed_mps = 6.0;
  wp.direction_deg = 20.0;
  wp.seed = 42;
  Table stages(
      {"n", "threads", "stage", "ms/call", "NxN transforms", "raw FFT ms", "stage / raw FFT", "pair ratio q25-q75"});
  Table step({"n", "threads", "pipeline", "ms/full step", "raw FFTs ms", "transforms/step", "step/raw (wall)",
              "q25-q75", "step/raw (ratio of medians)", "step/raw (CPU)", "step/in-step FFT", "ms/displayed frame",
              "transforms/frame", "reps"});
  Table ab({"n", "threads", "ms/step now", "ms/step previous stages", "now / previous", "q25-q75", "reps"});
  for (const int threads : thread_counts)
    for (int n : sizes) {
      // the same thread count for every plan and pass of this row (plans made after this)
      fft_set_threads(threads);
      omp_set_num_threads(threads);
      const double len = 15.0 * n / 512.0;                                     // dx = 15/512 m as in the default scene
      const int margin = 64;                                                   // the paper's M (patch 2M = 128)
      const int reps = ctx.quick ? 20 : (n <= 256 ? 80 : n <= 512 ? 40 : 20);  // blocks of 4 calls each
      const int warm = 5;
      HuygensParams hp;
      hp.n = n;
      hp.length_m = len;
      hp.margin = margin;
      hp.dt = dt;
      hp.water = water;
      hp.spatial = true;
      hp.check_every = 16;  // as a scene runs (the solver's default)
      hp.external_height = true;
      hp.effort = PlanEffort::measure;
      const std::string ns = std::to_string(n);

      // ---- stages, each paired with one raw inverse N x N transform (the height plan's problem)
      Pipeline twin1(hp, false, wp, 2 * margin);  // its first-order height plan is the unit
      auto unit = [&] { twin1.st.raw_transforms(); };
      auto stage_row = [&](const std::string& name, int transforms, const std::function<void()>& fn) {
        const Paired p = paired(warm, reps, fn, unit);
        stages.add({ns, std::to_string(threads), name, num(1e3 * median(p.wa), 3), std::to_string(transforms),
                    num(1e3 * median(p.wb), 3), num(p.ratio(), 3),
                    num(p.ratio_q(0.25), 3) + "-" + num(p.ratio_q(0.75), 3)});
      };
      {
        Pipeline pl(hp, true, wp, 2 * margin);
        for (int i = 0; i < warm; ++i) pl.step();
        const float inv = 1.0f / (static_cast<float>(n) * static_cast<float>(n));
        stage_row("propagate (rotation + 1 IFFT)", 1, [&] { pl.prop.propagate(); });
        // the cutoff repeated on the same field would drive the margin into subnormals: time it
        // with the propagation that refills the field (its own cost is the difference)
        stage_row("propagate + cutoff", 1, [&] {
          pl.prop.propagate();
          pl.prop.cutoff();
        });
        stage_row(fmt("ship patch (P = %d, 1 ship)", 2 * margin), 0, [&] {
          pl.sw.add(pl.prop.field().data(), pl.t, dt);
          pl.t += dt;
        });
        stage_row("spectrum (1 FFT)", 1, [&] { pl.prop.spectrum(); });
        stage_row("wind advance", 0, [&] { pl.sea.advance(); });
        Pipeline p1(hp, false, wp, 2 * margin);
        for (int i = 0; i < warm; ++i) p1.step();
        stage_row("height, 1st order + wind", 1, [&] {
          p1.st.compute(pl.prop.spectrum_view().data(), inv, pl.sea.spectrum(), pl.eta.data(), pl.etad.data());
        });
        stage_row("height, 2nd-order Stokes + wind", 3, [&] {
          pl.st.compute(pl.prop.spectrum_view().data(), inv, pl.sea.spectrum(), pl.eta.data(), pl.etad.data());
        });
        AlignedBuffer<float> e1(pl.eta.size()), d1(pl.eta.size()), out(pl.eta.size());
        const HermiteWeights hw = hermite_weights(1, 3);
        stage_row("cubic interpolation (1 frame)", 0, [&] {
          hermite_interpolate(pl.eta.data(), pl.etad.data(), e1.data(), d1.data(), pl.eta.size(), hw, dt, out.data());
        });
      }

      // ---- composite full steps against their raw twins; "previous stages" = the same step with
      // the former height and wind stages (HeadHeight, HeadWind), as an in-run before/after
      double t_interp = 0.0;
      for (int variant = 0; variant < 3; ++variant) {
        const bool second = variant >= 1, head = variant == 2;
        Pipeline pl(hp, second, wp, 2 * margin, head), raw(hp, second, wp, 2 * margin);
        for (int i = 0; i < warm; ++i) pl.step();
        std::vector<double> in_step;
        std::uint64_t f0 = 0;
        const Paired p = paired(
            warm, reps,
            [&] {
              f0 = pl.fft_ns();
              const auto t0 = std::chrono::steady_clock::now();
              pl.step();
              if (!head) in_step.push_back(seconds_since(t0) / (1e-9 * static_cast<double>(pl.fft_ns() - f0)));
            },
            [&] { raw.raw(); });
        if (variant == 1) {
          AlignedBuffer<float> e1(pl.eta.size()), d1(pl.eta.size()), out(pl.eta.size());
          const HermiteWeights hw = hermite_weights(1, 3);
          t_interp = median_seconds(reps, [&] {
            hermite_interpolate(pl.eta.data(), pl.etad.data(), e1.data(), d1.data(), pl.eta.size(), hw, dt, out.data());
          });
        }
        const int tr = pl.transforms();
        const double ts = median(p.wa);
        const std::string name = head     ? "previous stages: ship + wind + 2nd-order Stokes"
                                 : second ? "ship + wind + 2nd-order Stokes"
                                          : "ship + wind + 1st order";
        step.add({ns, std::to_string(threads), name, num(1e3 * ts, 3), num(1e3 * median(p.wb), 3), std::to_string(tr),
                  num(p.ratio(), 3), num(p.ratio_q(0.25), 3) + "-" + num(p.ratio_q(0.75), 3), num(ts / median(p.wb), 3),
                  num(median(p.ca) / median(p.cb), 3), head ? "-" : num(median(in_step), 3),
                  second ? num(1e3 * (ts + 2.0 * t_interp) / 3.0, 3) : "-", num(tr / 3.0, 3), std::to_string(reps)});
      }
      {
        // before/after directly: the current step against the previous stages' step, alternated
        Pipeline now(hp, true, wp, 2 * margin), before(hp, true, wp, 2 * margin, true);
        const Paired p = paired(
            warm, reps, [&] { now.step(); }, [&] { before.step(); });
        ab.add({ns, std::to_string(threads), num(1e3 * median(p.wa), 3), num(1e3 * median(p.wb), 3), num(p.ratio(), 3),
                num(p.ratio_q(0.25), 3) + "-" + num(p.ratio_q(0.75), 3), std::to_string(reps)});
      }
      {
        // the integrated solver (HuygensSolver from a scene: ship + wind + Stokes,
        // display_per_step = 3): Solver::step and Solver::display_outputs(j), against a raw twin
        // made from the solver's own parameters
        const std::string text = fmt(R"({"solver": "huygens", "grid": {"n": %d, "length_m": %.17g, "margin": %d},
          "time": {"dt": %.17g, "display_per_step": 3}, "stokes": true,
          "wind": {"speed_mps": 6, "direction_deg": 20, "seed": 42},
          "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
                     "path": [{"t": 0, "x_m": %.17g, "y_m": %.17g}, {"t": 10000, "x_m": %.17g, "y_m": %.17g}]}]})",
                                     n, len, margin, dt, 0.3 * len, 0.5 * len, 0.3 * len + 1.2e4, 0.5 * len);
        RunOptions ro;
        ro.measure_plans = true;
        HuygensSolver solver(parse_huygens_scene(parse_scene_text(text), ro));
        const HuygensParams& sp = solver.scene().params;
        Pipeline raw(sp, true, wp, solver.scene().ship_patch);
        const Paired p = paired(
            warm, reps, [&] { solver.step(); }, [&] { raw.raw(); });
        const double t_disp = median_seconds(reps, [&] { (void)solver.display_outputs(1); });
        const int tr = solver.transforms_per_step();
        const double ts = median(p.wa);
        step.add({ns, std::to_string(threads), "HuygensSolver: ship + wind + 2nd-order Stokes", num(1e3 * ts, 3),
                  num(1e3 * median(p.wb), 3), std::to_string(tr), num(p.ratio(), 3),
                  num(p.ratio_q(0.25), 3) + "-" + num(p.ratio_q(0.75), 3), num(ts / median(p.wb), 3),
                  num(median(p.ca) / median(p.cb), 3), "-", num(1e3 * (ts + 2.0 * t_disp) / 3.0, 3), num(tr / 3.0, 3),
                  std::to_string(reps)});
      }
    }
  fft_set_threads(omp_get_num_procs());
  omp_set_num_threads(omp_get_num_procs());
  ctx.report("ships",
             "stages of issue 3 against one raw N x N inverse c2c transform (same plan), alternated; median wall ms, "
             "median of the per-pair ratios",
             stages);
  ctx.report("ships",
             "full step (propagate, cutoff, ship, spectrum, wind, height) against the raw FFTW transforms it performs "
             "(a raw twin with the same plans), alternated; median wall ms; step/raw = median of per-pair wall "
             "ratios (target <= 1.2); displayed frame at display_per_step = 3; paper 004 Table 1: 52 + 6 ms per "
             "displayed frame at n = 512 (Pentium 4, 2003)",
             step);
  ctx.report("ships",
             "before/after in one run: the step (ship + wind + 2nd-order Stokes) with the current height and wind "
             "stages against the same step with the previous ones (copied into this file), alternated",
             ab);
}

}  // namespace huygens::bench
