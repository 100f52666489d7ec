// huygens: run a scene without graphics, or validate the physics against analytic solutions.
//   huygens run SCENE [--steps N] [--dump DIR] [--dump-every K] [--stats-json FILE] [--fast-plans]
//   huygens validate [CASE...] [--list]
// Exit codes: 0 success, 1 a validation case failed or an I/O error, 2 bad scene or usage,
// 3 the run stopped on a non-finite value (the stage is named; earlier dumps stay valid) or, in
//   the LBM solver, on a cell running dry (LbmDryError names the step and cell).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "huygens/common/atomic_file.hpp"
#include "huygens/common/npy.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/lbm/shallow.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/validation/validation.hpp"

using namespace huygens;
using nlohmann::json;

namespace {

const char* kUsage =
    "usage: huygens run SCENE [--steps N] [--dump DIR] [--dump-every K] [--stats-json FILE] [--fast-plans]\n"
    "       huygens validate [CASE...] [--list]\n"
    "       huygens --help\n"
    "\n"
    "run       runs SCENE (a JSON scene file) without graphics for N full steps (default 100),\n"
    "          prints the per-stage timing table, and with --dump writes DIR/<field>_NNNNNN.npy\n"
    "          (float32, C order, metres) every K steps (default 1) plus DIR/meta.json. With\n"
    "          time.display_per_step = D > 1 it also writes the D - 1 displayed frames\n"
    "          interpolated inside the step before each dumped step as <field>_NNNNNN_J.npy\n"
    "          (NNNNNN = the step they follow, J = 1..D-1, time (NNNNNN + J/D) dt); meta.json\n"
    "          marks them \"interpolated\": true with \"s\": J/D.\n"
    "          --stats-json FILE writes the stage table as JSON. --fast-plans plans FFTs with\n"
    "          FFTW_ESTIMATE instead of FFTW_MEASURE (quicker start, slower steps).\n"
    "validate  runs the analytic validation cases (all, or the named ones) and prints\n"
    "          case, quantity, measured, expected, error, tolerance, pass/fail.\n"
    "          --list prints the case names.\n"
    "\n"
    "exit codes: 0 ok; 1 a case failed or I/O error; 2 bad scene or usage; 3 non-finite value\n"
    "            (or an LBM cell ran dry).\n";

[[noreturn]] void usage_error(const std::string& msg) {
  std::fprintf(stderr, "huygens: %s\n\n%s", msg.c_str(), kUsage);
  std::exit(2);
}

long long parse_count(const char* flag, const char* v, long long lo) {
  char* end = nullptr;
  const long long x = std::strtoll(v, &end, 10);
  if (!end || *end || x < lo)
    usage_error(std::string(flag) + " needs an integer >= " + std::to_string(lo) + ", got '" + v + "'");
  return x;
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

int cmd_run(int argc, char** argv) {
  std::string scene_file, dump_dir, stats_file;
  long long steps = 100, every = 1;
  RunOptions opt;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--steps")
      steps = parse_count("--steps", value(), 0);
    else if (a == "--dump")
      dump_dir = value();
    else if (a == "--dump-every")
      every = parse_count("--dump-every", value(), 1);
    else if (a == "--stats-json")
      stats_file = value();
    else if (a == "--fast-plans")
      opt.measure_plans = false;
    else if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (!a.empty() && a[0] == '-')
      usage_error("unknown option " + a);
    else if (scene_file.empty())
      scene_file = a;
    else
      usage_error("more than one scene given");
  }
  if (scene_file.empty()) usage_error("run needs a SCENE file");

  std::unique_ptr<Solver> solver;
  try {
    solver = make_solver(load_scene(scene_file), opt);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "huygens: scene error in %s: %s\n", scene_file.c_str(), e.what());
    return 2;
  }

