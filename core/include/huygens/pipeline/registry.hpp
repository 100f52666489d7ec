#pragma once
// The solver registry: one entry per solver, found by the scene's "solver" name. The CLI (run,
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

#include "huygens/common/memory.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/sizing.hpp"
#include "huygens/pipeline/solver.hpp"

namespace huygens {

/// What the programs need to know of a solver besides its Solver interface.
struct SolverEntry {
  /// The scene's "solver" value ("huygens", "sph", "lbm").
  std::string name;
  /// One line for lists and --help: what it solves.
  std::string summary;
  /// Builds the solver from the scene (parses its block; throws SceneError naming the JSON path;
  /// checks the memory estimate before allocating).
  std::function<std::unique_ptr<Solver>(const Scene&, const RunOptions&)> make;
  /// The grid and how far the scene splits over MPI ranks (no allocation). Throws SceneError.
  std::function<SceneSizing(const Scene&)> sizing;
  /// The memory of the largest of P ranks as a function of P, from the scene alone (nothing
  /// allocated; `scene` outlives the function). Throws SceneError.
  std::function<std::function<MemoryEstimate(int)>(const Scene&)> rank_memory;
  /// A representative scene (JSON text) that huygens-bench's "solvers" section steps.
  std::string bench_scene;
  /// Steps of bench_scene the "solvers" section times (--quick: a quarter).
  int bench_steps = 100;
};

/// Adds a solver. Throws std::invalid_argument for an empty name, a missing function or a name
/// already registered. Not thread-safe: register before the programs start threads (static
/// initializers, main).
void register_solver(SolverEntry entry);

/// Every registered solver, the library's first (huygens, sph, lbm), then in registration order.
const std::vector<SolverEntry>& registered_solvers();

/// The entry of the scene's solver. Throws SceneError("$.solver", ...) listing the registered names.
const SolverEntry& solver_entry(const std::string& name);

}  // namespace huygens
