#include "huygens/pipeline/solver.hpp"

#include "huygens/huygens/solver.hpp"
#include "huygens/lbm/solver.hpp"
#include "huygens/sph/solver.hpp"

namespace huygens {

std::unique_ptr<Solver> make_solver(const Scene& scene, const RunOptions& options) {
  if (scene.solver == "huygens") return make_huygens_solver(scene, options);
  if (scene.solver == "sph") return make_sph_solver(scene, options);
  if (scene.solver == "lbm") return make_lbm_solver(scene, options);
  throw SceneError("$.solver", "unknown solver \"" + scene.solver + "\"");
}

}  // namespace huygens
