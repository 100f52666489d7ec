// Section "ships": the stages of issue 3 (ship patch, Stokes height, wind, cubic time
// interpolation) in units of one raw N x N FFTW transform measured in the same run,
// and a composite full step (propagator + ship + wind + second-order Stokes) with its cost per
// displayed frame at display_per_step = 3.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <functional>
#include <vector>

#include "bench.hpp"
#include "huygens/fft.hpp"
#include "huygens/huygens_propagator.hpp"
#include "huygens/huygens_solver.hpp"
#include "huygens/report.hpp"
#include "huygens/scene.hpp"
#include "huygens/ship_waves.hpp"
#include "huygens/stokes.hpp"
#include "huygens/time_interp.hpp"
#include "huygens/wind.hpp"

namespace huygens::bench {

namespace {

double process_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Median process CPU time of fn (all threads summed), after one warm-up. On a shared machine
// wall time includes the time other processes hold the cores; CPU time does not, so the
// ratios below use it (with one thread it is the wall time of an idle machine).
double median_cpu_seconds(int reps, const std::function<void()>& fn) {
  fn();
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const double t0 = process_cpu_seconds();
    fn();
    t.push_back(process_cpu_seconds() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

Ship bench_ship(double length_m) {
  Ship s;
  s.path = ShipPath({{0.0, 0.3 * length_m, 0.5 * length_m}, {1e4, 0.3 * length_m + 1.2e4, 0.5 * length_m}});
  return s;
}

}  // namespace

void bench_ships(Context& ctx) {
  const std::vector<int> sizes = ctx.quick ? std::vector<int>{256, 512} : std::vector<int>{512, 1024};
  const int reps = ctx.quick ? 5 : 15;
  const double dt = 3.0 / 60.0;
  Water water;
  Table stages({"n", "stage", "ms/call", "NxN transforms", "raw FFT ms", "stage time in raw FFTs"});
  Table step(
      {"n", "pipeline", "ms/full step", "transforms/step", "ms/displayed frame", "transforms/frame", "step/raw FFTs"});
  for (int n : sizes) {
    const double len = 15.0 * n / 512.0;  // dx = 15/512 m as in the default scene
    const int margin = 64;                // the paper's M (patch 2M = 128)
    const int vis = n - 2 * margin;
    const std::size_t nn = static_cast<std::size_t>(n) * n;

    // raw inverse N x N transform (the unit of all ratios)
    AlignedBuffer<cfloat> raw(nn);
    for (std::size_t i = 0; i < nn; ++i) raw[i] = cfloat(1e-3f * static_cast<float>(i % 97), 0.0f);
    Fft2D plan(n, n, raw.data(), raw.data(), Fft2D::backward, PlanEffort::measure);
    const double t_fft = median_cpu_seconds(reps, [&] { plan.execute(); });

    // ship patch stage (P = 2M), one ship moving steadily
    ShipWaves ships(water, n, len, 2 * margin, {bench_ship(len)}, PlanEffort::measure);
    AlignedBuffer<cfloat> z(nn);
    double t_ship_clock = 0.0;
    const double t_ship = median_cpu_seconds(reps, [&] {
      ships.add(z.data(), t_ship_clock, dt);
      t_ship_clock += dt;
    });
    stages.add({std::to_string(n), fmt("ship patch (P = %d, 1 ship)", 2 * margin), num(1e3 * t_ship, 3), "0",
                num(1e3 * t_fft, 3), num(t_ship / t_fft, 3)});

    // Stokes height: first and second order (visible region out), wind sea superposed
    WindParams wp;
    WindSea sea(wp, water, n, len, dt);
    std::vector<float> eta(static_cast<std::size_t>(vis) * vis), etad(eta.size());
    for (bool second : {false, true}) {
      StokesHeight st(water, n, len, second, PlanEffort::measure, margin);
      const double t =
          median_cpu_seconds(reps, [&] { st.compute(z.data(), 1.0f / nn, sea.spectrum(), eta.data(), etad.data()); });
      stages.add({std::to_string(n), second ? "height, 2nd-order Stokes (+ wind)" : "height, 1st order (+ wind)",
                  num(1e3 * t, 3), std::to_string(st.transforms_per_call()), num(1e3 * t_fft, 3), num(t / t_fft, 3)});
    }
    const double t_wind = median_cpu_seconds(reps, [&] { sea.advance(); });
    stages.add(
        {std::to_string(n), "wind advance", num(1e3 * t_wind, 3), "0", num(1e3 * t_fft, 3), num(t_wind / t_fft, 3)});

    // interpolation of one displayed frame over the visible region
    std::vector<float> e1(eta.size()), d1(eta.size()), out(eta.size());
    const HermiteWeights hw = hermite_weights(1, 3);
    const double t_interp = median_cpu_seconds(reps, [&] {
      hermite_interpolate(eta.data(), etad.data(), e1.data(), d1.data(), eta.size(), hw, dt, out.data());
    });
    stages.add({std::to_string(n), "cubic interpolation (1 frame)", num(1e3 * t_interp, 3), "0", num(1e3 * t_fft, 3),
                num(t_interp / t_fft, 3)});

    // composite full steps on the propagator
    HuygensParams hp;
    hp.n = n;
    hp.length_m = len;
    hp.margin = margin;
    hp.dt = dt;
    hp.water = water;
    hp.spatial = true;
    hp.check_every = 0;
    HuygensPropagator prop(hp);
    for (bool second : {false, true}) {
      StokesHeight st(water, n, len, second, PlanEffort::measure, margin);
      ShipWaves sw(water, n, len, 2 * margin, {bench_ship(len)}, PlanEffort::measure);
      double t_clock = 0.0;
      const double t_step = median_cpu_seconds(reps, [&] {
        prop.propagate();
        prop.cutoff();
        sw.add(prop.field().data(), t_clock, dt);
        prop.spectrum();
        st.compute(prop.spectrum_view().data(), 1.0f / nn, sea.spectrum(), eta.data(), etad.data());
        sea.advance();
        prop.end_step();
        t_clock += dt;
      });
      const int tr = 2 + st.transforms_per_call();
      // display_per_step = 3: one frame is the step's own, two are interpolated
      const double per_frame = (t_step + 2.0 * t_interp) / 3.0;
      step.add({std::to_string(n), second ? "ship + wind + 2nd-order Stokes" : "ship + wind + 1st order",
                num(1e3 * t_step, 3), std::to_string(tr), num(1e3 * per_frame, 3), num(tr / 3.0, 3),
                num(t_step / (tr * t_fft), 3)});
    }
    {
      // the same through the integrated solver (HuygensSolver from a scene: ship + wind +
      // Stokes, display_per_step = 3): Solver::step and Solver::display_outputs(j)
      const std::string text = fmt(R"({"solver": "huygens", "grid": {"n": %d, "length_m": %.17g, "margin": %d},
          "time": {"dt": %.17g, "display_per_step": 3}, "stokes": true,
          "wind": {"speed_mps": 6, "direction_deg": 20, "seed": 42},
          "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
                     "path": [{"t": 0, "x_m": %.17g, "y_m": %.17g}, {"t": 10000, "x_m": %.17g, "y_m": %.17g}]}]})",
                                   n, len, margin, dt, 0.3 * len, 0.5 * len, 0.3 * len + 1.2e4, 0.5 * len);
      HuygensSolver solver(parse_huygens_scene(parse_scene_text(text)));
      const double t_step = median_cpu_seconds(reps, [&] { solver.step(); });
      const double t_disp = median_cpu_seconds(reps, [&] { (void)solver.display_outputs(1); });
      const int tr = solver.transforms_per_step();
      const double per_frame = (t_step + 2.0 * t_disp) / 3.0;
      step.add({std::to_string(n), "HuygensSolver: ship + wind + 2nd-order Stokes", num(1e3 * t_step, 3),
                std::to_string(tr), num(1e3 * per_frame, 3), num(tr / 3.0, 3), num(t_step / (tr * t_fft), 3)});
    }
  }
  ctx.report("ships", "stages of issue 3 against one raw N x N inverse c2c transform (median process CPU ms)", stages);
  ctx.report("ships",
             "full step on the propagator (propagate, cutoff, ship, spectrum, height + wind; median process CPU ms); "
             "displayed frame at "
             "display_per_step = 3; paper 004 Table 1: 52 + 6 ms per displayed frame at n = 512 (Pentium 4, 2003)",
             step);
}

}  // namespace huygens::bench
