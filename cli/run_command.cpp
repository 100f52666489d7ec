// huygens run: one scene without graphics, its stage table, dumps and meta.json. A run ends
// complete (0), stopped by a non-finite value or a negative LBM depth (3), by SIGINT/SIGTERM (130/143)
// or by a failed write (1); every way leaves meta.json describing exactly the dumps that exist.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "commands.hpp"
#include "dump_writer.hpp"
#include "huygens/common/atomic_file.hpp"
#include "huygens/common/comm.hpp"
#include "huygens/common/memory.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"

namespace huygens {

namespace {

using nlohmann::json;

struct RunArgs {
  std::string scene_file, dump_dir, stats_file;
  long long steps = 100, every = 1;
  bool overwrite = false, dry_run = false;
  Sync sync = Sync::to_disk;  // --no-fsync: Sync::cache
  DumpFormat format;          // --dump-format
  bool format_given = false;
  int ranks = 0;          // --ranks (0: not given)
  double rank_gib = 0.0;  // --rank-memory (0: this machine's available memory)
  RunOptions options;
};

constexpr long long kMaxSteps = 1'000'000'000'000LL;

// Returns false for --help.
bool parse_run_args(int argc, char** argv, RunArgs& a) {
  for (int i = 0; i < argc; ++i) {
    const std::string w = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw UsageError(w + " needs a value");
      return argv[++i];
    };
    if (w == "--steps")
      a.steps = parse_int_arg(w, value(), 0, kMaxSteps);
    else if (w == "--dump")
      a.dump_dir = nonempty_arg(w, value());
    else if (w == "--dump-format") {
      a.format = parse_dump_format(value());
      a.format_given = true;
    } else if (w == "--dump-every")
      a.every = parse_int_arg(w, value(), 1, kMaxSteps);
    else if (w == "--stats-json")
      a.stats_file = nonempty_arg(w, value());
    else if (w == "--overwrite")
      a.overwrite = true;
    else if (w == "--fast-plans")
      a.options.measure_plans = false;
    else if (w == "--no-fsync")
      a.sync = Sync::cache;
    else if (w == "--dry-run")
      a.dry_run = true;
    else if (w == "--ranks")
      a.ranks = static_cast<int>(parse_int_arg(w, value(), 1, 1 << 20));
    else if (w == "--rank-memory")
      a.rank_gib = parse_real_arg(w, value(), 1e-3, 1e6);
    else if (w == "--help" || w == "-h")
      return false;
    else if (!w.empty() && w[0] == '-')
      throw UsageError("unknown option " + w);
    else if (a.scene_file.empty())
      a.scene_file = nonempty_arg("SCENE", argv[i]);
    else
      throw UsageError("more than one scene given");
  }
  if (a.scene_file.empty()) throw UsageError("run needs a SCENE (a scene file or a shipped scene's name)");
  if ((a.ranks || a.rank_gib > 0) && !a.dry_run)
    throw UsageError("--ranks and --rank-memory size a --dry-run (a run's ranks are mpirun -np P)");
  if (a.format_given && a.dump_dir.empty()) throw UsageError("--dump-format sets the format of --dump DIR; add it");
  if (a.format.vtk && comm::size() > 1)
    throw UsageError("--dump-format vtk and both write from one process only; under mpirun dump npy");
  return true;
}

// The stage table of the run: one process as it is; on P ranks each stage's time and calls are
// the largest over the ranks (a step lasts as long as its slowest rank), its buffer bytes and the
// bytes it sent to other ranks the sum over the ranks (the job's total).
std::vector<StageStat> reduced_stats(const StageStats& stats) {
  std::vector<StageStat> out(stats.all().begin(), stats.all().end());
  if (comm::size() == 1) return out;
  std::vector<double> mx, sm;
  for (const auto& s : out) {
    mx.insert(mx.end(), {static_cast<double>(s.ns), static_cast<double>(s.calls), static_cast<double>(s.transforms)});
    sm.insert(sm.end(), {static_cast<double>(s.bytes), static_cast<double>(s.sent)});
  }
  comm::max(mx);
  comm::sum(sm);
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i].ns = static_cast<std::uint64_t>(mx[3 * i]);
    out[i].calls = static_cast<std::uint64_t>(mx[3 * i + 1]);
    out[i].transforms = static_cast<std::uint64_t>(mx[3 * i + 2]);
    out[i].bytes = static_cast<std::uint64_t>(sm[2 * i]);
    out[i].sent = static_cast<std::uint64_t>(sm[2 * i + 1]);
  }
  return out;
}

