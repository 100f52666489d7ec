// Section "ships": the full step with ship, wind and Stokes (propagate, cutoff, ship, spectrum, wind, height
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
#include <ctime>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/common/time_interp.hpp"
#include "huygens/spectral/propagator.hpp"
#include "huygens/spectral/ship_waves.hpp"
#include "huygens/spectral/spectral_solver.hpp"
#include "huygens/spectral/stokes.hpp"
#include "huygens/spectral/wind.hpp"

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

Ship bench_ship(double length_m) {
  Ship s;
  s.path = ShipPath({{0.0, 0.3 * length_m, 0.5 * length_m}, {1e4, 0.3 * length_m + 1.2e4, 0.5 * length_m}});
  return s;
}

// The solver's step wired by hand on the public stages (the order of HuygensSolver::step).
struct Pipeline {
  Pipeline(const HuygensParams& hp, bool second, const WindParams& wp, int patch)
      : prop(hp),
        st(hp.water, hp.n, hp.length_m, second, PlanEffort::measure, hp.margin),
        sw(hp.water, hp.n, hp.length_m, patch, {bench_ship(hp.length_m)}, PlanEffort::measure),
        sea(wp, hp.water, hp.n, hp.length_m, hp.dt_s),
        eta(static_cast<std::size_t>(prop.visible_size()) * prop.visible_size()),
        etad(eta.size()),
        dt(hp.dt_s) {}
  void step() {
    const float inv = 1.0f / (static_cast<float>(prop.n()) * static_cast<float>(prop.n()));
    prop.propagate();
    prop.cutoff();
    sw.add(prop.field().data(), t, dt);
    prop.spectrum();
    sea.advance();
    st.compute(prop.spectrum_view().data(), inv, sea, eta.data(), etad.data());  // as HuygensSolver
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
};

// One row of the sweep: a grid size at a thread count, and the parameters every table shares.
struct ShipsCase {
  int n = 0, threads = 1, reps = 20, warm = 5, margin = 64;
  double dt = 0, len = 0;
  HuygensParams hp;
  WindParams wp;
  std::string ns, ts;  // n and threads as printed
};

ShipsCase ships_case(const Context& ctx, int n, int threads) {
  ShipsCase c;
  c.n = n;
  c.threads = threads;
  c.dt = 3.0 / 60.0;
  c.len = 15.0 * n / 512.0;                                        // dx = 15/512 m as in the default scene
  c.margin = 64;                                                   // the paper's M (patch 2M = 128)
  c.reps = ctx.quick ? 20 : (n <= 256 ? 80 : n <= 512 ? 40 : 20);  // blocks of 4 calls each
  c.wp.speed_mps = 6.0;
  c.wp.direction_deg = 20.0;
  c.wp.seed = 42;
  c.hp.n = n;
  c.hp.length_m = c.len;
  c.hp.margin = c.margin;
  c.hp.dt_s = c.dt;
  c.hp.water = Water{};
  c.hp.spatial = true;
  c.hp.check_every = 16;  // as a scene runs (the solver's default)
  c.hp.external_height = true;
  c.hp.effort = PlanEffort::measure;
  c.ns = std::to_string(n);
  c.ts = std::to_string(threads);
  return c;
}

std::string quartiles(const Paired& p) { return num(p.ratio_q(0.25), 3) + "-" + num(p.ratio_q(0.75), 3); }

// Stages, each paired with one raw inverse N x N transform (the height plan's problem).
void ships_stage_rows(const ShipsCase& c, Table& stages) {
  Pipeline twin1(c.hp, false, c.wp, 2 * c.margin);  // its first-order height plan is the unit
  auto unit = [&] { twin1.st.raw_transforms(); };
  auto stage_row = [&](const std::string& name, int transforms, const std::function<void()>& fn) {
    const Paired p = paired(c.warm, c.reps, fn, unit);
    stages.add({c.ns, c.ts, name, num(1e3 * median(p.wa), 3), std::to_string(transforms), num(1e3 * median(p.wb), 3),
                num(p.ratio(), 3), quartiles(p)});
  };
  Pipeline pl(c.hp, true, c.wp, 2 * c.margin);
  for (int i = 0; i < c.warm; ++i) pl.step();
  const float inv = 1.0f / (static_cast<float>(c.n) * static_cast<float>(c.n));
  stage_row("propagate (rotation + 1 IFFT)", 1, [&] { pl.prop.propagate(); });
  // the cutoff repeated on the same field would drive the margin into subnormals: time it
  // with the propagation that refills the field (its own cost is the difference)
  stage_row("propagate + cutoff", 1, [&] {
    pl.prop.propagate();
    pl.prop.cutoff();
  });
  stage_row(fmt("ship patch (P = %d, 1 ship)", 2 * c.margin), 0, [&] {
    pl.sw.add(pl.prop.field().data(), pl.t, c.dt);
    pl.t += c.dt;
  });
  stage_row("spectrum (1 FFT)", 1, [&] { pl.prop.spectrum(); });
  stage_row("wind advance", 0, [&] { pl.sea.advance(); });
  Pipeline p1(c.hp, false, c.wp, 2 * c.margin);
  for (int i = 0; i < c.warm; ++i) p1.step();
  stage_row("height, 1st order + wind", 1, [&] {
    p1.st.compute(pl.prop.spectrum_view().data(), inv, pl.sea.spectrum(), pl.eta.data(), pl.etad.data());
  });
  stage_row("height, 2nd-order Stokes + wind", 3, [&] {
    pl.st.compute(pl.prop.spectrum_view().data(), inv, pl.sea.spectrum(), pl.eta.data(), pl.etad.data());
  });
  AlignedBuffer<float> e1(pl.eta.size()), d1(pl.eta.size()), out(pl.eta.size());
  const HermiteWeights hw = hermite_weights(1, 3);
  stage_row("cubic interpolation (1 frame)", 0, [&] {
    hermite_interpolate(pl.eta.data(), pl.etad.data(), e1.data(), d1.data(), pl.eta.size(), hw, c.dt, out.data());
  });
}

// A step table row: step (a) against its raw transforms (b); `in_step` and the displayed frame
// (step plus two interpolated frames at display_per_step = 3) are "-" when not measured.
void add_step_row(const ShipsCase& c, Table& step, const std::string& name, const Paired& p, int tr,
                  const std::string& in_step, double t_between) {
  const double ts = median(p.wa);
  step.add({c.ns, c.ts, name, num(1e3 * ts, 3), num(1e3 * median(p.wb), 3), std::to_string(tr), num(p.ratio(), 3),
            quartiles(p), num(ts / median(p.wb), 3), num(median(p.ca) / median(p.cb), 3), in_step,
            t_between >= 0 ? num(1e3 * (ts + 2.0 * t_between) / 3.0, 3) : "-", num(tr / 3.0, 3),
            std::to_string(c.reps)});
}

// Composite full steps (first order, second-order Stokes) against their raw twins.
void ships_step_rows(const ShipsCase& c, Table& step) {
  for (const bool second : {false, true}) {
    Pipeline pl(c.hp, second, c.wp, 2 * c.margin), raw(c.hp, second, c.wp, 2 * c.margin);
    for (int i = 0; i < c.warm; ++i) pl.step();
    std::vector<double> in_step;
    std::uint64_t f0 = 0;
    const Paired p = paired(
        c.warm, c.reps,
        [&] {
          f0 = pl.fft_ns();
          const auto t0 = std::chrono::steady_clock::now();
          pl.step();
          in_step.push_back(seconds_since(t0) / (1e-9 * static_cast<double>(pl.fft_ns() - f0)));
        },
        [&] { raw.raw(); });
    double t_interp = -1.0;
    if (second) {
      AlignedBuffer<float> e1(pl.eta.size()), d1(pl.eta.size()), out(pl.eta.size());
      const HermiteWeights hw = hermite_weights(1, 3);
      t_interp = median_seconds(c.reps, [&] {
        hermite_interpolate(pl.eta.data(), pl.etad.data(), e1.data(), d1.data(), pl.eta.size(), hw, c.dt, out.data());
      });
    }
    add_step_row(c, step, second ? "ship + wind + 2nd-order Stokes" : "ship + wind + 1st order", p, pl.transforms(),
                 num(median(in_step), 3), t_interp);
  }
}

// The integrated solver (HuygensSolver from a scene: ship + wind + Stokes, display_per_step = 3):
// Solver::step and Solver::display_outputs(j), against a raw twin made from the solver's own
// parameters.
void ships_solver_row(const ShipsCase& c, Table& step) {
  const double len = c.len;
  const std::string text = fmt(R"({"solver": "huygens", "grid": {"n": %d, "length_m": %.17g, "margin": %d},
          "time": {"dt_s": %.17g, "display_per_step": 3}, "stokes": true,
          "wind": {"speed_mps": 6, "direction_deg": 20, "seed": 42},
          "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
                     "path": [{"t_s": 0, "x_m": %.17g, "y_m": %.17g}, {"t_s": 10000, "x_m": %.17g, "y_m": %.17g}]}]})",
                               c.n, len, c.margin, c.dt, 0.3 * len, 0.5 * len, 0.3 * len + 1.2e4, 0.5 * len);
  RunOptions ro;
  ro.measure_plans = true;
  // the round trip every step: the raw twin performs those transforms (the every-K steps are in
  // ships_scene_rows)
  HuygensScene scene = parse_huygens_scene(parse_scene_text(text), ro);
  scene.params.round_trip_every = 1;
  HuygensSolver solver(scene);
  const HuygensParams& sp = solver.scene().params;
  Pipeline raw(sp, true, c.wp, solver.scene().ship_patch);
  const Paired p = paired(
      c.warm, c.reps, [&] { solver.step(); }, [&] { raw.raw(); });
  const double t_disp = median_seconds(c.reps, [&] { (void)solver.display_outputs(1); });
  add_step_row(c, step, "HuygensSolver: ship + wind + 2nd-order Stokes", p,
               static_cast<int>(std::lround(solver.transforms_per_step())), "-", t_disp);
}

