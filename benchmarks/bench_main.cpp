// huygens-bench [SECTION[:PART]...] [--quick] [--csv FILE] [--threads LIST]
// Prints run time against error, baselines and ratios measured in the same run.
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>

#include "bench.hpp"
#include "bench_scenes.hpp"
#include "huygens/common/fft.hpp"

namespace huygens::bench {

void Context::report(const std::string& section, const std::string& title, const Table& table) {
  std::printf("\n== %s: %s ==\n%s", section.c_str(), title.c_str(), table.text().c_str());
  std::fflush(stdout);
  tables.emplace_back(section + ": " + title, table);
}

void Context::expect(bool ok, const std::string& what) {
  if (ok) return;
  ++failures;
  std::printf("ACCURACY CHECK FAILED: %s\n", what.c_str());
}

std::string shipped_scene(const std::string& name) {
  const std::string_view text = embedded::bench_scenes(name);
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

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

const char* kUsage =
    "usage: huygens-bench [SECTION[:PART]...] [--quick] [--csv FILE] [--threads LIST]\n"
    "sections: all (default)";

}  // namespace

int main(int argc, char** argv) {
  using namespace huygens::bench;
  const std::map<std::string, Section> sections = {
      {"huygens", bench_huygens}, {"pipeline", bench_pipeline}, {"ships", bench_ships}, {"lbm", bench_lbm},
      {"sph", bench_sph},         {"accuracy", bench_accuracy}, {"skip", bench_skip},   {"stress", bench_stress},
      {"interp", bench_interp},   {"render", bench_render},
  };
  Context ctx;
  std::string csv;
  std::vector<std::string> chosen;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      ctx.quick = true;
    else if (a == "--csv" && i + 1 < argc)
      csv = argv[++i];
    else if (a == "--threads" && i + 1 < argc) {
      ctx.threads.clear();
      for (char* t = std::strtok(argv[++i], ","); t; t = std::strtok(nullptr, ",")) ctx.threads.push_back(std::atoi(t));
    } else if (a == "--help" || a == "-h") {
      std::printf("%s", kUsage);
      for (const auto& [name, fn] : sections) std::printf(", %s", name.c_str());
      std::printf(
          "\n  SECTION:PART runs one part of a section (stress:huygens, stress:sph, stress:lbm)\n"
          "  --quick    CI-sized sweeps (under 3 minutes in all)\n"
          "  --csv FILE also write every table's rows as CSV\n"
          "  --threads  comma-separated thread counts to sweep (default 1,<cores>)\n");
      return 0;
    } else if (a == "all") {
    } else if (sections.count(a))
      chosen.push_back(a);
    else if (const auto colon = a.find(':'); colon != std::string::npos && sections.count(a.substr(0, colon))) {
      chosen.push_back(a.substr(0, colon));  // SECTION:PART runs one part (e.g. stress:sph)
      ctx.parts.push_back(a.substr(colon + 1));
    } else {
      std::fprintf(stderr, "huygens-bench: unknown argument '%s' (see --help)\n", a.c_str());
      return 2;
    }
  }
  if (ctx.threads.empty()) {
    ctx.threads.push_back(1);
    const int hw = static_cast<int>(std::thread::hardware_concurrency());
    if (hw > 1) ctx.threads.push_back(hw);
  }
  std::printf("machine: %s, %u cores, g++ %s, %s, OpenMP threads %d, %s run\n", cpu_model().c_str(),
              std::thread::hardware_concurrency(), __VERSION__, huygens::fft_version(), omp_get_max_threads(),
              ctx.quick ? "quick" : "full");
  const auto start = std::chrono::steady_clock::now();
  huygens::Table took({"section", "wall s"});
  for (const auto& [name, fn] : sections)
    if (chosen.empty() || std::find(chosen.begin(), chosen.end(), name) != chosen.end()) {
      const auto t0 = std::chrono::steady_clock::now();
      fn(ctx);
      took.add({name, huygens::fmt("%.1f", seconds_since(t0))});
    }
  took.add({"total", huygens::fmt("%.1f", seconds_since(start))});
  std::printf("\n== run time per section ==\n%s", took.text().c_str());
  if (!csv.empty()) {
    std::ofstream f(csv);
    for (const auto& [title, table] : ctx.tables) f << "# " << title << "\n" << table.csv() << "\n";
  }
  std::printf("\nhuygens-bench: %d accuracy check(s) failed\n", ctx.failures);
  return ctx.failures ? 1 : 0;
}
