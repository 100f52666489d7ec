// A scene sized for P MPI ranks (huygens/solvers/sizing.hpp): each solver's own estimate, through
// its registry entry.
#include "huygens/solvers/sizing.hpp"

#include "huygens/solvers/registry.hpp"

namespace huygens {

SceneSizing scene_sizing(const Scene& scene) { return solver_entry(scene.solver).sizing(scene); }

std::function<MemoryEstimate(int)> scene_rank_memory(const Scene& scene) {
  return solver_entry(scene.solver).rank_memory(scene);
}

}  // namespace huygens