// The shipped scenes (default, ocean, kelvin) as HuygensSolver at n (the margin scaled with n, so
// the margin in metres and the automatic K stay), with the round trip every step (K = 1, before
// issue 37 item 2) and every K = grid.round_trip_every steps (automatic), alternated in blocks of
// K steps in one run. transforms/step is counted by the stages; step/raw = ms per step over
// transforms/step x one raw N x N c2c transform (an Fft2D of the same size, effort and threads).
void ships_scene_rows(const Context& ctx, int n, int threads, Table& t) {
  const double raw = [&] {
    AlignedBuffer<cfloat> b(static_cast<std::size_t>(n) * n);
    for (std::size_t i = 0; i < b.size(); ++i) b[i] = cfloat(1e-3f * static_cast<float>(i % 97), 0.0f);
    Fft2D f(n, n, b.data(), b.data(), Fft2D::backward, PlanEffort::measure);
    return median_seconds(ctx.quick ? 20 : 60, [&] { f.execute(); });
  }();
  for (const char* name : {"default", "ocean", "kelvin"}) {
    nlohmann::json j = nlohmann::json::parse(shipped_scene(std::string(name) + ".json"));
    j["grid"]["margin"] = j["grid"]["margin"].get<int>() * n / j["grid"]["n"].get<int>();
    j["grid"]["n"] = n;
    RunOptions ro;
    ro.measure_plans = true;
    std::unique_ptr<HuygensSolver> s[2];
    for (int v = 0; v < 2; ++v) {
      j["grid"]["round_trip_every"] = v == 0 ? 1 : 0;
      s[v] = std::make_unique<HuygensSolver>(parse_huygens_scene(parse_scene_text(j.dump()), ro));
    }
    const int k = s[1]->scene().params.round_trip_every, blocks = ctx.quick ? 6 : (n <= 512 ? 16 : 6);
    std::vector<double> ms[2];
    for (int b = 0; b < blocks; ++b)
      for (int v = 0; v < 2; ++v) {
        const auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < k; ++i) s[v]->step();
        ms[v].push_back(1e3 * seconds_since(t0) / k);
      }
    for (int v = 0; v < 2; ++v) {
      std::uint64_t tr = 0;
      for (const auto& st : s[v]->stats().all()) tr += st.transforms;
      const double per = static_cast<double>(tr) / (static_cast<double>(blocks) * k), m = median(ms[v]);
      t.add({std::to_string(n), std::to_string(threads), name, v == 0 ? "1 (every step)" : std::to_string(k), num(m, 3),
             num(per, 3), num(1e3 * raw, 3), num(m / (per * 1e3 * raw), 3), std::to_string(blocks * k)});
    }
  }
}

}  // namespace