json stats_json(const std::vector<StageStat>& stats) {
  json out = json::array();
  for (const auto& s : stats)
    out.push_back({{"stage", s.name},
                   {"calls", s.calls},
                   {"total_ms", s.ns * 1e-6},
                   {"ms_per_call", s.calls ? s.ns * 1e-6 / s.calls : 0.0},
                   {"bytes", s.bytes},
                   {"sent_bytes", s.sent},
                   {"transforms", s.transforms}});
  return out;
}

std::string stats_table(const std::vector<StageStat>& stats) {
  bool sent = false;
  for (const auto& s : stats) sent = sent || s.sent > 0;
  std::vector<std::string> head = {"stage", "calls", "total ms", "ms/call", "transforms", "bytes"};
  if (sent) head.push_back("sent bytes");
  Table t(head);
  for (const auto& s : stats) {
    std::vector<std::string> row = {s.name,
                                    std::to_string(s.calls),
                                    fmt("%.2f", s.ns * 1e-6),
                                    s.calls ? fmt("%.4f", s.ns * 1e-6 / s.calls) : "-",
                                    std::to_string(s.transforms),
                                    std::to_string(s.bytes)};
    if (sent) row.push_back(std::to_string(s.sent));
    t.add(row);
  }
  return t.text();
}

// The stop request all ranks agree on at a step boundary: the largest signal number any rank
// received (SIGTERM over SIGINT), 0 for none. One process: its own request.
int agreed_signal() { return static_cast<int>(comm::max(static_cast<std::int64_t>(stop_request::signal()))); }

const char* signal_name(int sig) { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal"; }

// The steps, with a dump every `every` steps; returns 0, or the code of how the run stopped.
int run_steps(const RunArgs& a, Solver& solver, DumpWriter* dumps) {
  auto stop = [&](json entry, const std::string& message, int code) {
    if (comm::root()) std::fprintf(stderr, "huygens: %s\n", message.c_str());
    if (dumps) dumps->stopped(entry);
    return code;
  };
  auto signalled = [&](int sig) {
    const long long s = solver.steps();
    return stop({{"signal", signal_name(sig)}, {"step", s}}, fmt("stopped at step %lld by %s", s, signal_name(sig)),
                128 + sig);
  };
  try {
    if (const int sig = agreed_signal()) return signalled(sig);  // during the set-up (FFT planning)
    if (dumps) dumps->dump();
    std::optional<Progress> bar;
    if (comm::root()) bar.emplace("huygens run", a.steps);
    for (long long s = 1; s <= a.steps; ++s) {
      if (const int sig = agreed_signal()) return signalled(sig);
      solver.step();
      if (dumps && s % a.every == 0) dumps->dump();
      if (bar) bar->update(s);
    }
  } catch (const RunStopped& e) {
    // a non-finite value, or a solver's own stop (an LBM depth below 0): a named stage and step
    return stop({{"stage", e.stage()}, {"step", e.step()}, {"reason", e.what()}},
                std::string("run stopped: ") + e.what() + "; the dumps listed in meta.json are valid", kExitNonFinite);
  } catch (const IoError& e) {
    // meta.json keeps its last good version (it may be the file that failed)
    if (comm::root())
      std::fprintf(stderr, "huygens: run stopped at step %lld: %s\n", static_cast<long long>(solver.steps()), e.what());
    return kExitFailed;
  }
  if (const int sig = agreed_signal()) return signalled(sig);
  if (dumps) dumps->complete();
  return kExitOk;
}

void print_header(const RunArgs& a, Solver& solver) {
  const MemoryEstimate m = solver.memory();
  if (!comm::root()) return;
  const std::string ranks = comm::size() > 1 ? fmt(" per rank on %d ranks", comm::size()) : "";
  std::printf("scene %s (solver %s): memory %s estimated%s, %s available\n", a.scene_file.c_str(),
              solver.meta().value("solver", "?").c_str(), m.summary().c_str(), ranks.c_str(),
              format_bytes(available_memory()).c_str());
  std::fflush(stdout);
}

// The closing lines: steps and wall time (the slowest rank's), the stage table, --stats-json.
void report(const RunArgs& a, Solver& solver, double wall, int rc) {
  const std::vector<StageStat> stats = reduced_stats(solver.stats());
  wall = comm::max(wall);
  // bytes this rank sent to the others per step (the halo rows of docs/scale.md)
  double sent = 0.0;
  for (const auto& s : solver.stats().all()) sent += static_cast<double>(s.sent);
  sent /= static_cast<double>(std::max<std::int64_t>(1, solver.steps()));
  const double sent_max = comm::max(sent), sent_all = comm::sum(sent);
  if (!comm::root()) return;
  std::printf("scene %s (solver %s): %lld steps to t = %.4g s in %.3f s wall\n", a.scene_file.c_str(),
              solver.meta().value("solver", "?").c_str(), static_cast<long long>(solver.steps()), solver.time(), wall);
  if (comm::size() > 1)
    std::printf("stage table of %d ranks: times and calls the largest over the ranks, bytes summed over them\n",
                comm::size());
  std::printf("%s", stats_table(stats).c_str());
  if (sent_all > 0)
    std::printf("sent to other ranks per step: %.0f bytes on the busiest rank, %.0f on all %d ranks\n", sent_max,
                sent_all, comm::size());
  if (!a.stats_file.empty()) {
    const json out = {{"scene", a.scene_file},
                      {"steps", solver.steps()},
                      {"time_s", solver.time()},
                      {"wall_s", wall},
                      {"exit_code", rc},
                      {"ranks", comm::size()},
                      {"sent_bytes_per_step_max", sent_max},
                      {"stages", stats_json(stats)}};
    write_file_atomic(a.stats_file, out.dump(2) + "\n");
  }
  if (!a.dump_dir.empty()) std::printf("dumps: %s (meta.json)\n", a.dump_dir.c_str());
}

// --stats-json must not name the scene file or a file the dump writes (meta.json, *.npy, ... in DIR): it
// replaced them when the run ended, with exit code 0 (a scene turned into stats, a dump's meta.json
// that was not one).
void check_outputs_apart(const RunArgs& a) {
  namespace fs = std::filesystem;
  if (a.stats_file.empty()) return;
  std::error_code ec;
  if (fs::equivalent(a.stats_file, a.scene_file, ec))
    throw UsageError("--stats-json " + a.stats_file + " is the scene file; name another file");
  if (a.dump_dir.empty() || !is_run_file(a.stats_file)) return;
  const fs::path stats_dir = fs::weakly_canonical(fs::absolute(a.stats_file).parent_path(), ec);
  if (!ec && stats_dir == fs::weakly_canonical(fs::absolute(a.dump_dir), ec) && !ec)
    throw UsageError("--stats-json " + a.stats_file + " is a file the dump writes in " + a.dump_dir +
                     " (meta.json, run.pvd, *.npy, *.vti, *.vtu); name another file");
}

}  // namespace

