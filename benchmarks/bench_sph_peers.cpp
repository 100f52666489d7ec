// Section "sph", parts "peers" (25 particles across) and "peers46" (46 across): the 3D dam break that issue 37
// measured against SPlisHSPlasH's DFSPH on one machine (a column a x a x 2a, a = 0.05715 m, in a box 8a x a x 4a,
// to t = 0.14 s), with WCSPH and DFSPH at each thread count: wall and CPU seconds per simulated second, mean dt,
// iterations per step, the surge front's error against Martin & Moyce (1952) at T = t sqrt(2 g / a) = 1.5 and
// 2.5, and the time of each pass of the step (SphSystem::stats()). The peer's figures are quoted, not measured
// here. Each run's scene is written next to the output, to rerun with `huygens run`.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>

#include "bench.hpp"
#include "huygens/common/atomic_file.hpp"
#include "huygens/common/isa.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/sph/sph_solver.hpp"
#include "huygens/sph/system.hpp"
#include "huygens/validation/reference/martin_moyce.hpp"

namespace huygens::bench {

namespace {

constexpr double kA = 0.05715;  // column width a (m): Martin & Moyce's 2.25 in
constexpr double kG = 9.81;
constexpr double kTEnd = 0.14;  // simulated time (s): T = 2.59
const double kTs = std::sqrt(2 * kG / kA);
constexpr double kTQ[2] = {1.5, 2.5};  // the front error's times T

// SPlisHSPlasH's DFSPH on this scene at 25 across (31 250 particles), its defaults and volume-map walls, measured
// in issue 37 on the same machine class with alternated runs at load 1-2: wall seconds to t = 0.14 s at 1 and 2
// threads (range of the runs), mean dt and pressure iterations per step
struct PeerFigures {
  int threads;
  double wall_lo, wall_hi;
};
constexpr PeerFigures kPeer[2] = {{1, 43.0, 58.0}, {2, 27.0, 36.0}};
constexpr double kPeerDt = 5.1e-4;
constexpr int kPeerIterations = 31;

const char* method_name(SphMethod m) { return m == SphMethod::dfsph ? "dfsph" : "wcsph"; }

// The scene of the part, as `huygens run` reads it.
std::string peers_scene(int na, SphMethod method) {
  const double a = kA, dx = a / na;
  std::string s = "{\n  \"solver\": \"sph\",\n";
  s +=
      fmt("  \"description\": \"3D dam break of huygens-bench sph:peers (issue 37): column a x a x 2a, a = %g m, "
          "%d particles across a, box 8a x a x 4a; run to t = %g s (T = t sqrt(2g/a) = %.3g)\",\n",
          a, na, kTEnd, kTEnd * kTs);
  s += "  \"sph\": {\n";
  s += fmt("    \"method\": \"%s\",\n    \"spacing_m\": %.9g,\n", method_name(method), dx);
  s += fmt("    \"container_m\": [%.9g, %.9g, %.9g],\n", 8 * a, a, 4 * a);
  s += fmt("    \"fluid\": [ { \"min_m\": [0.0, 0.0, 0.0], \"max_m\": [%.9g, %.9g, %.9g] } ]\n", a, a, 2 * a);
  s += "  }\n}\n";
  return s;
}

struct PeerRun {
  SphMethod method = SphMethod::dfsph;
  int na = 0, threads = 1;
  std::size_t particles = 0;
  std::int64_t steps = 0;
  double wall = 0, cpu = 0, sim = 0, div_it = 0, dens_it = 0, load = 0;
  std::vector<double> T, Z;  // front Z = z / a against T, every step
  StageStats stages;
  std::string scene;  // the file written
};

// Linear interpolation of y(x) at x over increasing xs (clamped at the ends).
double interp_at(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const auto it = std::lower_bound(xs.begin(), xs.end(), x);
  if (it == xs.begin()) return ys.front();
  if (it == xs.end()) return ys.back();
  const std::size_t i = static_cast<std::size_t>(it - xs.begin());
  return ys[i - 1] + (x - xs[i - 1]) / (xs[i] - xs[i - 1]) * (ys[i] - ys[i - 1]);
}

// The measured front at T: the mean of the two Martin & Moyce series, each interpolated linearly.
double martin_moyce_front(double T) {
  double sum = 0;
  int n = 0;
  for (const char* series : {"1.125", "2.25"}) {
    std::vector<double> ts, zs;
    for (const MartinMoycePoint& p : martin_moyce_1952())
      if (p.series == series) ts.push_back(p.T), zs.push_back(p.Z);
    if (ts.empty()) continue;
    sum += interp_at(ts, zs, T);
    ++n;
  }
  return n ? sum / n : 0.0;
}

// Signed relative error of the simulated front at T against Martin & Moyce (%).
double front_error(const PeerRun& r, double T) {
  const double ref = martin_moyce_front(T);
  return 100 * (interp_at(r.T, r.Z, T) - ref) / ref;
}

PeerRun run_peers(int na, SphMethod method, int threads, const std::string& dir) {
  PeerRun r;
  r.method = method;
  r.na = na;
  r.threads = threads;
  const std::string text = peers_scene(na, method);
  r.scene = (std::filesystem::path(dir) / fmt("sph_peers_%d_%s.json", na, method_name(method))).string();
  write_file_atomic(r.scene, text);
  omp_set_num_threads(threads);
  SphSystem s(parse_sph_scene(parse_scene_text(text, r.scene)).params);
  const float dx = s.params().spacing_m;
  auto front = [&] {
    float fx = 0.f;
    for (float x : s.x()) fx = std::max(fx, x);
    r.T.push_back(s.time() * kTs);
    r.Z.push_back((fx + 0.5 * dx) / kA);
  };
  front();
  s.stats().reset_counts();
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  while (s.time() < kTEnd) {
    s.step();
    r.div_it += s.dfsph_divergence_iterations();
    r.dens_it += s.dfsph_density_iterations();
    front();
  }
  r.wall = seconds_since(t0);
  r.cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
  r.load = load_average();
  r.particles = s.count();
  r.steps = s.steps();
  r.sim = s.time();
  r.stages = s.stats();
  return r;
}

std::string iterations(const PeerRun& r) {
  if (r.method != SphMethod::dfsph) return "-";
  const double st = double(std::max<std::int64_t>(r.steps, 1));
  return num((r.div_it + r.dens_it) / st, 3) + " (" + num(r.div_it / st, 3) + " + " + num(r.dens_it / st, 3) + ")";
}

std::vector<std::string> run_row(const PeerRun& r) {
  const double st = double(std::max<std::int64_t>(r.steps, 1));
  return {method_name(r.method),
          std::to_string(r.particles),
          std::to_string(r.threads),
          std::to_string(r.steps),
          num(1e3 * r.sim / st, 3),
          iterations(r),
          num(r.wall, 4),
          num(r.cpu, 4),
          num(r.wall / r.sim, 4),
          num(r.cpu / r.sim, 4),
          num(1e6 * r.cpu / (st * double(r.particles)), 3),
          fmt("%+.1f", front_error(r, kTQ[0])),
          fmt("%+.1f", front_error(r, kTQ[1])),
          fmt("%.2f", r.load)};
}

Table runs_table() {
  return Table({"method", "particles", "threads", "steps", "mean dt ms", "iterations/step (div + dens)", "wall s",
                "CPU s", "wall s per simulated s", "CPU s per simulated s", "CPU us per particle-step",
                "front error % T=1.5", "front error % T=2.5", "load (1 min, end)"});
}

// The quoted SPlisHSPlasH rows (25 across only).
void add_peer_rows(Table& t) {
  for (const PeerFigures& p : kPeer)
    t.add({"SPlisHSPlasH DFSPH (quoted: measured in issue 37 on the same machine class, not by this run)", "31250",
           std::to_string(p.threads), num(kTEnd / kPeerDt, 3), num(1e3 * kPeerDt, 3), std::to_string(kPeerIterations),
           num(p.wall_lo, 3) + "-" + num(p.wall_hi, 3), "-",
           num(p.wall_lo / kTEnd, 3) + "-" + num(p.wall_hi / kTEnd, 3), "-", "-", "-", "-", "1-2"});
}

// The time of each pass (stage) of the step, in seconds and as a share of the run's wall time ("other": the
// bench's front tracking and the step's finiteness checks).
void report_passes(Context& ctx, const std::vector<PeerRun>& runs, int na) {
  const std::vector<std::string> names = {"neighbour search", "density",  "divergence solve", "forces",
                                          "density solve",    "boundary", "integration"};
  std::vector<std::string> head = {"method", "particles", "threads"};
  for (const std::string& n : names) head.push_back(n + " s (%)");
  head.insert(head.end(), {"other s (%)", "ms per divergence iteration", "ms per density iteration"});
  Table t(head);
  for (const PeerRun& r : runs) {
    std::vector<std::string> row = {method_name(r.method), std::to_string(r.particles), std::to_string(r.threads)};
    double sum = 0;
    auto cell = [&](double sec) { return num(sec, 3) + " (" + fmt("%.1f", 100 * sec / r.wall) + ")"; };
    auto stage_s = [&](const std::string& n) {
      const int id = r.stages.find(n);
      return id < 0 ? -1.0 : 1e-9 * double(r.stages[id].ns);
    };
    for (const std::string& n : names) {
      const double sec = stage_s(n);
      row.push_back(sec < 0 ? "-" : cell(sec));
      sum += std::max(sec, 0.0);
    }
    row.push_back(cell(r.wall - sum));
    const bool df = r.method == SphMethod::dfsph;
    row.push_back(df && r.div_it > 0 ? num(1e3 * stage_s("divergence solve") / r.div_it, 3) : "-");
    row.push_back(df && r.dens_it > 0 ? num(1e3 * stage_s("density solve") / r.dens_it, 3) : "-");
    t.add(row);
  }
  ctx.report("sph", fmt("peers: where the time goes, %d across (seconds per pass to t = %g s, %% of wall)", na, kTEnd),
             t);
}

// Ours against the quoted peer: the peer's wall time over ours, per thread count (its range of runs).
void report_ratios(Context& ctx, const std::vector<PeerRun>& runs) {
  Table t({"method", "threads", "ours: wall s to t = 0.14 s", "SPlisHSPlasH DFSPH (quoted) wall s",
           "ahead of SPlisHSPlasH (its wall / ours)", "goal", "front error % T=1.5 / T=2.5"});
  for (const PeerRun& r : runs)
    for (const PeerFigures& p : kPeer) {
      if (p.threads != r.threads) continue;
      const double ours = r.wall * kTEnd / r.sim;  // to exactly 0.14 s
      t.add({method_name(r.method), std::to_string(r.threads), num(ours, 3),
             num(p.wall_lo, 3) + "-" + num(p.wall_hi, 3),
             num(p.wall_lo / ours, 3) + "-" + num(p.wall_hi / ours, 3) + "x (mid " +
                 num(0.5 * (p.wall_lo + p.wall_hi) / ours, 3) + "x)",
             r.method == SphMethod::dfsph ? ">= 5x" : "-",
             fmt("%+.1f / %+.1f", front_error(r, kTQ[0]), front_error(r, kTQ[1]))});
    }
  ctx.report("sph", "peers: ahead of SPlisHSPlasH's DFSPH (quoted figures; the ratio's range is the peer's runs')", t);
}

// 46 against 25 across, where both ran: how the cost grows with the particle count.
void report_growth(Context& ctx, const std::vector<PeerRun>& runs) {
  Table t({"method", "threads", "particles x", "steps x", "wall per simulated s x", "CPU per particle-step x"});
  for (const PeerRun& big : runs)
    for (const PeerRun& small : runs)
      if (big.na > small.na && big.method == small.method && big.threads == small.threads) {
        const double pn = double(big.particles) / double(small.particles);
        const double sn = double(big.steps) / double(small.steps);
        const double cb = big.cpu / (double(big.steps) * double(big.particles));
        const double cs = small.cpu / (double(small.steps) * double(small.particles));
        t.add({method_name(big.method), std::to_string(big.threads), num(pn, 3), num(sn, 3),
               num((big.wall / big.sim) / (small.wall / small.sim), 3), num(cb / cs, 3)});
      }
  if (!t.rows().empty())
    ctx.report("sph", "peers: growth with the particle count (goal: CPU per particle-step x <= 1, cost ~ particles)",
               t);
}

}  // namespace

void sph_peers(Context& ctx, const std::vector<int>& nas) {
  std::vector<PeerRun> all;
  for (int na : nas) {
    std::vector<PeerRun> runs;
    for (SphMethod m : {SphMethod::dfsph, SphMethod::wcsph})
      for (int th : ctx.threads) {
        runs.push_back(run_peers(na, m, th, ctx.output_dir));
        const std::vector<std::string> row = run_row(runs.back());
        std::printf(
            "  sph:peers %d across, %s, %d thread(s): %s steps, iterations/step %s, wall %s s, CPU %s s, front "
            "error %% %s / %s, load %s\n",
            na, row[0].c_str(), th, row[3].c_str(), row[5].c_str(), row[6].c_str(), row[7].c_str(), row[11].c_str(),
            row[12].c_str(), row[13].c_str());
        std::fflush(stdout);
      }
    omp_set_num_threads(ctx.threads.back());
    Table t = runs_table();
    for (const PeerRun& r : runs) t.add(run_row(r));
    if (na == 25) add_peer_rows(t);
    ctx.report("sph",
               fmt("peers: 3D dam break, %d across a, to t = %g s (T = %.3g); front error against Martin & Moyce "
                   "1952 (Z = %.3f at T = 1.5, %.3f at T = 2.5)",
                   na, kTEnd, kTEnd * kTs, martin_moyce_front(kTQ[0]), martin_moyce_front(kTQ[1])),
               t);
    for (const PeerRun& r : runs)
      if (r.threads == ctx.threads.front())
        std::printf("scene written: %s (rerun: huygens run %s --steps %lld)\n", r.scene.c_str(), r.scene.c_str(),
                    static_cast<long long>(r.steps));
    report_passes(ctx, runs, na);
    if (na == 25) report_ratios(ctx, runs);
    all.insert(all.end(), runs.begin(), runs.end());
  }
  report_growth(ctx, all);
}

}  // namespace huygens::bench