void bench_ships(Context& ctx) {
  const std::vector<int> sizes = ctx.quick ? std::vector<int>{256, 512} : std::vector<int>{256, 512, 1024};
  const std::vector<int> thread_counts = ctx.threads.empty() ? std::vector<int>{omp_get_max_threads()} : ctx.threads;
  Table stages(
      {"n", "threads", "stage", "ms/call", "NxN transforms", "raw FFT ms", "stage / raw FFT", "pair ratio q25-q75"});
  Table step({"n", "threads", "pipeline", "ms/full step", "raw FFTs ms", "transforms/step", "step/raw (wall)",
              "q25-q75", "step/raw (ratio of medians)", "step/raw (CPU)", "step/in-step FFT", "ms/displayed frame",
              "transforms/frame", "reps"});
  Table scenes({"n", "threads", "scene", "round trip every", "ms/step", "transforms/step", "raw FFT ms",
                "step/raw transforms", "steps"});
  for (const int threads : thread_counts)
    for (int n : sizes) {
      // the same thread count for every plan and pass of this row (plans made after this)
      fft_set_threads(threads);
      omp_set_num_threads(threads);
      const ShipsCase c = ships_case(ctx, n, threads);
      ships_stage_rows(c, stages);
      ships_step_rows(c, step);
      ships_solver_row(c, step);
      if (n >= 512) ships_scene_rows(ctx, n, threads, scenes);
    }
  fft_set_threads(omp_get_num_procs());
  omp_set_num_threads(omp_get_num_procs());
  ctx.report("ships",
             "stages of a full ship + wind + Stokes step against one raw N x N inverse c2c transform (same plan), "
             "alternated; median wall ms, "
             "median of the per-pair ratios",
             stages);
  ctx.report("ships",
             "full step (propagate, cutoff, ship, spectrum, wind, height) against the raw FFTW transforms it performs "
             "(a raw twin with the same plans), alternated; median wall ms; step/raw = median of per-pair wall "
             "ratios (target <= 1.2); displayed frame at display_per_step = 3; paper 004 Table 1: 52 + 6 ms per "
             "displayed frame at n = 512 (Pentium 4, 2003)",
             step);
  ctx.report("ships",
             "shipped scenes (margin scaled with n) with the spatial round trip every step and every K = "
             "grid.round_trip_every steps (automatic), alternated in blocks of K steps; transforms/step counted by the "
             "stages; step/raw transforms = ms/step / (transforms/step x one raw N x N c2c transform)",
             scenes);
}

}  // namespace huygens::bench
