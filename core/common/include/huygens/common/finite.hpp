#pragma once
// Cheap checks for non-finite values after a stage (docs/design.md 7, failure containment).
// Vectorised: sums x - x over the array (0 for finite x, NaN for NaN or infinity).
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "huygens/common/fft.hpp"

namespace huygens {

/// True when every value is finite.
bool all_finite(std::span<const float> v);
/// True when every real and imaginary part is finite.
bool all_finite(std::span<const cfloat> v);

/// The run cannot go on: a stage left the state no longer a solution. Names the stage and the step; every
/// output written before the step stands. The one type programs catch for "the run stopped" (the CLI's
/// exit 3, the runner's failed state, Python's RunStopped); each solver's own stops derive from it.
class RunStopped : public std::runtime_error {
 public:
  RunStopped(std::string stage, std::int64_t step, const std::string& what)
      : std::runtime_error(what), stage_(std::move(stage)), step_(step) {}
  const std::string& stage() const { return stage_; }
  std::int64_t step() const { return step_; }

 private:
  std::string stage_;
  std::int64_t step_;
};

/// Raised when a stage produced a non-finite value; names the stage and the step.
class NonFiniteError : public RunStopped {
 public:
  NonFiniteError(std::string stage, std::int64_t step)
      : RunStopped(stage, step, "non-finite value produced by stage '" + stage + "' at step " + std::to_string(step)) {}
};

}  // namespace huygens
