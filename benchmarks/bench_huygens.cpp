// Section "huygens": the propagator's full step against the raw FFTW transforms it performs
// (the same three plans, executed back to back on a second propagator of the same size),
// measured in the same run with the repeats interleaved. "in-step" columns time the FFTW
// executions inside each measured step itself, so the ratio compares the two on the very same
// step (robust on a shared, loaded machine). Plus a quick phase-speed accuracy check.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "bench.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/huygens/propagator.hpp"
#include "huygens/validation/validation.hpp"

namespace huygens::bench {

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

HuygensParams bench_params(int n) {
  HuygensParams p;
  p.n = n;
  p.length_m = 15.0 * n / 512.0;  // dx as in the default scene
  p.margin = n / 8;
  p.dt_s = 1.0 / 60.0;
  p.effort = PlanEffort::measure;
  return p;
}

}  // namespace

void bench_huygens(Context& ctx) {
  std::vector<int> sizes = {256, 512, 1024};
  if (ctx.quick) sizes.pop_back();
  Table t({"n", "threads", "step ms", "raw FFT ms", "ratio", "in-step FFT ms", "in-step ratio", "transforms/step",
           "non-FFT ms", "reps"});
  for (const int n : sizes) {
    for (const int threads : ctx.threads) {
      fft_set_threads(threads);
      omp_set_num_threads(threads);
      const HuygensParams p = bench_params(n);
      // the measured propagator carries a real wave field; the raw one (same plans, from
      // FFTW's wisdom) runs only the transforms, whose time does not depend on the data
      HuygensPropagator prop(p), raw(p);
      prop.add_gaussian(0.5 * p.length_m, 0.5 * p.length_m, 0.1, 0.01);
      prop.add_gaussian(0.3 * p.length_m, 0.6 * p.length_m, 0.05, -0.01);
      prop.height();
      const int reps = ctx.quick ? (n <= 256 ? 60 : 20) : (n <= 256 ? 300 : n <= 512 ? 120 : 30);
      for (int i = 0; i < 3; ++i) {
        prop.step();
        raw.raw_transforms();
      }
      std::vector<double> ts, tr, tf, ratio_in;
      for (int i = 0; i < reps; ++i) {
        const std::uint64_t f0 = prop.fft_ns();
        auto t0 = std::chrono::steady_clock::now();
        prop.step();
        ts.push_back(seconds_since(t0));
        tf.push_back((prop.fft_ns() - f0) * 1e-9);
        ratio_in.push_back(ts.back() / tf.back());
        t0 = std::chrono::steady_clock::now();
        raw.raw_transforms();
        tr.push_back(seconds_since(t0));
      }
      const double step = median(ts), fft = median(tr), fin = median(tf);
      const int tps = prop.transforms_per_step();
      t.add({std::to_string(n), std::to_string(threads), fmt("%.3f", step * 1e3), fmt("%.3f", fft * 1e3),
             fmt("%.3f", step / fft), fmt("%.3f", fin * 1e3), fmt("%.3f", median(ratio_in)), std::to_string(tps),
             fmt("%.3f", median(std::vector<double>(ts.begin(), ts.end())) * 1e3 - fin * 1e3), std::to_string(reps)});
    }
  }
  fft_set_threads(omp_get_num_procs());
  omp_set_num_threads(omp_get_num_procs());
  ctx.report("huygens", "full step (propagate, cutoff, spectrum, height) vs the raw FFTW transforms it performs", t);

  // accuracy next to the speed: the phase-speed validation case (1000 steps, four regimes)
  Table acc({"quantity", "measured", "expected", "error", "tolerance", "result"});
  for (const auto& c : huygens_validation_cases()) {
    if (c.name != "phase_speed") continue;
    for (const auto& r : c.run()) {
      acc.add({r.quantity, num(r.measured, 8), num(r.expected, 8), num(r.error, 3), num(r.tolerance, 3),
               r.pass ? "pass" : "FAIL"});
      ctx.expect(r.pass, "huygens phase speed: " + r.quantity);
    }
  }
  ctx.report("huygens", "phase speed after 1000 steps (accuracy check)", acc);
}

}  // namespace huygens::bench
