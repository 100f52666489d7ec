#include "huygens/common/time_interp.hpp"

#include <cstdint>

namespace huygens {

HermiteWeights hermite_weights(double s) {
  const double s2 = s * s, s3 = s2 * s;
  return {2.0 * s3 - 3.0 * s2 + 1.0, -2.0 * s3 + 3.0 * s2, s3 - 2.0 * s2 + s, s3 - s2};
}

HermiteWeights hermite_weights(int j, int d) {
  // numerators over d^3, exact in 64-bit integers; one rounding per weight
  const std::int64_t J = j, D = d, D3 = D * D * D;
  const double den = static_cast<double>(D3);
  return {static_cast<double>(2 * J * J * J - 3 * J * J * D + D3) / den,
          static_cast<double>(-2 * J * J * J + 3 * J * J * D) / den,
          static_cast<double>(J * J * J - 2 * J * J * D + J * D * D) / den,
          static_cast<double>(J * J * J - J * J * D) / den};
}

void hermite_interpolate(const float* eta0, const float* etadot0, const float* eta1, const float* etadot1,
                         std::size_t n, const HermiteWeights& w, double dt, float* out) {
  const float a = static_cast<float>(w.e0), b = static_cast<float>(w.e1);
  const float c = static_cast<float>(w.d0 * dt), d = static_cast<float>(w.d1 * dt);
  const long long total = static_cast<long long>(n);
#pragma omp parallel for simd schedule(static) if (total > 65536)
  for (long long i = 0; i < total; ++i) out[i] = a * eta0[i] + b * eta1[i] + c * etadot0[i] + d * etadot1[i];
}

}  // namespace huygens
