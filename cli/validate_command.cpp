// huygens validate: the analytic validation cases (validation/), as a table of measured against
// expected values with their tolerances; exit 1 when a case fails.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/validation/validation.hpp"

namespace huygens {

int cmd_validate(int argc, char** argv) {
  std::vector<std::string> names;
  bool list = false;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--list")
      list = true;
    else if (a == "--help" || a == "-h") {
      print_usage();
      return 0;
    } else if (!a.empty() && a[0] == '-')
      throw UsageError("unknown option " + a);
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
    if (!found) throw UsageError("unknown validation case '" + n + "' (huygens validate --list)");
  }
  Table t({"case", "quantity", "measured", "expected", "error", "tolerance", "result"});
  int failed = 0, passed = 0, reported = 0;
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
      t.add({r.case_name, r.quantity, num(r.measured, 6), num(r.expected, 6), num(r.error, 3),
             r.judged ? num(r.tolerance, 3) : "-", r.judged ? (r.pass ? "pass" : "FAIL") : "report"});
      (r.judged ? (r.pass ? passed : failed) : reported)++;
    }
  }
  std::printf("%s", t.text().c_str());
  std::printf("validate: %d passed, %d failed", passed, failed);
  std::printf(reported ? ", %d reported (no target)\n" : "\n", reported);
  return failed ? 1 : 0;
}

}  // namespace huygens
