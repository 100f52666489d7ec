#pragma once
// The SPH pair sums of one step over one contiguous index range [b, e) of the cell-sorted arrays
// (Mueller, Charypar and Gross 2003 eq. 3, 10 and 14; Monaghan 1992 eq. 4.1-4.2), h = support
// radius, r = |x_ij|, x_ij = x_i - x_j, P = l p / rho^2 (Bonet and Lok 1999 correction l):
//   density  sum_j (h^2 - r^2)^3                            (x m 315/(64 pi h^9) = rho_i)
//   moment   sum_j (h - r)^2 r                               (x m/rho0 45/(pi h^6) / 3 = tr(M_i)/3)
//   pressure sum_j (P_i + P_j + Pi_ij) (h - r)^2 / r x_ij    (x m 45/(pi h^6))
//   viscous  sum_j (v_j - v_i) (h - r) / rho_j               (x nu rho0 m 45/(pi h^6) / rho_i)
// Pi_ij = (pik + pbk mu) mu, mu = max(0, -v_ij . x_ij) / (r^2 + h^2/100), pik = alpha c0 h / rho0,
// pbk = beta h^2 / rho0: the impact viscosity on approaching pairs only. kBoundary: the sums over
// boundary particles (boundary.hpp), each weighted by its mass ratio W = m_b / m, at rest, without
// the viscous term (free-slip walls).
// Whole aligned 8-float vectors over [b & ~7, (e + 7) & ~7), lanes outside [b, e) masked (arrays
// padded: no scalar remainder); 1/r without square root or division (sph_rsqrt). The loop bodies
// are branch-free: every term is computed for every lane and the support and range test selects
// it by a bitwise and (sph_keep), which SSE, AVX2 and AVX-512 all express, so the compiler
// vectorises the loops for each of them (a conditional h - r needs masked arithmetic, AVX-512
// only, because a floating-point operation may trap; docs/sph.md, "Vectorisation"). The two range
// sums are kept out of line (one call per range of ~100-200 candidates), so each instantiation is
// a function of its own whose object code scripts/simd_report.py checks (test simd_object_code).
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "huygens/sph/boundary.hpp"
#include "huygens/sph/grid.hpp"

