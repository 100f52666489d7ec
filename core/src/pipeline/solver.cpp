#include "huygens/pipeline/solver.hpp"

#include "huygens/pipeline/registry.hpp"

namespace huygens {

std::unique_ptr<Solver> make_solver(const Scene& scene, const RunOptions& options) {
  return solver_entry(scene.solver).make(scene, options);
}

}  // namespace huygens
