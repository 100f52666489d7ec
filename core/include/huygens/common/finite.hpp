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

/// Raised when a stage produced a non-finite value; names the stage and the step.
class NonFiniteError : public std::runtime_error {
 public:
  NonFiniteError(std::string stage, std::int64_t step)
      : std::runtime_error("non-finite value produced by stage '" + stage + "' at step " + std::to_string(step)),
        stage_(std::move(stage)),
        step_(step) {}
  const std::string& stage() const { return stage_; }
  std::int64_t step() const { return step_; }

 private:
  std::string stage_;
  std::int64_t step_;
};

}  // namespace huygens
