#include "huygens/common/finite.hpp"

#include <cmath>

namespace huygens {

bool all_finite(std::span<const float> v) {
  // x - x is 0 for finite x and NaN otherwise; NaN survives the sum. Built without
  // -ffast-math, so the compiler keeps the test (and vectorises the loop).
  float acc = 0.0f;
  const float* p = v.data();
  const long n = static_cast<long>(v.size());
#pragma omp simd reduction(+ : acc)
  for (long i = 0; i < n; ++i) acc += p[i] - p[i];
  return acc == 0.0f;
}

bool all_finite(std::span<const cfloat> v) {
  return all_finite(std::span<const float>(reinterpret_cast<const float*>(v.data()), 2 * v.size()));
}

}  // namespace huygens
