#include "huygens/validation/validation.hpp"

#include <cmath>
#include <utility>

#include "huygens/solvers/registry.hpp"

namespace huygens {

ValidationRow check(std::string case_name, std::string quantity, double measured, double expected, double error,
                    double tolerance) {
  return ValidationRow{std::move(case_name),
                       std::move(quantity),
                       measured,
                       expected,
                       error,
                       tolerance,
                       std::isfinite(error) && error <= tolerance};
}

ValidationRow report_only(std::string case_name, std::string quantity, double measured, double expected, double error) {
  ValidationRow r{std::move(case_name), std::move(quantity), measured, expected, error, NAN, true};
  r.judged = false;
  return r;
}

namespace {

using CaseSource = std::pair<std::string, std::function<std::vector<ValidationCase>()>>;

// The library's solvers' cases: one line each.
std::vector<CaseSource>& case_sources() {
  static std::vector<CaseSource> sources = {
      {"huygens", huygens_validation_cases},
      {"sph", sph_validation_cases},
      {"lbm", lbm_validation_cases},
  };
  return sources;
}

}  // namespace

void register_validation_cases(const std::string& solver, std::function<std::vector<ValidationCase>()> cases) {
  case_sources().emplace_back(solver, std::move(cases));
}

std::vector<ValidationCase> all_validation_cases() {
  std::vector<ValidationCase> all;
  for (const SolverEntry& e : registered_solvers())
    for (const CaseSource& source : case_sources())
      if (source.first == e.name)
        for (ValidationCase& c : source.second()) all.push_back(std::move(c));
  return all;
}

}  // namespace huygens
