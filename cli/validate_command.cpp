// huygens validate: the analytic validation cases (validation/), as a table of measured against
// expected values with their tolerances; exit 1 when a case fails. --jobs N runs N cases at once
// (each with its share of the OpenMP threads); the table keeps the registry's order.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/validation/validation.hpp"

namespace huygens {

namespace {

struct ValidateArgs {
  std::vector<std::string> names;
  bool list = false, help = false;
  int jobs = 1;
};

ValidateArgs parse_validate_args(int argc, char** argv) {
  ValidateArgs a;
  for (int i = 0; i < argc; ++i) {
    const std::string s = argv[i];
    if (s == "--list") {
      a.list = true;
    } else if (s == "--help" || s == "-h") {
      a.help = true;
    } else if (s == "--jobs") {
      if (i + 1 >= argc) throw UsageError("--jobs needs a value");
      a.jobs = static_cast<int>(parse_int_arg(s, argv[++i], 1, 64));
    } else if (!s.empty() && s[0] == '-') {
      throw UsageError("unknown option " + s);
    } else {
      a.names.push_back(s);
    }
  }
  return a;
}

// The rows of one case; an exception becomes a failed row naming it.
std::vector<ValidationRow> run_case(const ValidationCase& c) {
  try {
    return c.run();
  } catch (const std::exception& e) {
    return {ValidationRow{c.name, std::string("exception: ") + e.what(), 0, 0, 0, 0, false}};
  }
}

// Runs the cases on `jobs` threads, each taking the next case not yet started; a case's OpenMP
// regions get threads / jobs threads. Prints each case's wall time as it ends (stderr).
std::vector<std::vector<ValidationRow>> run_cases(const std::vector<const ValidationCase*>& todo, int jobs) {
  std::vector<std::vector<ValidationRow>> rows(todo.size());
  std::atomic<std::size_t> next{0};
  std::mutex print;
  const int omp_each = std::max(1, omp_get_max_threads() / jobs);
  auto worker = [&]() {
    omp_set_num_threads(omp_each);
    for (std::size_t i; (i = next.fetch_add(1)) < todo.size();) {
      const auto t0 = std::chrono::steady_clock::now();
      rows[i] = run_case(*todo[i]);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const std::lock_guard lock(print);
      std::fprintf(stderr, "validated %s in %.1f s\n", todo[i]->name.c_str(), s);
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < std::min<int>(jobs, static_cast<int>(todo.size())); ++j) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  return rows;
}

}  // namespace

int cmd_validate(int argc, char** argv) {
  const ValidateArgs a = parse_validate_args(argc, argv);
  if (a.help) {
    print_usage();
    return 0;
  }
  const std::vector<ValidationCase> cases = all_validation_cases();
  if (a.list) {
    Table t({"case", "solver", "description"});
    for (const auto& c : cases) t.add({c.name, c.solver, c.description});
    std::printf("%s", t.text().c_str());
    return 0;
  }
  for (const auto& n : a.names)
    if (std::none_of(cases.begin(), cases.end(), [&](const ValidationCase& c) { return c.name == n; }))
      throw UsageError("unknown validation case '" + n + "' (huygens validate --list)");
  std::vector<const ValidationCase*> todo;
  for (const auto& c : cases)
    if (a.names.empty() || std::find(a.names.begin(), a.names.end(), c.name) != a.names.end()) todo.push_back(&c);
  const auto t0 = std::chrono::steady_clock::now();
  const auto results = run_cases(todo, a.jobs);
  Table t({"case", "quantity", "measured", "expected", "error", "tolerance", "result"});
  int failed = 0, passed = 0, reported = 0;
  for (const auto& rows : results)
    for (const auto& r : rows) {
      t.add({r.case_name, r.quantity, num(r.measured, 6), num(r.expected, 6), num(r.error, 3),
             r.judged ? num(r.tolerance, 3) : "-", r.judged ? (r.pass ? "pass" : "FAIL") : "report"});
      (r.judged ? (r.pass ? passed : failed) : reported)++;
    }
  std::printf("%s", t.text().c_str());
  std::printf("validate: %d passed, %d failed", passed, failed);
  std::printf(reported ? ", %d reported (no target)" : "", reported);
  std::printf(" (%zu cases in %.0f s, --jobs %d; one case: huygens validate CASE)\n", todo.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), a.jobs);
  return failed ? 1 : 0;
}

}  // namespace huygens
