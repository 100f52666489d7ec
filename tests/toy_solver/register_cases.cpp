// The toy solver's validation cases, registered for the programs that link the validation library
// (huygens validate, huygens-bench).
#include "toy_solver.hpp"

namespace {
const bool kRegistered = [] {
  huygens::register_validation_cases("toy", huygens::toy::toy_validation_cases);
  return true;
}();
}  // namespace
