#include "huygens/validation/validation.hpp"

#include <cmath>

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

std::vector<ValidationCase> all_validation_cases() {
  std::vector<ValidationCase> all = huygens_validation_cases();
  for (auto& c : sph_validation_cases()) all.push_back(std::move(c));
  for (auto& c : lbm_validation_cases()) all.push_back(std::move(c));
  return all;
}

}  // namespace huygens
