// The MCG03 kernels (eq. 20-22) and the cubic spline: see huygens/sph/kernels.hpp.
#include "huygens/sph/kernels.hpp"

#include <cmath>
#include <numbers>

namespace huygens {

namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

SphKernels::SphKernels(float support)
    : h(support),
      h2(support * support),
      poly6_k(static_cast<float>(315.0 / (64.0 * kPi * std::pow(double(support), 9)))),
      spiky_k(static_cast<float>(45.0 / (kPi * std::pow(double(support), 6)))),
      cubic_k(static_cast<float>(8.0 / (kPi * std::pow(double(support), 3)))),
      cubic_g(static_cast<float>(48.0 / (kPi * std::pow(double(support), 5)))) {}

float SphKernels::viscosity(float r) const {
  if (r >= h || r <= 0.f) return 0.f;
  const double hd = h, rd = r;
  return static_cast<float>(15.0 / (2.0 * kPi * hd * hd * hd) *
                            (-rd * rd * rd / (2 * hd * hd * hd) + rd * rd / (hd * hd) + hd / (2 * rd) - 1.0));
}

}  // namespace huygens