namespace huygens {

/// 1/sqrt(x) by the bit-level first guess of Lomont (2003) and two Newton steps
/// y <- y (3/2 - x y^2 / 2); relative error below 5e-6. GCC vectorises it.
inline float sph_rsqrt(float x) {
  float y = std::bit_cast<float>(0x5f375a86u - (std::bit_cast<std::uint32_t>(x) >> 1));
  const float hx = 0.5f * x;
  y = y * (1.5f - hx * y * y);
  y = y * (1.5f - hx * y * y);
  return y;
}

/// keep ? x : +0, as x & (all ones or zero): branch-free, bit for bit the select, and a NaN x
/// becomes 0 where keep is false.
inline float sph_keep(bool keep, float x) {
  return std::bit_cast<float>(std::bit_cast<std::uint32_t>(x) & (0u - static_cast<std::uint32_t>(keep)));
}

/// The offset x_i - x_j of candidate j from (xi, yi, zi) (m) and its squared length r^2 (m^2).
struct SphOffset {
  float dx, dy, dz, r2;
};
[[gnu::always_inline]] inline SphOffset sph_offset(const float* X, const float* Y, const float* Z, std::size_t j,
                                                   float xi, float yi, float zi) {
  const float dx = xi - X[j], dy = yi - Y[j], dz = zi - Z[j];
  return {dx, dy, dz, dx * dx + dy * dy + dz * dz};
}

/// The particle arrays a pair sum reads (cell-sorted, 64-byte aligned): positions (m), velocities
/// (m/s), PP = l p / rho^2, IR = 1 / rho, LR = l / rho. Boundary particles: X, Y, Z, PP, W (the
/// mass ratio m_b / m) and the unit normal NX, NY, NZ into the fluid.
struct SphView {
  const float *X, *Y, *Z, *VX, *VY, *VZ, *PP, *IR, *LR;
  const float* W = nullptr;
  const float *NX = nullptr, *NY = nullptr, *NZ = nullptr;
};

/// The cursor of a pass that reads positions only (SphCellGather): the fluid positions of v as arrays 0-2
/// and, with `boundary`, the boundary positions and mass ratios of bv as arrays 3-6 (sph_gathered_boundary).
inline SphCellGather::Cursor sph_position_cursor(const SphGrid& grid, SphCellGather& gather, int thread,
                                                 const SphView& v, const SphView& bv, bool boundary) {
  const float* src[7] = {v.X, v.Y, v.Z, bv.X, bv.Y, bv.Z, bv.W};
  return SphCellGather::Cursor(grid, gather, thread, src, 3, src + 3, boundary ? 4 : 0);
}
/// The gathered fluid positions of an sph_position_cursor.
inline SphView sph_gathered_fluid(const SphCellGather::Cursor& c) {
  return {c.scratch(0), c.scratch(1), c.scratch(2), nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
}
/// The gathered boundary positions and mass ratios of an sph_position_cursor.
inline SphView sph_gathered_boundary(const SphCellGather::Cursor& c) {
  return {c.scratch(3), c.scratch(4), c.scratch(5), nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, c.scratch(6)};
}

/// Adds the density sum of particle (xi, yi, zi) to `sum` and, with kMoment, the first moment of
/// the spiky gradient to `msum`; kBoundary: over boundary candidates, each weighted by W.
template <bool kBoundary, bool kMoment>
[[gnu::noinline]] void sph_poly6_range(const SphView& v, std::uint32_t b, std::uint32_t e, float xi, float yi, float zi,
                                       float h, float h2, float& sum, float& msum) {
  const float *X = v.X, *Y = v.Y, *Z = v.Z, *W = v.W;
  const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
  float s6 = 0.f, sm = 0.f;
#pragma omp simd reduction(+ : s6, sm) aligned(X, Y, Z : 32)
  for (std::uint32_t j = b0; j < e0; ++j) {
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, j, xi, yi, zi);
    const bool in = (r2 < h2) & (j >= b) & (j < e);
    const float q = sph_keep(in, h2 - r2);
    // the selected cube is added: the and between product and sum keeps them two roundings (no
    // fused multiply-add), the same sums for every ISA
    const float q3 = kBoundary ? q * q * q * W[j] : q * q * q;
    s6 += sph_keep(in, q3);
    if constexpr (kMoment) {
      // first moment of the spiky gradient: (h - r)^2 r, r = r2 / sqrt(r2 + 1e-30): 0 at r2 = 0, and
      // r2 + 1e-30 rounds to r2 for r2 > 2e-23 m^2
      const float r = r2 * sph_rsqrt(r2 + 1e-30f);
      const float hr = sph_keep(in, h - r);
      sm += sph_keep(in, kBoundary ? hr * hr * r * W[j] : hr * hr * r);
    }
  }
  sum += s6;
  msum += sm;
}

/// Adds the pressure sum to acc[0..2], the viscous sum to acc[3..5] and the spiky first moment
/// (for the next step's correction) to acc[6]; vi = v_i, Pi = P_i, rmin = smallest r used (m).
/// kBoundary: over boundary candidates, pressure, impact and moment terms weighted by W, no viscous
/// term (free slip); the impact term sees the velocity of a mirror image of particle i across the
/// wall, v_i - v_i' = 2 (v_i . n) n, so only motion into the wall is damped, not sliding along it.
template <bool kBoundary>
[[gnu::noinline]] void sph_force_range(const SphView& v, std::uint32_t b, std::uint32_t e, float xi, float yi, float zi,
                                       const float vi[3], float Pi, float h, float h2, float rmin, float pik, float pbk,
                                       float acc[7]) {
  const float rmin2 = rmin * rmin, eta2 = 0.01f * h2;
  const float *X = v.X, *Y = v.Y, *Z = v.Z, *VX = v.VX, *VY = v.VY, *VZ = v.VZ, *PP = v.PP, *IR = v.IR, *W = v.W,
              *NX = v.NX, *NY = v.NY, *NZ = v.NZ;
  const float vxi = vi[0], vyi = vi[1], vzi = vi[2];
  const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
  float fpx = 0.f, fpy = 0.f, fpz = 0.f, fvx = 0.f, fvy = 0.f, fvz = 0.f, sm = 0.f;
#pragma omp simd reduction(+ : fpx, fpy, fpz, fvx, fvy, fvz, sm) aligned(X, Y, Z, PP : 32)
  for (std::uint32_t j = b0; j < e0; ++j) {
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, j, xi, yi, zi);
    const float ri = sph_rsqrt(std::max(r2, rmin2));  // 1 / r
    const float r = r2 * ri;
    const float hr = sph_keep((r2 < h2) & (j >= b) & (j < e), h - r);
    float vr;
    if constexpr (kBoundary) {
      vr = 2.f * (vxi * NX[j] + vyi * NY[j] + vzi * NZ[j]) * (dx * NX[j] + dy * NY[j] + dz * NZ[j]);
    } else {
      vr = (vxi - VX[j]) * dx + (vyi - VY[j]) * dy + (vzi - VZ[j]) * dz;
    }
    const float ie = sph_rsqrt(r2 + eta2);  // Monaghan's 1 / (r^2 + h^2/100), squared below
    const float mu = std::max(-vr, 0.f) * ie * ie;
    const float Pv = (pik + pbk * mu) * mu;
    const float wj = kBoundary ? W[j] : 1.f;
    const float fp = (Pi + PP[j] + Pv) * hr * hr * ri * wj;
    fpx += fp * dx;
    fpy += fp * dy;
    fpz += fp * dz;
    if constexpr (!kBoundary) {
      const float fv = hr * IR[j];
      fvx += fv * (VX[j] - vxi);
      fvy += fv * (VY[j] - vyi);
      fvz += fv * (VZ[j] - vzi);
    }
    sm += hr * hr * r * wj;  // first moment of the spiky gradient, for the next step's correction
  }
  acc[0] += fpx;
  acc[1] += fpy;
  acc[2] += fpz;
  acc[3] += fvx;
  acc[4] += fvy;
  acc[5] += fvz;
  acc[6] += sm;
}

