#pragma once
// Analytic validation cases shared by `huygens validate` and the GoogleTest suites:
// a test asserts that a case passes, the program prints the same rows as a table.
#include <functional>
#include <string>
#include <vector>

namespace huygens {

/// One checked quantity: pass means error <= tolerance.
struct ValidationRow {
  std::string case_name;
  std::string quantity;  ///< what was measured, with its unit
  double measured = 0;
  double expected = 0;
  double error = 0;      ///< as the case defines it (relative or absolute, see quantity)
  double tolerance = 0;
  bool pass = false;
};

struct ValidationCase {
  std::string name;         ///< short id used on the command line, e.g. "phase_speed"
  std::string solver;       ///< "huygens", "sph" or "lbm"
  std::string description;  ///< one line
  std::function<std::vector<ValidationRow>()> run;
};

/// Helper: a row whose pass flag is error <= tolerance.
ValidationRow check(std::string case_name, std::string quantity, double measured, double expected,
                    double error, double tolerance);

std::vector<ValidationCase> huygens_validation_cases();
std::vector<ValidationCase> sph_validation_cases();
std::vector<ValidationCase> lbm_validation_cases();
/// All cases, Huygens first.
std::vector<ValidationCase> all_validation_cases();

}  // namespace huygens
