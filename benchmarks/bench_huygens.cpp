// Section "huygens": the propagator's full step against the raw FFTW transforms it performs
// (the same three plans, executed back to back on a second propagator of the same size),
// measured in the same run with the repeats interleaved. "in-step" columns time the FFTW
// executions inside each measured step itself, so the ratio compares the two on the very same
// step (robust on a shared, loaded machine). Plus the 2D transform's plans (FFTW's own
// FFTW_ESTIMATE 2D plan, Fft2D's deterministic row-column form, FFTW_MEASURE) timed alternately,
// and a quick phase-speed accuracy check.
#include <fftw3.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <vector>

#include "bench.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/spectral/propagator.hpp"
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

// One backward N x N transform in place, in three plans: FFTW's own 2D FFTW_ESTIMATE plan (what
// Fft2D made before the row-column form), Fft2D with PlanEffort::estimate (row-column form from
// N = 256), both planned without wisdom, and Fft2D with PlanEffort::measure, executed in turn `reps` times: median ms
// of each, and the largest difference of the row-column result from the 2D plan's relative to the largest value.
void bench_plans(Context& ctx) {
  std::vector<int> sizes = {256, 512, 1024};
  if (!ctx.quick) sizes.push_back(2048);
  Table t({"n", "threads", "ESTIMATE 2D plan ms", "row-column ms", "MEASURE ms", "2D plan / row-column",
           "row-column / MEASURE", "max diff / max", "reps"});
  for (const int n : sizes)
    for (const int threads : ctx.threads) {
      fft_set_threads(threads);
      omp_set_num_threads(threads);
      const std::size_t m = static_cast<std::size_t>(n) * n;
      AlignedBuffer<cfloat> a(m), b(m), c(m);
      auto* fa = reinterpret_cast<fftwf_complex*>(a.data());
      // FFTW_ESTIMATE takes a measured plan from the wisdom when one exists (the table above
      // measured 256^2 and 512^2): without wisdom, as in a process that measured nothing
      fftwf_forget_wisdom();
      fftwf_plan p2 = fftwf_plan_dft_2d(n, n, fa, fa, FFTW_BACKWARD, FFTW_ESTIMATE);
      Fft2D rc(n, n, b.data(), b.data(), Fft2D::backward, PlanEffort::estimate);
      Fft2D me(n, n, c.data(), c.data(), Fft2D::backward, PlanEffort::measure);
      auto fill = [&](AlignedBuffer<cfloat>& x) {
        for (std::size_t i = 0; i < m; ++i)
          x[i] = cfloat(std::sin(0.37f * float(i % 977)), std::cos(0.11f * float(i % 613)));
      };
      fill(a);
      fill(b);
      fftwf_execute(p2);
      rc.execute();
      double diff = 0, big = 0;
      for (std::size_t i = 0; i < m; ++i) {
        diff = std::max(diff, double(std::abs(a[i] - b[i])));
        big = std::max(big, double(std::abs(a[i])));
      }
      const int reps = ctx.quick ? 5 : n <= 512 ? 30 : 10;
      std::vector<double> t2, trc, tme;
      for (int i = 0; i < reps; ++i) {
        auto t0 = std::chrono::steady_clock::now();
        fftwf_execute(p2);
        t2.push_back(seconds_since(t0));
        t0 = std::chrono::steady_clock::now();
        rc.execute();
        trc.push_back(seconds_since(t0));
        t0 = std::chrono::steady_clock::now();
        me.execute();
        tme.push_back(seconds_since(t0));
      }
      fftwf_destroy_plan(p2);
      const double m2 = median(t2), mrc = median(trc), mme = median(tme);
      t.add({std::to_string(n), std::to_string(threads), fmt("%.3f", m2 * 1e3), fmt("%.3f", mrc * 1e3),
             fmt("%.3f", mme * 1e3), fmt("%.2f", m2 / mrc), fmt("%.2f", mrc / mme), fmt("%.1e", diff / big),
             std::to_string(reps)});
      ctx.expect(diff <= 1e-5 * big, fmt("fft %d^2: the row-column form gives the 2D plan's transform", n));
    }
  fft_set_threads(omp_get_num_procs());
  omp_set_num_threads(omp_get_num_procs());
  ctx.report("huygens",
             "2D transform plans (one backward N^2 transform in place, alternated): FFTW's own FFTW_ESTIMATE 2D "
             "plan, Fft2D's deterministic row-column form (PlanEffort::estimate), FFTW_MEASURE (not deterministic)",
             t);
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
      const double tps = prop.transforms_per_step();
      t.add({std::to_string(n), std::to_string(threads), fmt("%.3f", step * 1e3), fmt("%.3f", fft * 1e3),
             fmt("%.3f", step / fft), fmt("%.3f", fin * 1e3), fmt("%.3f", median(ratio_in)), fmt("%g", tps),
             fmt("%.3f", median(std::vector<double>(ts.begin(), ts.end())) * 1e3 - fin * 1e3), std::to_string(reps)});
    }
  }
  fft_set_threads(omp_get_num_procs());
  omp_set_num_threads(omp_get_num_procs());
  ctx.report("huygens", "full step (propagate, cutoff, spectrum, height) vs the raw FFTW transforms it performs", t);
  bench_plans(ctx);

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
