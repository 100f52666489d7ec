// The solver registry (huygens/solvers/registry.hpp).
#include "huygens/solvers/registry.hpp"

#include <stdexcept>

#include "huygens/lbm/lbm_solver.hpp"
#include "huygens/spectral/spectral_solver.hpp"
#include "huygens/sph/sph_solver.hpp"

namespace huygens {

namespace {

// The library's solvers: one line each.
std::vector<SolverEntry> builtin_solvers() {
  return {
      huygens_solver_entry(),
      sph_solver_entry(),
      lbm_solver_entry(),
  };
}

std::vector<SolverEntry>& registry() {
  static std::vector<SolverEntry> entries = builtin_solvers();
  return entries;
}

}  // namespace

void register_solver(SolverEntry entry) {
  if (entry.name.empty()) throw std::invalid_argument("register_solver: an entry needs a name");
  if (!entry.make || !entry.sizing || !entry.rank_memory)
    throw std::invalid_argument("register_solver: \"" + entry.name + "\" needs make, sizing and rank_memory");
  for (const SolverEntry& e : registry())
    if (e.name == entry.name) throw std::invalid_argument("register_solver: \"" + entry.name + "\" is registered");
  registry().push_back(std::move(entry));
}

const std::vector<SolverEntry>& registered_solvers() { return registry(); }

const SolverEntry& solver_entry(const std::string& name) {
  std::string names;
  for (const SolverEntry& e : registry()) {
    if (e.name == name) return e;
    names += (names.empty() ? "\"" : ", \"") + e.name + "\"";
  }
  throw SceneError("$.solver", "\"" + name + "\" is not one of " + names + " (the registered solvers)");
}

std::unique_ptr<Solver> make_solver(const Scene& scene, const RunOptions& options) {
  return solver_entry(scene.solver).make(scene, options);
}

}  // namespace huygens
