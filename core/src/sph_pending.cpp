// Placeholder until the sph solver lands: its scene is refused with a clear message.
// Delete this file when core/src/ gets the real make_sph_solver and sph_validation_cases.
#include "huygens/solver.hpp"
#include "huygens/validation.hpp"

namespace huygens {

std::unique_ptr<Solver> make_sph_solver(const Scene&, const RunOptions&) {
  throw SceneError("$.solver", "the \"sph\" solver is not yet supported by this build");
}

std::vector<ValidationCase> sph_validation_cases() { return {}; }

}  // namespace huygens
