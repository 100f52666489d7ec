#pragma once
// Cubic time interpolation of displayed frames between full steps (paper 004 section 3,
// docs/design.md 3.5): the cubic Hermite interpolant of eta and etadot at both ends,
//   eta(t + s dt) = h00(s) eta0 + h01(s) eta1 + dt (h10(s) etadot0 + h11(s) etadot1),
//   h00 = 2s^3 - 3s^2 + 1,  h01 = -2s^3 + 3s^2,  h10 = s^3 - 2s^2 + s,  h11 = s^3 - s^2.
// At s = 1/3: 20/27, 7/27, 4/27 dt, -2/27 dt (the paper's weights). Exact for cubics in t;
// the error for a mode of frequency omega is O((omega dt)^4).
#include <cstddef>

namespace huygens {

/// Weights of the interpolant at one s; d0 and d1 multiply dt * etadot.
struct HermiteWeights {
  /// Weight of eta at the start of the step (unit: 1).
  double e0 = 1.0;
  /// Weight of eta at the end of the step (unit: 1).
  double e1 = 0.0;
  /// Weight of dt * etadot at the start (unit: 1).
  double d0 = 0.0;
  /// Weight of dt * etadot at the end (unit: 1).
  double d1 = 0.0;
};

/// Weights at s in [0, 1].
HermiteWeights hermite_weights(double s);
/// Weights at s = j / d computed from exact integers (so s = 1/3 gives exactly the doubles
/// 20.0/27, 7.0/27, 4.0/27, -2.0/27): use for display frame j of d per step.
HermiteWeights hermite_weights(int j, int d);

/// out[i] = e0 eta0[i] + e1 eta1[i] + dt (d0 etadot0[i] + d1 etadot1[i]) over n floats
/// (vectorised, OpenMP over chunks; out may alias none of the inputs). dt in s.
void hermite_interpolate(const float* eta0, const float* etadot0, const float* eta1, const float* etadot1,
                         std::size_t n, const HermiteWeights& w, double dt, float* out);

}  // namespace huygens
