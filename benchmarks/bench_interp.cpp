// Section "interp": run time against error of the displayed frames (paper 004 section 3,
// docs/design.md 3.5). The display runs at 60 Hz; the solver takes full steps of dt = D / 60 s and
// fills the D - 1 frames in between by the cubic Hermite interpolant of eta and eta_dot
// (display_per_step = D). Reference: the same sea stepped at 1/60 s (the Huygens step is exact in
// time for the linear field, so D = 1 is the reference itself). For each D: time per displayed
// frame (the full step shared by D frames plus D - 1 interpolations, medians), the RMS error of the
// interpolated frames against the reference relative to the RMS height, and the same frames by
// linear interpolation between the two full steps (what a renderer without eta_dot could do).
// The Pareto front is marked over (time per frame, error) for both interpolants together.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bench.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"

namespace huygens::bench {

namespace {

std::string interp_scene(int n, int per_step) {
  return fmt(R"({"solver": "huygens", "grid": {"n": %d, "length_m": 60.0, "margin": 0, "cutoff": false},
    "time": {"dt_s": %.17g, "display_per_step": %d}, "stokes": true,
    "wind": {"speed_mps": 8.0, "direction_deg": 20.0, "seed": 7}})",
             n, per_step / 60.0, per_step);
}

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

void bench_interp(Context& ctx) {
  const std::vector<int> sizes = ctx.quick ? std::vector<int>{256} : std::vector<int>{256, 512};
  const int full_steps = ctx.quick ? 12 : 24;
  for (int n : sizes) {
    struct Row {
      int d;
      double ms_frame, cubic, linear, step_ms, interp_ms;
    };
    std::vector<Row> rows;
    Progress bar(fmt("interp n=%d", n), 7);
    int done = 0;
    for (int d : {1, 2, 3, 4, 6, 8, 12}) {
      RunOptions o;
      o.measure_plans = true;
      auto a = make_solver(parse_scene_text(interp_scene(n, d)), o);
      auto ref = make_solver(parse_scene_text(interp_scene(n, 1)), o);
      std::vector<double> t_step, t_interp;
      double e2c = 0, e2l = 0, h2 = 0;
      for (int k = 0; k < full_steps; ++k) {
        const std::vector<float> e0(a->height().begin(), a->height().end());
        const auto t0 = std::chrono::steady_clock::now();
        a->step();
        t_step.push_back(seconds_since(t0));
        const std::vector<float> e1(a->height().begin(), a->height().end());
        for (int j = 1; j < d; ++j) {
          ref->step();
          const auto t1 = std::chrono::steady_clock::now();
          const auto f = a->display_outputs(j);
          t_interp.push_back(seconds_since(t1));
          const auto r = ref->height();
          const double s = static_cast<double>(j) / d;
          for (std::size_t i = 0; i < r.size(); ++i) {
            const double lin = (1 - s) * e0[i] + s * e1[i];
            e2c += (double(f[0].data[i]) - r[i]) * (double(f[0].data[i]) - r[i]);
            e2l += (lin - r[i]) * (lin - r[i]);
            h2 += double(r[i]) * r[i];
          }
        }
        ref->step();  // the reference reaches the full step too
      }
      const double step_ms = median_of(t_step) * 1e3, interp_ms = median_of(t_interp) * 1e3;
      const double rms = d > 1 ? std::sqrt(h2) : 1.0;
      rows.push_back({d, (step_ms + (d - 1) * interp_ms) / d, d > 1 ? std::sqrt(e2c) / rms : 0.0,
                      d > 1 ? std::sqrt(e2l) / rms : 0.0, step_ms, interp_ms});
      bar.update(++done);
    }
    std::vector<double> time, err;
    for (const Row& r : rows) time.push_back(r.ms_frame), err.push_back(r.cubic);
    for (const Row& r : rows) time.push_back(r.ms_frame), err.push_back(r.linear);
    const std::vector<bool> front = pareto_front(time, err);
    Table t({"D", "dt s", "step ms", "interp ms", "ms/displayed frame", "cubic rms err / rms h", "Pareto",
             "linear rms err / rms h", "Pareto", "cubic gain"});
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const Row& r = rows[i];
      t.add({std::to_string(r.d), num(r.d / 60.0, 3), fmt("%.3f", r.step_ms), fmt("%.3f", r.interp_ms),
             fmt("%.3f", r.ms_frame), num(r.cubic, 3), front[i] ? "*" : "", num(r.linear, 3),
             front[rows.size() + i] ? "*" : "", r.d > 1 ? fmt("%.0fx", r.linear / r.cubic) : "-"});
    }
    ctx.report("interp",
               fmt("displayed frames at 60 Hz, wind sea 8 m/s with Stokes, n = %d, 60 m: run time against error "
                   "(reference: steps of 1/60 s; * = Pareto front)",
                   n),
               t);
    // the interpolant must be what it claims: better than linear at every D > 1, and within
    // the 1 % target at the default D = 3
    for (const Row& r : rows)
      if (r.d > 1) ctx.expect(r.cubic < r.linear, fmt("interp: cubic beats linear at D = %d (n = %d)", r.d, n));
    for (const Row& r : rows)
      if (r.d == 3) ctx.expect(r.cubic < 0.01, fmt("interp: D = 3 error below 1 %% of the rms height (n = %d)", n));
  }
}

}  // namespace huygens::bench
