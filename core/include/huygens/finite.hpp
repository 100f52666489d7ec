#pragma once
// Cheap checks for non-finite values after a stage (DESIGN.md 7, failure containment).
// Vectorised: sums x - x over the array (0 for finite x, NaN for NaN or infinity).
#include <span>

#include "huygens/fft.hpp"

namespace huygens {

/// True when every value is finite.
bool all_finite(std::span<const float> v);
/// True when every real and imaginary part is finite.
bool all_finite(std::span<const cfloat> v);

}  // namespace huygens
