#pragma once
// What the programs need to know of a solver besides its Solver interface: one SolverEntry per
// solver, which each solver's adapter gives and the registry (huygens/solvers/registry.hpp) holds.
// Data only, so an adapter depends on the pipeline and not on the registry above it.
#include <functional>
#include <memory>
#include <string>

#include "huygens/common/memory.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"

namespace huygens {

/// What splitting a scene over ranks depends on.
struct SceneSizing {
  /// The solver's registered name ("huygens", "sph", "lbm").
  std::string solver;
  /// The grid as text ("512 x 512", "200 rows x 400 cols"); "" for SPH.
  std::string grid;
  /// The most ranks it can run on (LBM: 3 rows per rank at least; Huygens: a row per rank).
  int max_ranks = 1 << 16;
  /// False for SPH (one process whatever P).
  bool distributed = true;
  /// Why max_ranks is the limit ("a row per rank at least"); for a refusal's message.
  std::string split_rule = "a row per rank at least";
};

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

}  // namespace huygens
