// huygens-bench [SECTION[:PART]...] [--quick] [--csv FILE] [--threads LIST]
// Prints run time against error, baselines and ratios measured in the same run.
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>

#include "bench.hpp"
#include "huygens/common/atomic_file.hpp"
#include "huygens/common/isa.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/solvers/registry.hpp"

namespace huygens::bench {

void Context::report(const std::string& section, const std::string& title, const Table& table) {
  std::printf("\n== %s: %s ==\n%s", section.c_str(), title.c_str(), table.text().c_str());
  std::fflush(stdout);
  tables.emplace_back(section + ": " + title, table);
  huygens::stop_request::throw_if_requested("after the table \"" + section + ": " + title + "\"");  // a check point
}

void Context::expect(bool ok, const std::string& what) {
  if (ok) return;
  ++failures;
  std::printf("ACCURACY CHECK FAILED: %s\n", what.c_str());
}

std::string shipped_scene(const std::string& name) {
  const std::string_view text = shipped_scene_text(name);
  if (text.empty()) throw std::runtime_error("huygens-bench: scene '" + name + "' is not embedded");
  return std::string(text);
}

std::vector<bool> pareto_front(const std::vector<double>& time, const std::vector<double>& error) {
  const std::size_t n = time.size();
  std::vector<bool> front(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(time[i]) || !std::isfinite(error[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j)
      dominated = j != i && std::isfinite(time[j]) && std::isfinite(error[j]) && time[j] <= time[i] &&
                  error[j] <= error[i] && (time[j] < time[i] || error[j] < error[i]);
    front[i] = !dominated;
  }
  return front;
}

}  // namespace huygens::bench

namespace {

const char* kUsage =
    "usage: huygens-bench [SECTION[:PART]...] [--quick] [--csv FILE] [--threads LIST]\n"
    "sections: all (default)";

// The parts a section offers (SECTION:PART); other sections have none. "solvers" offers one per
// registered solver.
std::map<std::string, std::vector<std::string>> section_parts() {
  std::map<std::string, std::vector<std::string>> parts = {
      {"stress", {"huygens", "sph", "lbm"}}, {"sph", {"throughput", "grid", "front", "methods", "peers", "peers46"}}};
  for (const huygens::SolverEntry& e : huygens::registered_solvers()) parts["solvers"].push_back(e.name);
  return parts;
}

// "stress:huygens, stress:sph, ..." for the help and a refusal
std::string part_list() {
  std::string list;
  for (const auto& [section, parts] : section_parts())
    for (const std::string& part : parts) list += (list.empty() ? "" : ", ") + section + ":" + part;
  return list;
}

void print_help(const std::map<std::string, huygens::bench::Section>& sections) {
  std::printf("%s", kUsage);
  for (const auto& [name, fn] : sections) std::printf(", %s", name.c_str());
  std::printf("\n  SECTION:PART runs one part of a section (%s);\n", part_list().c_str());
  std::printf("    sph:peers also runs in a full run of sph (not with --quick), sph:peers46 only when named\n");
  std::printf(
      "  --quick    CI-sized sweeps (under 3 minutes in all)\n"
      "  --csv FILE also write every table's rows as CSV (checked before the run, written atomically)\n"
      "  --threads  comma-separated thread counts to sweep, each in [1, 1024] (default 1,<cores>)\n"
      "exit codes: 0 ok; 1 an accuracy check failed or a write failed; 2 bad usage; 130/143 stopped by\n"
      "  SIGINT/SIGTERM after the current table (the tables so far are printed, and written to --csv\n"
      "  with a first line that says the run stopped; a second signal ends it at once)\n");
}

// Reads the command line; false for --help. Throws UsageError for bad usage.
bool parse_bench_args(int argc, char** argv, const std::map<std::string, huygens::bench::Section>& sections,
                      huygens::bench::Context& ctx, std::string& csv, std::vector<std::string>& chosen) {
  using huygens::UsageError;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw UsageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--quick") {
      ctx.quick = true;
    } else if (a == "--csv") {
      csv = huygens::nonempty_arg(a, value());
    } else if (a == "--threads") {
      ctx.threads.clear();
      const std::string list = huygens::nonempty_arg(a, value());
      for (std::size_t b = 0; b <= list.size();) {
        const std::size_t e = std::min(list.find(',', b), list.size());
        ctx.threads.push_back(static_cast<int>(huygens::parse_int_arg(a, list.substr(b, e - b).c_str(), 1, 1024)));
        b = e + 1;
      }
    } else if (a == "--help" || a == "-h") {
      print_help(sections);
      return false;
    } else if (a == "all") {
    } else if (sections.count(a)) {
      chosen.push_back(a);
    } else if (const auto colon = a.find(':'); colon != std::string::npos) {
      const std::string section = a.substr(0, colon), part = a.substr(colon + 1);
      const auto all_parts = section_parts();
      const auto parts = all_parts.find(section);
      if (parts == all_parts.end() ||
          std::find(parts->second.begin(), parts->second.end(), part) == parts->second.end())
        throw UsageError("unknown section part '" + a + "' (parts: " + part_list() + ")");
      chosen.push_back(section);  // SECTION:PART runs one part (e.g. stress:sph)
      ctx.parts.push_back(part);
    } else {
      throw UsageError("unknown argument '" + a + "'");
    }
  }
  return true;
}

}  // namespace

