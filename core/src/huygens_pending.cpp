// Placeholder until the huygens solver lands: its scene is refused with a clear message.
// Delete this file when core/src/ gets the real make_huygens_solver and huygens_validation_cases.
#include "huygens/solver.hpp"
#include "huygens/validation.hpp"

namespace huygens {

std::unique_ptr<Solver> make_huygens_solver(const Scene&, const RunOptions&) {
  throw SceneError("$.solver", "the \"huygens\" solver is not yet supported by this build");
}

std::vector<ValidationCase> huygens_validation_cases() { return {}; }

}  // namespace huygens
