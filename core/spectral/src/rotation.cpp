// The phase rotation of the Huygens step: the formulas of rotation.hpp.
#include "huygens/spectral/rotation.hpp"

#include <cmath>
#include <numbers>

namespace huygens {

RotationEntry rotation_entry(Rotation kind, double omega_dt, double scale) {
  constexpr double kPi = std::numbers::pi;
  double phi = std::remainder(-omega_dt, 2.0 * kPi);
  if (kind == Rotation::complex)
    return {static_cast<float>(std::cos(phi) * scale), static_cast<float>(std::sin(phi) * scale),
            static_cast<float>(scale)};
  double sign = 1.0;  // lift only |phi| <= pi/2, where |tan(phi/2)| <= 1
  if (phi > kPi / 2) phi -= kPi, sign = -1.0;
  if (phi < -kPi / 2) phi += kPi, sign = -1.0;
  const float t = static_cast<float>(std::tan(0.5 * phi));
  const double sh = std::sin(0.5 * phi);
  const float s = t == 0.0f ? 0.0f : static_cast<float>(2.0 * sh * sh / static_cast<double>(t));
  return {t, s, static_cast<float>(sign * scale)};
}

namespace {
// The lifting of one complex value (x, y) at column col by entries a, b, c (rotation.hpp).
[[gnu::always_inline]] inline void lift(const float* sr, float* zr, int col, float a, float b, float c) {
  float x = c * sr[2 * col], y = c * sr[2 * col + 1];
  x -= a * y;
  y += b * x;
  x -= a * y;
  zr[2 * col] = x;
  zr[2 * col + 1] = y;
}
}  // namespace

void rotate_row(Rotation kind, const float* a, const float* b, const float* c, const float* sr, float* zr, int n,
                float scale) {
  const int h = n / 2;
  if (kind == Rotation::complex) {
#pragma omp simd
    for (int col = 0; col < n; ++col) {
      const int j = col <= h ? col : n - col;
      const float x = sr[2 * col], y = sr[2 * col + 1], aj = a[j] * scale, bj = b[j] * scale;
      zr[2 * col] = aj * x - bj * y;
      zr[2 * col + 1] = aj * y + bj * x;
    }
    return;
  }
  if (scale != 1.0f) {
#pragma omp simd
    for (int col = 0; col <= h; ++col) lift(sr, zr, col, a[col], b[col], c[col] * scale);
#pragma omp simd
    for (int col = h + 1; col < n; ++col) lift(sr, zr, col, a[n - col], b[n - col], c[n - col] * scale);
    return;
  }
  // columns 0..N/2 read the tables forward, N/2+1..N-1 backward: two loops, each contiguous
#pragma omp simd
  for (int col = 0; col <= h; ++col) lift(sr, zr, col, a[col], b[col], c[col]);
#pragma omp simd
  for (int col = h + 1; col < n; ++col) lift(sr, zr, col, a[n - col], b[n - col], c[n - col]);
}

}  // namespace huygens
