#pragma once
// What the LBM sources share inside the module (not installed): the D2Q9 link tables, one cell's
// nine populations, the bed terms and the BGK collision (paper 002 eq. 1-4), used by the all-wet
// kernel (kernel.cpp) and the wet/dry pass (wet_dry.cpp) alike.
#include <cstddef>
#include <sstream>
#include <string>

namespace huygens::lbm_cell {

inline constexpr int kEx[9] = {0, 1, 0, -1, 0, 1, -1, -1, 1};
inline constexpr int kEy[9] = {0, 0, 1, 0, -1, 1, 1, -1, -1};
inline constexpr int kOpp[9] = {0, 3, 4, 1, 2, 7, 8, 5, 6};
inline constexpr int kMirrorX[9] = {0, 3, 2, 1, 4, 6, 5, 8, 7};
inline constexpr int kMirrorY[9] = {0, 1, 4, 3, 2, 8, 7, 6, 5};
inline constexpr double kLambda[9] = {0, 1, 1, 1, 1, 0.25, 0.25, 0.25, 0.25};

// A number in 4 significant digits, for messages.
inline std::string g6(double x) {
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

inline const char* side_name(int i) {
  static const char* n[4] = {"left", "right", "bottom", "top"};
  return n[i];
}

// The nine populations of one cell (shifted by the still-water equilibrium, unit: m).
struct Cell9 {
  float f0, f1, f2, f3, f4, f5, f6, f7, f8;
};

// Centred bed term added to the pulled populations, k1 = g/6, k5 = g/24 (lattice units):
//   S_a = -lambda_a g (h(x) + h(x - e_a)) (z(x) - z(x - e_a)) / 6
[[gnu::always_inline]] inline void add_centred_bed(Cell9& f, const float* __restrict h, const float* __restrict z,
                                                   std::ptrdiff_t c, std::ptrdiff_t S, float k1, float k5) {
  const float hc = h[c], zc = z[c];
  f.f1 -= k1 * (hc + h[c - 1]) * (zc - z[c - 1]);
  f.f2 -= k1 * (hc + h[c - S]) * (zc - z[c - S]);
  f.f3 -= k1 * (hc + h[c + 1]) * (zc - z[c + 1]);
  f.f4 -= k1 * (hc + h[c + S]) * (zc - z[c + S]);
  f.f5 -= k5 * (hc + h[c - S - 1]) * (zc - z[c - S - 1]);
  f.f6 -= k5 * (hc + h[c - S + 1]) * (zc - z[c - S + 1]);
  f.f7 -= k5 * (hc + h[c + S + 1]) * (zc - z[c + S + 1]);
  f.f8 -= k5 * (hc + h[c + S - 1]) * (zc - z[c + S - 1]);
}

// Naive bed term: F = -g h(x) grad z_b (central difference at x); S_a = lambda_a e_a.F / 3.
[[gnu::always_inline]] inline void add_naive_bed(Cell9& f, const float* __restrict h, const float* __restrict z,
                                                 std::ptrdiff_t c, std::ptrdiff_t S, float g) {
  const float gh = -0.5f * g * h[c];
  const float fx = gh * (z[c + 1] - z[c - 1]), fy = gh * (z[c + S] - z[c - S]);
  f.f1 += fx * (1.0f / 3.0f);
  f.f3 -= fx * (1.0f / 3.0f);
  f.f2 += fy * (1.0f / 3.0f);
  f.f4 -= fy * (1.0f / 3.0f);
  f.f5 += (fx + fy) * (1.0f / 12.0f);
  f.f7 -= (fx + fy) * (1.0f / 12.0f);
  f.f6 += (fy - fx) * (1.0f / 12.0f);
  f.f8 -= (fy - fx) * (1.0f / 12.0f);
}

// Constants of the collision: omega = 1/tau, g_lat (1/m), the force a dt^2/dx, H and h_min (m).
struct Collision {
  float w, g, ax, ay, hmin, href, umax2 = 0.0f;
};

// BGK collision (paper 002 eq. 1) of a cell's pulled populations f: moments (eq. 3-4) and the
// equilibrium (eq. 2), both minus the shift, plus the force lambda_a h (e_a . a) / 3 (Force; with
// a = 0 the force adds exact zeros: the force-free form gives the same floats, up to the sign of a
// zero). Writes the new depth h; `bad` counts h < h_min (also NaN).
template <bool Cap = false, bool Force = true>
[[gnu::always_inline]] inline Cell9 collide(const Cell9& f, const Collision& k, float& h, float& bad) {
  const float f0 = f.f0, f1 = f.f1, f2 = f.f2, f3 = f.f3, f4 = f.f4, f5 = f.f5, f6 = f.f6, f7 = f.f7, f8 = f.f8;
  // moments of the shifted populations: dh = h - H exactly as precise as the wave
  const float dh = ((f0 + f1) + (f2 + f3)) + ((f4 + f5) + (f6 + f7)) + f8;
  h = k.href + dh;
  const float mx = (f1 + f5 + f8) - (f3 + f6 + f7);
  const float my = (f2 + f5 + f6) - (f4 + f7 + f8);
  const float ih = h > k.hmin ? 1.0f / h : 0.0f;
  bad += h >= k.hmin ? 0.0f : 1.0f;
  float ux = mx * ih, uy = my * ih;
  float w = k.w;
  if constexpr (Cap) {  // |u| <= u_max (wet/dry pass: the thin layer at a front)
    const float u2 = ux * ux + uy * uy;
    const float r = u2 > k.umax2 ? std::sqrt(k.umax2 / u2) : 1.0f;
    ux *= r;
    uy *= r;
    w = r < 1.0f ? 1.0f : w;
  }
  // equilibrium minus the shift: axis base g (h^2 - H^2)/6 - h u.u/6;
  // rest = dh - sum of the others (so the shifted equilibria sum to dh: mass exact)
  const float usq = ux * ux + uy * uy;
  const float base = (k.g * dh * (h + k.href) - h * usq) * (1.0f / 6.0f);
  const float hh = 0.5f * h, h3 = h * (1.0f / 3.0f);
  const float q1 = base + hh * ux * ux, q2 = base + hh * uy * uy;
  const float e1 = q1 + h3 * ux, e3 = q1 - h3 * ux;
  const float e2 = q2 + h3 * uy, e4 = q2 - h3 * uy;
  const float s5 = ux + uy, s6 = uy - ux;
  const float q5 = 0.25f * (base + hh * s5 * s5), q6 = 0.25f * (base + hh * s6 * s6);
  const float e5 = q5 + 0.25f * h3 * s5, e7 = q5 - 0.25f * h3 * s5;
  const float e6 = q6 + 0.25f * h3 * s6, e8 = q6 - 0.25f * h3 * s6;
  const float e0 = dh - (((e1 + e2) + (e3 + e4)) + ((e5 + e6) + (e7 + e8)));
  if constexpr (!Force)
    return {f0 + w * (e0 - f0), f1 + w * (e1 - f1), f2 + w * (e2 - f2), f3 + w * (e3 - f3), f4 + w * (e4 - f4),
            f5 + w * (e5 - f5), f6 + w * (e6 - f6), f7 + w * (e7 - f7), f8 + w * (e8 - f8)};
  const float gx = h3 * k.ax, gy = h3 * k.ay;
  const float g5 = 0.25f * (gx + gy), g6 = 0.25f * (gy - gx);
  return {f0 + w * (e0 - f0),      f1 + w * (e1 - f1) + gx, f2 + w * (e2 - f2) + gy,
          f3 + w * (e3 - f3) - gx, f4 + w * (e4 - f4) - gy, f5 + w * (e5 - f5) + g5,
          f6 + w * (e6 - f6) + g6, f7 + w * (e7 - f7) - g5, f8 + w * (e8 - f8) - g6};
}

}  // namespace huygens::lbm_cell