  json meta;
  if (!dump_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(dump_dir, ec);
    if (ec) {
      std::fprintf(stderr, "huygens: cannot create %s: %s\n", dump_dir.c_str(), ec.message().c_str());
      return 1;
    }
    meta = solver->meta();
    meta["scene"] = scene_file;
    meta["dumps"] = json::array();
    meta["complete"] = false;
  }
  // meta.json is rewritten (atomically) after every dump, with the solver's meta refreshed
  // (step counts, adaptive dt history), so it always describes the dumps that exist
  auto save_meta = [&]() {
    if (dump_dir.empty()) return;
    const json now = solver->meta();
    for (const auto& [key, value] : now.items()) meta[key] = value;
    write_file_atomic(dump_dir + "/meta.json", meta.dump(2) + "\n");
  };
  const int per_step = solver->display_per_step();
  auto write_entry = [&](json entry, const std::vector<OutputField>& fields, const std::string& suffix) {
    entry["files"] = json::array();
    for (const auto& f : fields) {
      const std::string name = fmt("%s_%06lld%s.npy", f.name.c_str(),
                                   static_cast<long long>(entry["step"].get<long long>()), suffix.c_str());
      write_npy(dump_dir + "/" + name, f.data, f.shape);
      entry["files"].push_back(name);
    }
    entry["index"] = static_cast<long long>(meta["dumps"].size());
    meta["dumps"].push_back(entry);
  };
  auto dump = [&]() {
    const long long s = solver->steps();
    // displayed frames interpolated inside the last step (s - 1, s): written before the full step
    if (per_step > 1 && s >= 1) {
      const double dt = meta.value("dt", 0.0);
      for (int j = 1; j < per_step; ++j) {
        const double sj = static_cast<double>(j) / per_step;
        json entry = {{"step", s - 1},
                      {"time_s", (static_cast<double>(s - 1) + sj) * dt},
                      {"interpolated", true},
                      {"s", sj},
                      {"display_frame", (s - 1) * per_step + j}};
        write_entry(entry, solver->display_outputs(j), fmt("_%d", j));
      }
    }
    json entry = {
        {"step", s}, {"time_s", solver->time()}, {"interpolated", false}, {"s", 0.0}, {"display_frame", s * per_step}};
    write_entry(entry, solver->outputs(), "");
    save_meta();
  };
  // a run that stops keeps its dumps and says in meta.json where and why it stopped
  auto stopped = [&](const std::string& stage, long long step, const std::string& reason, const char* what) {
    std::fprintf(stderr, "huygens: run stopped: %s%s; dumps up to the last good step are in %s\n", what, reason.c_str(),
                 dump_dir.empty() ? "(no dump directory)" : dump_dir.c_str());
    meta["stopped"] = {{"stage", stage}, {"step", step}, {"reason", reason}};
    save_meta();
    return 3;
  };

  const auto t0 = std::chrono::steady_clock::now();
  int rc = 0;
  try {
    if (!dump_dir.empty()) dump();
    Progress bar("huygens run", steps);
    for (long long s = 1; s <= steps; ++s) {
      solver->step();
      if (!dump_dir.empty() && s % every == 0) dump();
      bar.update(s);
    }
  } catch (const NonFiniteError& e) {
    rc = stopped(e.stage(), e.step(), e.what(), "");
  } catch (const LbmDryError& e) {
    // not a non-finite value but the same kind of stop: a named step and cell, earlier dumps valid
    rc = stopped("dry_cell", solver->steps(), e.what(), "a cell ran dry: ");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "huygens: run failed: %s\n", e.what());
    return 1;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc == 0 && !dump_dir.empty()) {
    meta["complete"] = true;
    save_meta();
  }

  std::printf("scene %s (solver %s): %lld steps to t = %.4g s in %.3f s wall\n", scene_file.c_str(),
              solver->meta().value("solver", "?").c_str(), static_cast<long long>(solver->steps()), solver->time(),
              wall);
  std::printf("%s", stats_table(solver->stats()).c_str());
  if (!stats_file.empty()) {
    json out = {{"scene", scene_file},
                {"steps", solver->steps()},
                {"time_s", solver->time()},
                {"wall_s", wall},
                {"stages", stats_json(solver->stats())}};
    write_file_atomic(stats_file, out.dump(2) + "\n");
  }
  if (!dump_dir.empty()) std::printf("dumps: %s (meta.json)\n", dump_dir.c_str());
  return rc;
}

int cmd_validate(int argc, char** argv) {
  std::vector<std::string> names;
  bool list = false;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--list")
      list = true;
    else if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (!a.empty() && a[0] == '-')
      usage_error("unknown option " + a);
    else
      names.push_back(a);
  }
  auto cases = all_validation_cases();
  if (list) {
    Table t({"case", "solver", "description"});
    for (const auto& c : cases) t.add({c.name, c.solver, c.description});
    std::printf("%s", t.text().c_str());
    return 0;
  }
  for (const auto& n : names) {
    bool found = false;
    for (const auto& c : cases) found = found || c.name == n;
    if (!found) usage_error("unknown validation case '" + n + "' (huygens validate --list)");
  }
  Table t({"case", "quantity", "measured", "expected", "error", "tolerance", "result"});
  int failed = 0, passed = 0;
  for (const auto& c : cases) {
    if (!names.empty() && std::find(names.begin(), names.end(), c.name) == names.end()) continue;
    std::fprintf(stderr, "validating %s ...\n", c.name.c_str());
    std::vector<ValidationRow> rows;
    try {
      rows = c.run();
    } catch (const std::exception& e) {
      rows.push_back(ValidationRow{c.name, std::string("exception: ") + e.what(), 0, 0, 0, 0, false});
    }
    for (const auto& r : rows) {
      t.add({r.case_name, r.quantity, num(r.measured, 6), num(r.expected, 6), num(r.error, 3), num(r.tolerance, 3),
             r.pass ? "pass" : "FAIL"});
      (r.pass ? passed : failed)++;
    }
  }
  std::printf("%s", t.text().c_str());
  std::printf("validate: %d passed, %d failed\n", passed, failed);
  return failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) usage_error("no command given");
  const std::string cmd = argv[1];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd == "run") return cmd_run(argc - 2, argv + 2);
  if (cmd == "validate") return cmd_validate(argc - 2, argv + 2);
  usage_error("unknown command '" + cmd + "'");
}
