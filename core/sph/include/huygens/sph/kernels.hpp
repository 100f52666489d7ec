#pragma once
// The smoothing kernels of Mueller, Charypar and Gross 2003 (MCG03 eq. 20-22), h = support
// radius (unit: m), r = |x_i - x_j| (unit: m), all zero for r >= h:
//   poly6      W(r)      = 315 / (64 pi h^9) (h^2 - r^2)^3        density
//   spiky      grad W(r) = -45 / (pi h^6) (h - r)^2 x_ij / r      pressure force
//   viscosity  lap W(r)  =  45 / (pi h^6) (h - r)                 viscous force
// and, for the DFSPH solver (dfsph.hpp), the cubic spline of Monaghan 1992 in the form with
// compact support h (q = r / h; Bender and Koschier 2015 use it for value and gradient alike):
//   cubic      W(r)      = 8 / (pi h^3) (6 q^3 - 6 q^2 + 1)  for q <= 1/2,  16 / (pi h^3) (1 - q)^3  for q < 1
//   cubic      grad W(r) = -48 / (pi h^5) f(q) x_ij,  f = 2 - 3 q  (q <= 1/2),  (1 - q)^2 / q  (q < 1)
// Inline so the neighbour loops, the tests and the brute-force reference use the same code.

namespace huygens {

/// The MCG03 kernels for one support radius h.
struct SphKernels {
  /// Support radius h (unit: m) and h^2 (unit: m^2).
  float h, h2;
  /// 315 / (64 pi h^9) (unit: 1/m^9).
  float poly6_k;
  /// 45 / (pi h^6): the spiky gradient's and the viscosity Laplacian's factor (unit: 1/m^6).
  float spiky_k;
  /// Cubic spline: 8 / (pi h^3) (unit: 1/m^3) and its gradient's factor 48 / (pi h^5) (unit: 1/m^5).
  float cubic_k, cubic_g;
  explicit SphKernels(float support);
  /// Poly6 value of r^2 (unit: 1/m^3; r2 in m^2).
  float poly6(float r2) const {
    const float q = h2 - r2;
    return q > 0.f ? poly6_k * q * q * q : 0.f;
  }
  /// Spiky kernel value 15 / (pi h^6) (h - r)^3 (unit: 1/m^3).
  float spiky(float r) const { return r < h ? spiky_k / 3.f * (h - r) * (h - r) * (h - r) : 0.f; }
  /// dW_spiky/dr = -45 / (pi h^6) (h - r)^2 (unit: 1/m^4).
  float spiky_dr(float r) const { return r < h ? -spiky_k * (h - r) * (h - r) : 0.f; }
  /// Cubic spline value (unit: 1/m^3).
  float cubic(float r) const {
    const float q = r / h;
    return q <= 0.5f ? cubic_k * (6.f * q * q * q - 6.f * q * q + 1.f)
                     : (q < 1.f ? 2.f * cubic_k * (1.f - q) * (1.f - q) * (1.f - q) : 0.f);
  }
  /// f(q) of the cubic spline gradient, grad W = -cubic_g f x_ij (unit: 1).
  static float cubic_f(float q) { return q <= 0.5f ? 2.f - 3.f * q : (q < 1.f ? (1.f - q) * (1.f - q) / q : 0.f); }
  /// dW_cubic/dr = -48 / (pi h^5) f(q) r (unit: 1/m^4).
  float cubic_dr(float r) const { return -cubic_g * cubic_f(r / h) * r; }
  /// Viscosity kernel value 15 / (2 pi h^3) (-r^3/(2h^3) + r^2/h^2 + h/(2r) - 1) (unit: 1/m^3).
  float viscosity(float r) const;
  /// Laplacian of the viscosity kernel 45 / (pi h^6) (h - r) (unit: 1/m^5).
  float viscosity_lap(float r) const { return r < h ? spiky_k * (h - r) : 0.f; }
};

}  // namespace huygens
