// The toy solver's one registration: linked into a program as an object file, its static
// initializer adds the entry before main (solvers/registry.hpp).
#include "huygens/solvers/registry.hpp"
#include "toy_solver.hpp"

namespace {
const bool kRegistered = [] {
  huygens::register_solver(huygens::toy::toy_solver_entry());
  return true;
}();
}  // namespace