/// Adds the contact sum of a fluid particle at (xi, yi, zi) over boundary candidates to `csum`:
///   sum_b W_b max(0, (h^2 - r^2)^3 - q0c), q0c = (h^2 - r_c^2)^3, r_c = the contact range
/// (poly6 without its constant; W = m_b / m): every boundary particle nearer than r_c, by the
/// excess of its kernel value over the one at r_c, 0 for none (a lattice at a flat wall, r = dx: 0).
/// x m 315/(64 pi h^9) it is the compression the wall's particles impose on the fluid particle in
/// contact (SphSystem::compute_density: the contact density).
[[gnu::noinline]] inline void sph_contact_range(const SphView& v, std::uint32_t b, std::uint32_t e, float xi, float yi,
                                                float zi, float h2, float q0c, float& csum) {
  const float *X = v.X, *Y = v.Y, *Z = v.Z, *W = v.W;
  const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
  float sc = 0.f;
#pragma omp simd reduction(+ : sc) aligned(X, Y, Z : 32)
  for (std::uint32_t j = b0; j < e0; ++j) {
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, j, xi, yi, zi);
    const bool in = (r2 < h2) & (j >= b) & (j < e);
    const float q = sph_keep(in, h2 - r2);
    sc += sph_keep(in, std::max(q * q * q - q0c, 0.f) * W[j]);
  }
  csum += sc;
}

/// The sums of a boundary particle at (xb, yb, zb) over fluid candidates for its extrapolated
/// pressure (Adami et al. 2012 eq. 27): s[0] = sum W, s[1] = sum p W, s[2..4] = sum rho (x_b - x_f) W,
/// s[5] = sum l W, with W = (h^2 - r^2)^3 (poly6 without its constant, which cancels). v: X, Y, Z
/// of the fluid, PP = p (Pa), IR = rho (kg/m^3), LR = l (1). The density in the hydrostatic sum is
/// max(rho, rho_min): with rho_min = rho0 it is the density of the fluid's pressure by the clamped
/// equation of state (rho0 at p = 0), not the summation density, which a kernel cut off at the free
/// surface puts below rho0 (a lone particle on a floor: 0.38 rho0).
[[gnu::noinline]] inline void sph_wall_range(const SphView& v, std::uint32_t b, std::uint32_t e, float xb, float yb,
                                             float zb, float h2, float s[6], float rho_min = 0.f) {
  const float *X = v.X, *Y = v.Y, *Z = v.Z, *P = v.PP, *R = v.IR, *L = v.LR;
  const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
  float sw = 0.f, sp = 0.f, sx = 0.f, sy = 0.f, sz = 0.f, sl = 0.f;
#pragma omp simd reduction(+ : sw, sp, sx, sy, sz, sl) aligned(X, Y, Z, P, R, L : 32)
  for (std::uint32_t j = b0; j < e0; ++j) {
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, j, xb, yb, zb);
    const bool in = (r2 < h2) & (j >= b) & (j < e);
    const float q = sph_keep(in, h2 - r2);
    const float w = sph_keep(in, q * q * q);
    const float rw = sph_keep(in, std::max(R[j], rho_min) * w);
    sw += w;
    sp += sph_keep(in, P[j] * w);
    sx += rw * dx;
    sy += rw * dy;
    sz += rw * dz;
    sl += sph_keep(in, L[j] * w);
  }
  s[0] += sw;
  s[1] += sp;
  s[2] += sx;
  s[3] += sy;
  s[4] += sz;
  s[5] += sl;
}

}  // namespace huygens
