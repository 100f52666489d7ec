// huygens run: one scene without graphics, its stage table, dumps and meta.json. A run ends
// complete (0), stopped by a non-finite value or a negative LBM depth (3), by SIGINT/SIGTERM (130/143)
// or by a failed write (1); every way leaves meta.json describing exactly the dumps that exist.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "dump_writer.hpp"
#include "huygens/common/atomic_file.hpp"
#include "huygens/common/memory.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/lbm/shallow.hpp"
#include "huygens/pipeline/solver.hpp"

namespace huygens {

namespace {

using nlohmann::json;

struct RunArgs {
  std::string scene_file, dump_dir, stats_file;
  long long steps = 100, every = 1;
  bool overwrite = false;
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
    else if (w == "--dump-every")
      a.every = parse_int_arg(w, value(), 1, kMaxSteps);
    else if (w == "--stats-json")
      a.stats_file = nonempty_arg(w, value());
    else if (w == "--overwrite")
      a.overwrite = true;
    else if (w == "--fast-plans")
      a.options.measure_plans = false;
    else if (w == "--help" || w == "-h")
      return false;
    else if (!w.empty() && w[0] == '-')
      throw UsageError("unknown option " + w);
    else if (a.scene_file.empty())
      a.scene_file = nonempty_arg("SCENE", argv[i]);
    else
      throw UsageError("more than one scene given");
  }
  if (a.scene_file.empty()) throw UsageError("run needs a SCENE file");
  return true;
}

json stats_json(const StageStats& stats) {
  json out = json::array();
  for (const auto& s : stats.all())
    out.push_back({{"stage", s.name},
                   {"calls", s.calls},
                   {"total_ms", s.ns * 1e-6},
                   {"ms_per_call", s.calls ? s.ns * 1e-6 / s.calls : 0.0},
                   {"bytes", s.bytes},
                   {"transforms", s.transforms}});
  return out;
}

std::string stats_table(const StageStats& stats) {
  Table t({"stage", "calls", "total ms", "ms/call", "transforms", "bytes"});
  for (const auto& s : stats.all())
    t.add({s.name, std::to_string(s.calls), fmt("%.2f", s.ns * 1e-6),
           s.calls ? fmt("%.4f", s.ns * 1e-6 / s.calls) : "-", std::to_string(s.transforms), std::to_string(s.bytes)});
  return t.text();
}

// The steps, with a dump every `every` steps; returns 0, or the code of how the run stopped.
int run_steps(const RunArgs& a, Solver& solver, DumpWriter* dumps) {
  auto stop = [&](json entry, const std::string& message, int code) {
    std::fprintf(stderr, "huygens: %s\n", message.c_str());
    if (dumps) dumps->stopped(entry);
    return code;
  };
  auto signalled = [&]() {
    const long long s = solver.steps();
    return stop({{"signal", stop_request::signal_name()}, {"step", s}},
                fmt("stopped at step %lld by %s", s, stop_request::signal_name()), stop_request::exit_code());
  };
  try {
    if (stop_request::signal()) return signalled();  // during the set-up (FFT planning)
    if (dumps) dumps->dump();
    Progress bar("huygens run", a.steps);
    for (long long s = 1; s <= a.steps; ++s) {
      if (stop_request::signal()) return signalled();
      solver.step();
      if (dumps && s % a.every == 0) dumps->dump();
      bar.update(s);
    }
  } catch (const NonFiniteError& e) {
    return stop({{"stage", e.stage()}, {"step", e.step()}, {"reason", e.what()}},
                std::string("run stopped: ") + e.what() + "; the dumps listed in meta.json are valid", kExitNonFinite);
  } catch (const LbmDryError& e) {
    // not a non-finite value but the same kind of stop: a named step and cell, earlier dumps valid
    return stop({{"stage", "negative_depth"}, {"step", solver.steps()}, {"reason", e.what()}},
                std::string("run stopped: a negative depth: ") + e.what(), kExitNonFinite);
  } catch (const IoError& e) {
    // meta.json keeps its last good version (it may be the file that failed)
    std::fprintf(stderr, "huygens: run stopped at step %lld: %s\n", static_cast<long long>(solver.steps()), e.what());
    return kExitFailed;
  }
  if (stop_request::signal()) return signalled();
  if (dumps) dumps->complete();
  return kExitOk;
}

void print_header(const RunArgs& a, Solver& solver) {
  const MemoryEstimate m = solver.memory();
  std::printf("scene %s (solver %s): memory %s estimated, %s available\n", a.scene_file.c_str(),
              solver.meta().value("solver", "?").c_str(), m.summary().c_str(),
              format_bytes(available_memory()).c_str());
  std::fflush(stdout);
}

}  // namespace

int cmd_run(int argc, char** argv) {
  RunArgs a;
  if (!parse_run_args(argc, argv, a)) {
    std::fputs(kUsage, stdout);
    return kExitOk;
  }
  // every output target is checked before the run, not after it
  if (!a.stats_file.empty()) check_output_file(a.stats_file);
  if (!a.dump_dir.empty()) DumpWriter::prepare(a.dump_dir, a.overwrite);
  stop_request::install();
  std::unique_ptr<Solver> solver;
  try {
    solver = make_solver(load_scene(a.scene_file), a.options);
  } catch (const SceneError& e) {
    const bool named = std::string(e.what()).find(a.scene_file) != std::string::npos;  // syntax errors name it
    std::fprintf(stderr, "huygens: scene error%s%s: %s\n", named ? "" : " in ", named ? "" : a.scene_file.c_str(),
                 e.what());
    return kExitUsage;
  }
  print_header(a, *solver);
  std::unique_ptr<DumpWriter> dumps;
  if (!a.dump_dir.empty()) dumps = std::make_unique<DumpWriter>(a.dump_dir, a.scene_file, *solver);
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = run_steps(a, *solver, dumps.get());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("scene %s (solver %s): %lld steps to t = %.4g s in %.3f s wall\n", a.scene_file.c_str(),
              solver->meta().value("solver", "?").c_str(), static_cast<long long>(solver->steps()), solver->time(),
              wall);
  std::printf("%s", stats_table(solver->stats()).c_str());
  if (!a.stats_file.empty()) {
    const json out = {{"scene", a.scene_file}, {"steps", solver->steps()}, {"time_s", solver->time()},
                      {"wall_s", wall},        {"exit_code", rc},          {"stages", stats_json(solver->stats())}};
    write_file_atomic(a.stats_file, out.dump(2) + "\n");
  }
  if (dumps) std::printf("dumps: %s (meta.json)\n", a.dump_dir.c_str());
  return rc;
}

}  // namespace huygens
