// Section "lbm": the shallow-water LBM's fused stream-collide pass in million lattice updates
// per second (MLUPS) against a plain copy loop that moves the same bytes per cell (read 9
// populations and the bed, write 9 populations; with the bed term one plane more each way),
// measured in alternating pairs in the same run with the same threads; and run time against
// error for the Stoker dam break (h_L/h_R = 2).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <functional>
#include <vector>

#include "bench.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/lbm/shallow.hpp"
#include "huygens/validation/lbm_cases.hpp"

namespace huygens::bench {

namespace {

// The bandwidth reference of the same bytes per cell as the kernel: read 9 planes and the bed,
// write 9 planes (19 floats, 76 B: the flat kernel's 9 populations read, 9 and the depth written);
// with `bed_term` also read one plane and write one (21 floats, 84 B: the bed kernel also reads z
// and the old depth).
struct CopyLoop {
  std::size_t n;
  bool bed_term;
  AlignedBuffer<float> src, dst, bed, hin, hout;
  CopyLoop(std::size_t cells, bool with_bed)
      : n(cells),
        bed_term(with_bed),
        src(9 * cells),
        dst(9 * cells),
        bed(cells),
        hin(with_bed ? cells : 0),
        hout(with_bed ? cells : 0) {
    for (std::size_t i = 0; i < src.size(); ++i) src[i] = 1.0f + 1e-7f * static_cast<float>(i % 97);
    for (std::size_t i = 0; i < n; ++i) bed[i] = 0.01f * static_cast<float>(i % 13);
    for (std::size_t i = 0; i < hin.size(); ++i) hin[i] = 0.5f + 1e-3f * static_cast<float>(i % 7);
  }
  int bytes() const { return bed_term ? 84 : 76; }
  void run(int rows) {
    const std::size_t cols = n / static_cast<std::size_t>(rows);
    const float* s = src.data();
    const float* b = bed.data();
    const float* hi = bed_term ? hin.data() : nullptr;
    float* ho = bed_term ? hout.data() : nullptr;
    float* d = dst.data();
    const std::size_t N = n;
#pragma omp parallel for schedule(static)
    for (int r = 0; r < rows; ++r) {
      const std::size_t o = static_cast<std::size_t>(r) * cols;
      const float* __restrict ba = b + o;
      const float* __restrict s0 = s + o;
      float* __restrict d0 = d + o;
#pragma omp simd
      for (std::size_t c = 0; c < cols; ++c) d0[c] = s0[c] + ba[c];
      if (hi != nullptr) {
        const float* __restrict h0 = hi + o;
        float* __restrict h1 = ho + o;
#pragma omp simd
        for (std::size_t c = 0; c < cols; ++c) h1[c] = h0[c] + 1.f;
      }
      for (int a = 1; a < 9; ++a) {
        const float* __restrict sa = s + a * N + o;
        float* __restrict da = d + a * N + o;
#pragma omp simd
        for (std::size_t c = 0; c < cols; ++c) da[c] = sa[c];
      }
    }
  }
};

// Wall and process CPU time (all threads) of one call (unit: s).
struct Times {
  double wall, cpu;
};
Times time_call(const std::function<void()>& fn) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  fn();
  const std::clock_t c1 = std::clock();
  return {std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
          static_cast<double>(c1 - c0) / CLOCKS_PER_SEC};
}

// The kernel and the copy timed in alternating pairs (kernel then copy, then copy then kernel),
// so the two of a pair see the same load on a shared machine: the median wall time of each, the
// median of the pairs' ratios copy time / kernel time (LBM cells/s over copy cells/s), and the
// same ratio of CPU times (what the two cost where other processes take turns on the cores).
struct Paired {
  double kernel_s, copy_s, ratio, cpu_ratio;
};
Paired paired_medians(int reps, const std::function<void()>& kernel, const std::function<void()>& copy) {
  kernel();
  copy();
  std::vector<double> tk, tc, r, rc;
  for (int i = 0; i < reps; ++i) {
    const bool kernel_first = i % 2 == 0;
    const Times a = time_call(kernel_first ? kernel : copy);
    const Times b = time_call(kernel_first ? copy : kernel);
    const Times& k = kernel_first ? a : b;
    const Times& c = kernel_first ? b : a;
    tk.push_back(k.wall);
    tc.push_back(c.wall);
    r.push_back(c.wall / k.wall);
    rc.push_back(c.cpu / k.cpu);
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  return {median(tk), median(tc), median(r), median(rc)};
}

LbmShallow make_lattice(int n, bool with_bed) {
  LbmParams p;
  p.cols = p.rows = n;
  p.cell_m = 1.0;
  p.dt_s = 0.4 / std::sqrt(9.81);
  p.viscosity_m2s = (0.6 - 0.5) / (3.0 * p.dt_s);
  LbmFields f;
  const std::size_t cells = static_cast<std::size_t>(n) * n;
  f.depth_m.assign(cells, 1.0f);
  f.bed_m.assign(cells, 0.0f);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const double x = (c - 0.5 * n) / n, y = (r - 0.4 * n) / n;
      const float z = with_bed ? static_cast<float>(0.2 * std::exp(-(x * x + y * y) / 0.02)) : 0.0f;
      f.bed_m[static_cast<std::size_t>(r) * n + c] = z;
      f.depth_m[static_cast<std::size_t>(r) * n + c] =
          1.0f - z + 0.01f * static_cast<float>(std::exp(-((x + 0.2) * (x + 0.2) + y * y) / 0.005));
    }
  return LbmShallow(p, f);
}

}  // namespace

