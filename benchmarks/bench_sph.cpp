// Section "sph": particle-steps per second of the SPH step (paper 000 / MCG03) for 3 000,
// 30 000 and 300 000 particles and each thread count, split into neighbour search, density,
// boundary pressure, forces and integration; the same physics with an O(n^2) all-pairs neighbour search measured in
// the same run (speed-up and agreement); run time against error (density error and dam-break
// front error against particle spacing and time step); WCSPH against DFSPH (wall time per simulated
// second, mean dt and front error at 16 and 24 particles across the dam-break column); the 3D dam break against
// SPlisHSPlasH (parts peers and peers46, bench_sph_peers.cpp).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>

#include "bench.hpp"
#include "huygens/sph/system.hpp"
#include "huygens/validation/sph_cases.hpp"

namespace huygens::bench {

namespace {

// a pool-like block: n particles in a box whose floor is square and depth is 1/4 of its side
SphParams pool_params(std::size_t n) {
  SphParams p;
  p.spacing_m = 0.01f;
  const int side = std::max(4, static_cast<int>(std::round(std::cbrt(4.0 * n))));
  const int depth = std::max(2, static_cast<int>(std::round(double(n) / (side * side))));
  p.container_m = {side * p.spacing_m, side * p.spacing_m, 3.f * depth * p.spacing_m};
  p.fluid.push_back({{0, 0, 0}, {side * p.spacing_m, side * p.spacing_m, depth * p.spacing_m}});
  return p;
}

struct Measured {
  std::vector<double> T, Z;
  double max_comp = 0, wall = 0, sim = 0;
  std::int64_t steps = 0, iterations = 0;
  std::size_t particles = 0;
};

Measured dam(int na, float cfl, double T_end, SphMethod method = SphMethod::wcsph) {
  const float a = 0.05715f, dx = a / na;
  SphParams p;
  p.method = method;
  p.spacing_m = dx;
  p.cfl = cfl;
  p.container_m = {8 * a, 4 * dx, 4 * a};
  p.fluid.push_back({{0, 0, 0}, {a, 4 * dx, 2 * a}});
  SphSystem s(p);
  Measured m;
  const double Ts = std::sqrt(2 * 9.81 / a);
  const auto t0 = std::chrono::steady_clock::now();
  while (s.time() * Ts < T_end) {
    s.step();
    float fx = 0.f;
    for (float x : s.x()) fx = std::max(fx, x);
    m.T.push_back(s.time() * Ts);
    m.Z.push_back((fx + 0.5f * dx) / a);
    for (float r : s.density()) m.max_comp = std::max(m.max_comp, double(r / p.rest_density_kgpm3 - 1.f));
  }
  m.wall = seconds_since(t0);
  m.steps = s.steps();
  m.sim = s.time();
  m.iterations = s.dfsph_total_iterations();
  m.particles = s.count();
  return m;
}

// Mean and largest relative front error against the Martin & Moyce points up to T_end (%).
std::pair<double, double> front_errors(const Measured& m, double T_end) {
  double sum = 0, mx = 0;
  int cnt = 0;
  for (const MartinMoycePoint& p : martin_moyce_1952()) {
    if (p.T > T_end) continue;
    auto it = std::lower_bound(m.T.begin(), m.T.end(), p.T);
    if (it == m.T.end() || it == m.T.begin()) continue;
    const double e = std::fabs(m.Z[static_cast<std::size_t>(it - m.T.begin())] - p.Z) / p.Z;
    sum += e;
    mx = std::max(mx, e);
    ++cnt;
  }
  return {100 * sum / std::max(cnt, 1), 100 * mx};
}

// Throughput and stage split.
void sph_throughput(Context& ctx) {
  // wall-clock rates, and the rate per CPU-second of the process (on a shared, loaded machine the wall
  // rate understates what the cores deliver; both are printed)
  Table t({"particles", "threads", "steps", "steps/s", "Mparticle-steps/s", "per core", "per CPU-s", "neighbour %",
           "density %", "boundary %", "forces %", "integration %"});
  const std::vector<std::size_t> sizes = {3000, 30000, 300000};
  for (std::size_t n : sizes) {
    for (int th : ctx.threads) {
      omp_set_num_threads(th);
      SphSystem s(pool_params(n));
      const int warm = 3;
      for (int k = 0; k < warm; ++k) s.step();
      s.stats().reset_counts();
      const int steps = n <= 3000    ? (ctx.quick ? 200 : 1000)
                        : n <= 30000 ? (ctx.quick ? 20 : 100)
                                     : (ctx.quick ? 2 : 10);
      const auto t0 = std::chrono::steady_clock::now();
      const std::clock_t c0 = std::clock();
      for (int k = 0; k < steps; ++k) s.step();
      const double sec = seconds_since(t0);
      const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
      double tot = 0;
      for (const auto& st : s.stats().all()) tot += double(st.ns);
      auto pct = [&](int id) { return fmt("%.1f", 100.0 * double(s.stats()[id].ns) / tot); };
      const double rate = double(s.count()) * steps / sec;
      t.add({std::to_string(s.count()), std::to_string(th), std::to_string(steps), num(steps / sec, 4),
             num(rate * 1e-6, 4), num(rate * 1e-6 / th, 4), num(double(s.count()) * steps / cpu * 1e-6, 4),
             pct(s.stage_ids().neighbours), pct(s.stage_ids().density), pct(s.stage_ids().boundary),
             pct(s.stage_ids().forces), pct(s.stage_ids().integration)});
    }
  }
  omp_set_num_threads(ctx.threads.back());
  ctx.report(
      "sph",
      "step throughput (targets: 3000-particle pool >= 1000 steps/s; >= 1.5 M particle-steps/s per core at 300 000)",
      t);
}

// The grid neighbour search against all pairs: same physics, same state.
void sph_grid_vs_all_pairs(Context& ctx) {
  Table t({"particles", "grid step ms", "all-pairs step ms", "speed-up", "max |d rho|/rho0", "max |d a|/max|a - g|"});
  for (std::size_t n : {1000ul, 3000ul}) {
    SphSystem s(pool_params(n));
    for (int k = 0; k < 20; ++k) s.step();
    const std::size_t m = s.count();
    std::vector<float> a1(m), b1(m), c1(m), r1(m), a2(m), b2(m), c2(m), r2(m);
    const double tg = median_seconds(ctx.quick ? 3 : 7, [&] { s.grid_accelerations(a1, b1, c1, r1); });
    const double tb = median_seconds(ctx.quick ? 1 : 3, [&] { s.brute_force_accelerations(a2, b2, c2, r2); });
    double amax = 0, da = 0, dr = 0;
    // the neighbour sums make a - g (pressure and viscosity; gravity is added after): their
    // float summation order is compared against that sum's largest magnitude (about g in a pool
    // at rest, where the net acceleration a itself nearly vanishes)
    const auto g = s.gravity();
    for (std::size_t i = 0; i < m; ++i)
      amax = std::max(amax, double(std::hypot(a1[i] - g[0], b1[i] - g[1], c1[i] - g[2])));
    for (std::size_t i = 0; i < m; ++i) {
      da = std::max(da, double(std::hypot(a1[i] - a2[i], b1[i] - b2[i], c1[i] - c2[i])));
      dr = std::max(dr, double(std::fabs(r1[i] - r2[i])));
    }
    dr /= s.params().rest_density_kgpm3;
    da /= amax;
    t.add({std::to_string(m), num(tg * 1e3, 4), num(tb * 1e3, 4), num(tb / tg, 3), num(dr, 3), num(da, 3)});
    ctx.expect(dr < 1e-5 && da < 1e-3,
               "sph grid and all-pairs neighbour search give the same densities (and forces to float summation order)");
  }
  ctx.report("sph", "uniform grid (counting sort, 27 cells) vs O(n^2) all pairs, density + forces of one step", t);
}

// Run time against error: dam-break front and density error against spacing and time step.
void sph_front_error(Context& ctx) {
  const double T_end = ctx.quick ? 2.5 : 5.0;
  Table t({"particles across a", "spacing mm", "cfl", "steps", "wall s", "max density error %",
           "mean front error % (T <= " + num(T_end, 2) + ")", "max front error %"});
  const std::vector<int> nas = ctx.quick ? std::vector<int>{6, 8} : std::vector<int>{8, 12, 16};
  const std::vector<float> cfls = ctx.quick ? std::vector<float>{0.15f} : std::vector<float>{0.075f, 0.15f, 0.3f};
  for (int na : nas)
    for (float cfl : cfls) {
      const Measured m = dam(na, cfl, T_end);
      const auto [mean, mx] = front_errors(m, T_end);
      t.add({std::to_string(na), num(57.15 / na, 3), num(cfl, 3), std::to_string(m.steps), num(m.wall, 3),
             num(100 * m.max_comp, 3), num(mean, 3), num(mx, 3)});
    }
  ctx.report("sph", "run time against error: Martin & Moyce dam break (both series)", t);
}

// WCSPH against DFSPH on the Martin & Moyce dam break (the validate set-up): wall seconds per simulated
// second, mean dt, particle-steps/s and the front error, per resolution and thread count.
void sph_methods(Context& ctx) {
  const double T_end = ctx.quick ? 2.5 : 5.0;
  Table t({"method", "across a", "particles", "threads", "steps", "mean dt ms", "iterations/step", "wall s",
           "wall s per simulated s", "Mparticle-steps/s", "mean front error %", "max front error %"});
  Table r({"across a", "threads", "WCSPH / DFSPH wall per simulated s", "front error WCSPH / DFSPH %"});
  const std::vector<int> nas = ctx.quick ? std::vector<int>{16} : std::vector<int>{16, 24};
  const std::vector<int> ths = ctx.quick ? std::vector<int>{ctx.threads.back()} : ctx.threads;
  for (int na : nas)
    for (int th : ths) {
      omp_set_num_threads(th);
      double per_sim[2] = {0, 0}, err[2] = {0, 0};
      for (int k = 0; k < 2; ++k) {
        const SphMethod method = k == 0 ? SphMethod::wcsph : SphMethod::dfsph;
        const Measured m = dam(na, 0.15f, T_end, method);
        const auto [mean, mx] = front_errors(m, T_end);
        per_sim[k] = m.wall / m.sim;
        err[k] = mean;
        const double ps = double(m.particles) * double(m.steps) / m.wall;
        t.add({k == 0 ? "wcsph" : "dfsph", std::to_string(na), std::to_string(m.particles), std::to_string(th),
               std::to_string(m.steps), num(1e3 * m.sim / double(m.steps), 4),
               k == 0 ? "-" : num(double(m.iterations) / double(m.steps), 3), num(m.wall, 3), num(per_sim[k], 4),
               num(ps * 1e-6, 3), num(mean, 3), num(mx, 3)});
      }
      r.add({std::to_string(na), std::to_string(th), num(per_sim[0] / per_sim[1], 3),
             num(err[0], 3) + " / " + num(err[1], 3)});
    }
  omp_set_num_threads(ctx.threads.back());
  ctx.report("sph",
             "WCSPH vs DFSPH: Martin & Moyce dam break to T = " + num(T_end, 2) +
                 " (goal: DFSPH >= 5x less wall time per simulated second at equal front error)",
             t);
  ctx.report("sph", "WCSPH vs DFSPH: ratios", r);
}

}  // namespace

void bench_sph(Context& ctx) {
  if (ctx.part("throughput")) sph_throughput(ctx);
  if (ctx.part("grid")) sph_grid_vs_all_pairs(ctx);
  if (ctx.part("front")) sph_front_error(ctx);
  if (ctx.part("methods")) sph_methods(ctx);
  // the 3D dam break against SPlisHSPlasH (bench_sph_peers.cpp): 25 across when named or in a full run, 46 across
  // (about 6 times the particles) only when named
  std::vector<int> peers;
  if (ctx.named("peers") || (ctx.parts.empty() && !ctx.quick)) peers.push_back(25);
  if (ctx.named("peers46")) peers.push_back(46);
  if (!peers.empty()) sph_peers(ctx, peers);
}

}  // namespace huygens::bench
