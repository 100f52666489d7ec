// Section "solvers": every solver of the registry (solvers/registry.hpp) stepping the scene its
// entry names, one thread and the machine's count: ms per step, simulated seconds per wall second, and
// the stage that took the most time (the solver's own StageStats). A solver registered outside the
// library (tests/toy_solver/) appears here with no edit to the bench. `solvers:NAME` runs one.
#include <omp.h>

#include <algorithm>
#include <chrono>

#include "bench.hpp"
#include "huygens/common/report.hpp"
#include "huygens/solvers/registry.hpp"

namespace huygens::bench {

namespace {

// The slowest stage of the run and its share of the stages' time.
std::string slowest_stage(const StageStats& stats) {
  std::uint64_t total = 0;
  const StageStat* top = nullptr;
  for (const StageStat& s : stats.all()) {
    total += s.ns;
    if (!top || s.ns > top->ns) top = &s;
  }
  if (!top || total == 0) return "-";
  return fmt("%s (%.0f %%)", top->name.c_str(), 100.0 * double(top->ns) / double(total));
}

void time_solver(Context& ctx, const SolverEntry& e, int threads, Table& t) {
  omp_set_num_threads(threads);
  auto solver = e.make(parse_scene_text(e.bench_scene, e.name + " bench scene"), RunOptions{false});
  const int steps = std::max(1, ctx.quick ? e.bench_steps / 4 : e.bench_steps);
  solver->step();  // first touch, plans' first run
  const double t0 = solver->time();
  const auto w0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) solver->step();
  const double wall = seconds_since(w0), simulated = solver->time() - t0;
  const bool finite = all_finite(solver->height());
  ctx.expect(finite, e.name + " bench scene: height finite after " + std::to_string(steps + 1) + " steps");
  t.add({e.name, std::to_string(threads), std::to_string(steps), fmt("%.3f", 1e3 * wall / steps),
         fmt("%.3g", simulated / wall), slowest_stage(solver->stats())});
}

}  // namespace

void bench_solvers(Context& ctx) {
  Table t({"solver", "threads", "steps", "ms/step", "sim s / wall s", "slowest stage"});
  for (const SolverEntry& e : registered_solvers()) {
    if (!ctx.part(e.name) || e.bench_scene.empty()) continue;
    for (int threads : ctx.threads) time_solver(ctx, e, threads, t);
  }
  omp_set_num_threads(ctx.threads.back());
  ctx.report("solvers", "each registered solver stepping its bench scene", t);
}

}  // namespace huygens::bench
