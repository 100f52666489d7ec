// Section "load": a loaded machine. Time per step of the Huygens default scene, the SPH pool and
// the LBM channel on 1 and all threads, first on a quiet machine, then with a CPU hog on every
// core (busy-loop child processes at the same priority, started and stopped by this section).
// The programs' default OpenMP waits (a short spin, program.cpp) are what is measured; run with
// OMP_WAIT_POLICY=passive, =active, or empty (libgomp's own default) to compare. No timing is
// asserted.
#include <omp.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <thread>
#include <vector>

#include "bench.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"

namespace huygens::bench {

namespace {

// One busy-loop process per core, killed when the hog goes out of scope (or the bench dies).
class CpuHog {
 public:
  explicit CpuHog(int processes) {
    for (int i = 0; i < processes; ++i) {
      const pid_t pid = fork();
      if (pid == 0) {
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        volatile unsigned long spin = 0;
        for (;;) spin = spin + 1;
      }
      if (pid > 0) pids_.push_back(pid);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the scheduler has them running
  }
  ~CpuHog() {
    for (const pid_t p : pids_) kill(p, SIGKILL);
    for (const pid_t p : pids_) waitpid(p, nullptr, 0);
  }
  CpuHog(const CpuHog&) = delete;
  CpuHog& operator=(const CpuHog&) = delete;

 private:
  std::vector<pid_t> pids_;
};

struct LoadCase {
  const char* solver;
  const char* scene;
};

// Mean wall time of a step (unit: ms) over `seconds` of stepping after 3 warm-up steps: the mean,
// not the median, so that the steps a hog preempts count (throughput under load).
double ms_per_step(Solver& solver, double seconds) {
  for (int i = 0; i < 3; ++i) solver.step();
  long long steps = 0;
  const auto t0 = std::chrono::steady_clock::now();
  while (seconds_since(t0) < seconds || steps < 5) {
    solver.step();
    ++steps;
  }
  return 1e3 * seconds_since(t0) / static_cast<double>(steps);
}

// ms per step of each case at each thread count; `out[c][t]`.
std::vector<std::vector<double>> measure(const std::vector<LoadCase>& cases, const std::vector<int>& threads,
                                         double seconds) {
  std::vector<std::vector<double>> out;
  for (const LoadCase& c : cases) {
    out.emplace_back();
    for (const int th : threads) {
      omp_set_num_threads(th);
      fft_set_threads(th);
      RunOptions ro;
      ro.measure_plans = false;  // the same plans in both conditions (FFTW_MEASURE would time the hog)
      auto solver = make_solver(parse_scene_text(shipped_scene(c.scene), c.scene), ro);
      out.back().push_back(ms_per_step(*solver, seconds));
    }
  }
  return out;
}

}  // namespace

void bench_load(Context& ctx) {
  const std::vector<LoadCase> cases = {{"huygens", "default.json"}, {"sph", "pool.json"}, {"lbm", "channel.json"}};
  const int cores = omp_get_num_procs();
  const double seconds = ctx.quick ? 1.0 : 4.0;
  const std::vector<std::vector<double>> quiet = measure(cases, ctx.threads, seconds);
  std::vector<std::vector<double>> loaded;
  {
    CpuHog hog(cores);
    loaded = measure(cases, ctx.threads, seconds);
  }
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  Table t({"solver", "scene", "threads", "quiet ms/step", "loaded ms/step", "loaded / quiet", "loaded vs 1 thread"});
  for (std::size_t c = 0; c < cases.size(); ++c)
    for (std::size_t i = 0; i < ctx.threads.size(); ++i)
      t.add({cases[c].solver, cases[c].scene, std::to_string(ctx.threads[i]), fmt("%.3f", quiet[c][i]),
             fmt("%.3f", loaded[c][i]), fmt("%.2f", loaded[c][i] / quiet[c][i]),
             fmt("%.2fx", loaded[c][0] / loaded[c][i])});
  ctx.report("load",
             fmt("mean ms per step, quiet and with %d busy-loop processes (one per core); OMP_WAIT_POLICY=%s; "
                 "'loaded vs 1 thread' > 1 means the threads still pay under load",
                 cores, policy ? policy : "(unset)"),
             t);
  omp_set_num_threads(ctx.threads.back());
  fft_set_threads(ctx.threads.back());
}

}  // namespace huygens::bench