int cmd_run(int argc, char** argv) {
  RunArgs a;
  if (!parse_run_args(argc, argv, a)) {
    print_usage();
    return kExitOk;
  }
  if (a.dry_run) {
    try {
      return cmd_dry_run(a.scene_file, a.ranks ? a.ranks : comm::size(), a.rank_gib);
    } catch (const SceneError& e) {
      if (comm::root()) std::fprintf(stderr, "huygens: scene error in %s: %s\n", a.scene_file.c_str(), e.what());
      return kExitUsage;
    }
  }
  // every output target is checked before the run, not after it
  check_outputs_apart(a);
  if (!a.stats_file.empty() && comm::root()) check_output_file(a.stats_file);  // rank 0 writes it
  if (!a.dump_dir.empty()) DumpWriter::prepare(a.dump_dir, a.overwrite);
  stop_request::install();
  std::unique_ptr<Solver> solver;
  try {
    solver = make_solver(open_scene(a.scene_file), a.options);
  } catch (const SceneError& e) {
    const bool named = std::string(e.what()).find(a.scene_file) != std::string::npos;  // syntax errors name it
    if (comm::root())  // every rank read the same scene and failed alike
      std::fprintf(stderr, "huygens: scene error%s%s: %s\n", named ? "" : " in ", named ? "" : a.scene_file.c_str(),
                   e.what());
    return kExitUsage;
  }
  print_header(a, *solver);
  std::unique_ptr<DumpWriter> dumps;
  if (!a.dump_dir.empty()) dumps = std::make_unique<DumpWriter>(a.dump_dir, a.scene_file, *solver, a.sync, a.format);
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = run_steps(a, *solver, dumps.get());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  report(a, *solver, wall, rc);
  return rc;
}

}  // namespace huygens