void bench_lbm(Context& ctx) {
  // 1) MLUPS against the copy bound.
  Table speed({"lattice", "bed", "B/cell", "threads", "LBM MLUPS", "LBM GB/s", "copy MLUPS (same B/cell)", "copy GB/s",
               "LBM / copy (cells/s, median of pairs)", "LBM / copy (CPU time)"});
  const std::vector<int> sizes = {256, 1024, 4096};
  for (int n : sizes) {
    const std::size_t cells = static_cast<std::size_t>(n) * n;
    const int steps = n <= 256 ? (ctx.quick ? 100 : 400) : n <= 1024 ? (ctx.quick ? 8 : 30) : (ctx.quick ? 2 : 4);
    const int reps = ctx.quick ? 3 : 7;
    for (bool with_bed : {false, true}) {
      LbmShallow sim = make_lattice(n, with_bed);
      CopyLoop copy(cells, with_bed);
      ctx.expect(copy.bytes() == sim.bytes_per_cell(), fmt("lbm %d^2: the copy moves the kernel's bytes per cell", n));
      for (int t : ctx.threads) {
        omp_set_num_threads(t);
        const Paired pt = paired_medians(
            reps, [&] { sim.run(steps); },
            [&] {
              for (int s = 0; s < steps; ++s) copy.run(n);
            });
        const double mlups = cells * steps / pt.kernel_s * 1e-6, cops = cells * steps / pt.copy_s * 1e-6;
        speed.add({fmt("%d^2", n), with_bed ? "yes" : "flat", std::to_string(sim.bytes_per_cell()), std::to_string(t),
                   fmt("%.1f", mlups), fmt("%.1f", mlups * sim.bytes_per_cell() * 1e-3), fmt("%.1f", cops),
                   fmt("%.1f", cops * copy.bytes() * 1e-3), fmt("%.0f %%", 100.0 * pt.ratio),
                   fmt("%.0f %%", 100.0 * pt.cpu_ratio)});
      }
      ctx.expect(std::isfinite(sim.volume_m3()), fmt("lbm %d^2 stays finite", n));
    }
  }
  omp_set_num_threads(ctx.threads.back());
  ctx.report("lbm",
             fmt("fused stream-collide (flat: 76 B/cell, with bed term: 84 B/cell; kernel instruction set: %s) vs a "
                 "copy of the same bytes per cell (9 planes + bed read, 9 written; with bed term one plane more each "
                 "way), same run, timed in alternating pairs: MLUPS from the median wall times, the ratios the medians "
                 "of the pairs' ratios of wall and of process CPU time",
                 lbm_kernel_isa()),
             speed);

  // 2) Run time against error: Stoker dam break h_L/h_R = 2, L1 relative depth error.
  Table err({"cells", "steps", "L1 rel. error", "order", "run time s", "MLUPS"});
  double prev = NAN;
  std::vector<int> res = {256, 512, 1024, 2048, 4096};
  if (!ctx.quick) res.push_back(8192);
  for (int n : res) {
    const auto r = lbm_dam_break_1d(2.0, n);
    err.add({std::to_string(n), std::to_string(r.steps), fmt("%.3e", r.l1_relative),
             std::isfinite(prev) ? fmt("%.2f", std::log2(prev / r.l1_relative)) : "-", fmt("%.4f", r.wall_s),
             fmt("%.1f", n * static_cast<double>(r.steps) / r.wall_s * 1e-6)});
    if (n == 1024) ctx.expect(r.l1_relative < 5e-3, "lbm Stoker h_L/h_R = 2 at 1024 cells: L1 < 5e-3");
    prev = r.l1_relative;
  }
  ctx.report("lbm", "Stoker dam break h_L/h_R = 2 (1 row, tau 0.55, CFL 0.5): error against resolution and time", err);
}

}  // namespace huygens::bench
