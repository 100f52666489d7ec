#pragma once
// The solver registry: one entry (pipeline/solver_entry.hpp) per solver, found by the scene's
// "solver" name. The one target that links every solver (huygens_solvers). The CLI (run,
// --dry-run), the Python package, the viewer, `huygens validate` and huygens-bench's "solvers"
// section iterate it; none of them names a solver. A new solver is a folder with its adapter and one
// registration (docs/design.md, "Add a solver"):
//   * a solver of the library: a line in builtin_solvers() (registry.cpp);
//   * a solver outside the library (tests/toy_solver/): register_solver() from a static initializer
//     in an object file linked into the program.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/pipeline/solver_entry.hpp"

namespace huygens {

/// Adds a solver. Throws std::invalid_argument for an empty name, a missing function or a name
/// already registered. Not thread-safe: register before the programs start threads (static
/// initializers, main).
void register_solver(SolverEntry entry);

/// Every registered solver, the library's first (huygens, sph, lbm), then in registration order.
const std::vector<SolverEntry>& registered_solvers();

/// The entry of the scene's solver. Throws SceneError("$.solver", ...) listing the registered names.
const SolverEntry& solver_entry(const std::string& name);

/// Builds the solver the scene names (its entry's make). Throws SceneError (JSON path) for a bad scene.
std::unique_ptr<Solver> make_solver(const Scene& scene, const RunOptions& options = {});

}  // namespace huygens