int bench_main(int argc, char** argv) {
  using namespace huygens::bench;
  const std::map<std::string, Section> sections = {
      {"huygens", bench_huygens}, {"pipeline", bench_pipeline}, {"ships", bench_ships}, {"lbm", bench_lbm},
      {"sph", bench_sph},         {"accuracy", bench_accuracy}, {"skip", bench_skip},   {"stress", bench_stress},
      {"interp", bench_interp},   {"render", bench_render},     {"load", bench_load},   {"mpi", bench_mpi},
      {"solvers", bench_solvers},
  };
  Context ctx;
  std::string csv;
  std::vector<std::string> chosen;
  if (!parse_bench_args(argc, argv, sections, ctx, csv, chosen)) return 0;
  huygens::stop_request::install();                   // SIGINT/SIGTERM: stop after the current table
  if (!csv.empty()) huygens::check_output_file(csv);  // before the run, not after it
  if (const auto dir = std::filesystem::path(csv).parent_path(); !dir.empty()) ctx.output_dir = dir.string();
  if (ctx.threads.empty()) {
    ctx.threads.push_back(1);
    const int hw = static_cast<int>(std::thread::hardware_concurrency());
    if (hw > 1) ctx.threads.push_back(hw);
  }
  // where the figures ran: the CPU and its vector extensions, the build's instruction set, the
  // threads and the load average now (again in the footer: the load during the run)
  const std::string machine =
      huygens::machine_line(omp_get_max_threads()) + ", " + (ctx.quick ? "quick" : "full") + " run";
  std::printf("%s\n", machine.c_str());
  const auto start = std::chrono::steady_clock::now();
  huygens::Table took({"section", "wall s"});
  std::string stopped;  // what a SIGINT/SIGTERM abandoned; "" when every section ran
  try {
    for (const auto& [name, fn] : sections)
      if (chosen.empty() || std::find(chosen.begin(), chosen.end(), name) != chosen.end()) {
        huygens::stop_request::throw_if_requested("before the section " + name);
        const auto t0 = std::chrono::steady_clock::now();
        fn(ctx);
        took.add({name, huygens::fmt("%.1f", seconds_since(t0))});
      }
  } catch (const huygens::StopRequested& e) {
    stopped = e.what();
  }
  took.add({stopped.empty() ? "total" : "total (stopped)", huygens::fmt("%.1f", seconds_since(start))});
  std::printf("\n== run time per section ==\n%s", took.text().c_str());
  std::printf("load average (1 min) at the end: %.2f\n", huygens::load_average());
  if (!csv.empty()) {  // the complete tables; a stopped run says so in its first line, then the machine line
    std::string text = stopped.empty() ? ""
                                       : "# stopped by " + std::string(huygens::stop_request::signal_name()) + " " +
                                             stopped + ": the tables below are complete, later ones missing\n";
    text += "# " + machine + "; load average at the end " + huygens::fmt("%.2f", huygens::load_average()) + "\n";
    for (const auto& [title, table] : ctx.tables) text += "# " + title + "\n" + table.csv() + "\n";
    huygens::write_file_atomic(csv, text);
  }
  std::printf("\nhuygens-bench: %d accuracy check(s) failed\n", ctx.failures);
  if (!stopped.empty())
    throw huygens::StopRequested(stopped + "; the " + std::to_string(ctx.tables.size()) +
                                 " complete table(s) are printed above" + (csv.empty() ? "" : " and in " + csv));
  return ctx.failures ? 1 : 0;
}

int main(int argc, char** argv) {
  return huygens::run_program("huygens-bench", argv, [&]() { return bench_main(argc, argv); });
}
