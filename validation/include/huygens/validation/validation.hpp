#pragma once
// The row and case types and the case registry of the validation library, shared by
// `huygens validate` (prints every row as a table) and the GoogleTest suites (assert that the
// rows pass). Beside it: huygens_cases.hpp (smaller Kelvin, capillary and Froude runs for the
// tests), lbm_cases.hpp (the LBM runs behind the cases, at any size), sph_cases.hpp (the SPH
// cases at any size), reference/ (Cauchy-Poisson ring, Kelvin wake measurement, Martin & Moyce).
#include <functional>
#include <string>
#include <vector>

namespace huygens {

/// One checked quantity: pass means error <= tolerance. A reported row (judged = false) shows a
/// quantity worth seeing that is not a target (no tolerance, neither pass nor fail).
struct ValidationRow {
  std::string case_name;
  std::string quantity;  ///< what was measured, with its unit
  double measured = 0;
  double expected = 0;
  double error = 0;  ///< as the case defines it (relative or absolute, see quantity)
  double tolerance = 0;
  bool pass = false;
  bool judged = true;  ///< false: reported only, counted neither as passed nor as failed
};

/// A named validation case: `run` computes its rows (seconds to minutes at full size).
struct ValidationCase {
  std::string name;         ///< short id used on the command line, e.g. "phase_speed"
  std::string solver;       ///< "huygens", "sph" or "lbm"
  std::string description;  ///< one line
  std::function<std::vector<ValidationRow>()> run;
};

/// Helper: a row whose pass flag is error <= tolerance (false when error is not finite).
ValidationRow check(std::string case_name, std::string quantity, double measured, double expected, double error,
                    double tolerance);

/// Helper: a reported row, shown with its error but without tolerance or pass/fail.
ValidationRow report_only(std::string case_name, std::string quantity, double measured, double expected, double error);

/// The cases of each solver, in the order `huygens validate` runs them (defined in
/// huygens_cases.cpp, sph_cases.cpp and lbm_cases.cpp).
std::vector<ValidationCase> huygens_validation_cases();
std::vector<ValidationCase> sph_validation_cases();
std::vector<ValidationCase> lbm_validation_cases();
/// Adds the cases of a solver outside the library (its registry name, solvers/registry.hpp); the
/// library's own are listed in validation.cpp, one line per solver. Not thread-safe: call it from a
/// static initializer or main.
void register_validation_cases(const std::string& solver, std::function<std::vector<ValidationCase>()> cases);
/// All cases, in the order of the solver registry (Huygens, SPH, LBM, then the registered ones).
std::vector<ValidationCase> all_validation_cases();

}  // namespace huygens
