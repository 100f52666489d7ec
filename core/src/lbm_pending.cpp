// Placeholder until the lbm solver lands: its scene is refused with a clear message.
// Delete this file when core/src/ gets the real make_lbm_solver and lbm_validation_cases.
#include "huygens/solver.hpp"
#include "huygens/validation.hpp"

namespace huygens {

std::unique_ptr<Solver> make_lbm_solver(const Scene&, const RunOptions&) {
  throw SceneError("$.solver", "the \"lbm\" solver is not yet supported by this build");
}

std::vector<ValidationCase> lbm_validation_cases() { return {}; }

}  // namespace huygens
