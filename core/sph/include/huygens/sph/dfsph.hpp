#pragma once
// Divergence-free SPH (DFSPH) of Bender and Koschier 2015 ("Divergence-free smoothed particle
// hydrodynamics", SCA 2015; BK15 below), the pressure solver of `"method": "dfsph"` (SphParams).
// One step of SphSystem with it (dfsph.cpp; BK15 Algorithm 1, started at the neighbour search):
//   factors      rho_i = sum_j m_j W_ij (fluid and boundary neighbours)
//                alpha_i = rho_i / (|sum_j m_j grad W_ij|^2 + sum_j |m_j grad W_ij|^2)      (BK15 eq. 11)
//   divergence   Drho_i/Dt = sum_j m_j (v_i - v_j) . grad W_ij                           (BK15 eq. 6)
//                kappa^v_i += Drho_i/Dt alpha_i / dt                                     (BK15 eq. 17)
//   velocities   v_i -= dt sum_j m_j (k_i / rho_i + k_j / rho_j) grad W_ij                 (BK15 eq. 16)
//   advection    v*_i = v_i + dt (g + viscous acceleration + the walls' hydrostatic push, below)
//   density      rho*_i = rho_i + dt Drho_i/Dt(v*), kappa_i += (rho*_i - rho0) alpha_i / dt^2 (BK15 eq. 12-13)
//                then the same velocity update; x_i += dt v*_i
// Kernel: the cubic spline (kernels.hpp) for the density AND its gradient, support h = support_factor
// dx (2 dx: ~33 neighbours; its lattice sum there is 0.99997, and the particle mass is rho0 over it),
// so rho_i + dt Drho_i/Dt is the first-order change of the density sum the next step computes.
// Each solve is a relaxed Jacobi iteration, kappa += omega (error) alpha / dt^2 (omega =
// dfsph_relaxation, 0.5), repeated until the mean error is below its tolerance (0.005 % density,
// 0.1 % divergence; BK15 Algorithm 2 and 3: at least 2 density and 1 divergence iterations). The system matrix is A = J
// J^T with J the density change per velocity and alpha its exact diagonal; on the rest lattice the largest eigenvalue
// of diag(A)^-1 A is 2.82 (Fourier symbol |sum_d sin(k.d) grad W(d)|^2 / sum_d |grad W(d)|^2 at k ~ (1, 1, 1) / dx), so
// the signed Jacobi step converges only for omega < 2 / 2.82 = 0.71. kappa, kappa^v are kept >= 0 (a projected Jacobi
// step: an expanding particle is not pulled back, as the clamped free-surface density of BK15 section 4.2), and the
// error is that of the complementarity: |rho* - rho0| where kappa > 0, else max(0, rho* - rho0). dfsph_compression_only
// uses max(0, error) in the update as well (kappa only grows within a solve: stable at omega = 1,
// fewer iterations, but the overshoot is never taken back: docs/sph.md "DFSPH").
// Chebyshev semi-iteration (Wang 2015, "A Chebyshev semi-iterative approach for accelerating projective
// and position-based dynamics"): from the third iteration kappa = wc (kappa_Jacobi - kappa_prev) +
// kappa_prev (then >= 0), wc = 2 / (2 - rho^2), then 4 / (4 - rho^2 wc), rho = dfsph_chebyshev_rho (0.95):
// the smooth modes (eigenvalues near 0, the hydrostatic pressure of a deep column) converge ~2x faster.
// Warm start (BK15 section 4.3): kappa and kappa^v persist per particle (sorted with it); each solve
// first applies dfsph_warm_start (0.8) times the last step's values, then iterates on them.
// Particle deficiency (SPlisHSPlasH's rule): a particle with fewer than dfsph_min_neighbours (20) fluid and
// boundary neighbours within h takes no part in the divergence-free solve (its Drho/Dt counts as 0, its
// kappa^v stays 0, so nothing is warm-started): at the edge of a wall's support a lone particle's gradient
// sum, hence its change of density per kappa, is near 0 and its kappa^v huge, and the next step's warm
// start applied it to a steeper gradient (docs/sph.md, "DFSPH at the walls").
// Time step (BK15 section 4.3): dt = min(dfsph_cfl dx / v_max, force sqrt(h / a_max), viscous h^2 / nu, dt_max).
// Boundary particles (boundary.hpp, sampled volume V_b = w_b m / rho0): b adds m_b W_ib to the density
// and, at rest, m_b v_i . grad W_ib to Drho_i/Dt. Its pressure in the pair term
// m_b (p_i / rho_i^2 + p_b / rho0^2) grad W_ib (dfsph_wall) is, by default, the fluid particle's own
// continued hydrostatically, p_b = p_i + rho0 g . (x_b - x_i) (Adami et al. 2012 eq. 27 with the one
// fluid particle i, wall at rest): the part 2 k_i / rho_i is linear in the particle's own kappa, so it
// enters alpha_i's first sum (the change per kappa_i is along gf + 2 gb) and the kick; the part
// g . (x_b - x_i) / rho0 does not depend on kappa and is summed once per step into the advection
// acceleration, a_h = m 48/(pi h^5) / rho0 sum_b w_b f (g . x_bi) x_ib. Akinci et al. 2012 eq. 10's
// single p_i / rho_i^2 (akinci) leaves a wall particle half the push a fluid continuation gives and
// misses the hydrostatic rise below it and beside it, so p rises to 1.4-1.8 rho0 g (H - z) in a
// narrow column; p_b = p_i (mirror) misses the rise only. The walls do not move during the solves, so
// gb_i = sum_b w_b f x_ib is summed once per step (no boundary loop in the iterations).
// Reported pressure p_i = rho_i (kappa_i + kappa^v_i) / l_i: the pair term
// (k_i / rho_i + k_j / rho_j) equals (l_i p_i / rho_i^2 + l_j p_j / rho_j^2) of the WCSPH force with
// the gradient correction l (system.hpp, here from the cubic spline's first moment), so p is the
// field whose corrected gradient the solve applies.
// Walls: the contact (dfsph_contact_range r_c = 0.9 dx). The density constraint alone does not keep a particle
// out of a wall: a boundary particle counts in rho_i as a fluid particle would, so a particle whose own fluid
// share is below what the wall adds at its face (0.5 rho0 there; a lone spray particle has 0.32, a sheet 0.5-0.7:
// the surge tip, the jet up a wall) reaches rho0 only past the face, with kappa_i = 0 (expanding) until then, and a
// particle whose fluid neighbours recede keeps rho0 while it moves into the wall (the density sum does not tell
// wall from fluid); the divergence-free solve has the same blind spot and leaves gravity's part of the step to the
// density solve. So the constant-density solve also keeps each particle's centre r_c from every boundary particle
// at the end of the step: the contact excess E*_i = m 315/(64 pi h^9) sum_b w_b max(0, (h^2 - r_ib*^2)^3 - (h^2 -
// r_c^2)^3) (WCSPH's contact density, forces.cpp, at r_ib*, the distance at the end of the step) must be 0. It is
// taken to first order about the position the particle is expected to reach, x_p = x_i + dt_prev v_i (the factor
// pass sums it and its gradient over the b nearer than r_c to x_p): E*(v) = cex - dt cg . v, so a particle is
// caught on the step that would take it into the range, not one step later (at dt = dfsph_cfl dx / v_max a
// particle moves up to 0.4 dx in a step). The wall pushes with a multiplier Kc_i of its own in the wall term only,
// dv_i = dt m 48/(pi h^5) 2 Kc_i gb_i (as kappa's wall term: the wall's pressure on the particle, normal to the
// wall, not against the fluid neighbours), Kc_i = max(0, Kc_i + E*_i / (dt^2 2 m 48/(pi h^5) cg . gb)), 0 where cg
// and gb are more than 75 degrees apart; it is set particle by particle after each kick of the solve (a
// Gauss-Seidel step after the Jacobi step of kappa), starting from 0 in every step. r_c = 0.9 dx: above sqrt(3)/2 dx,
// the distance from a wall face to the four first-layer particles around a hollow of the layer, so the contact
// acts before a centre reaches the face anywhere on it (docs/sph.md, "DFSPH at the walls").
// Neighbour list: the factor pass, once per step after the sort, stores each particle's fluid neighbours
// within the support (index j and f(q) x_ij, grad W_ij = -48/(pi h^5) f x_ij) in SphDfsphList; the
// passes of both solves and the viscous term stream it (no cell search, no square root, no kernel in the
// iterations). x_ij = x_i - x_j, r = |x_ij|, q = r / h, w(q), f(q) the cubic spline's value and gradient
// shapes. Sums below (whole 8-float vectors, branch-free, in the style of forces.hpp):
//   boundary    over boundary candidates: sum W w, sum W f x_ib, sum W f r^2, sum W f (g . x_bi) x_ib, the count,
//               and over those nearer than r_c to x_p (q = h^2 - r_pb^2): sum W (q^3 - q_c^3), sum W q^2 x_pb
//   list        the list of particle i from its candidates (flags, then the indices), then over it:
//               sum w, sum f x_ij, sum f^2 r^2, sum f r^2 and the stored f x_ij
//   divergence  sum f (v_i - v_j) . x_ij      (x -m 48/(pi h^5) = Drho/Dt)
//   kick        sum (K_i + K_j) f x_ij        (x dt m 48/(pi h^5) = dv, K = kappa / rho)
//   viscous     sum (v_j - v_i) (h - r) / rho_j   (as forces.hpp: the MCG03 viscosity Laplacian)
#include <algorithm>
#include <cstdint>

#include "huygens/sph/forces.hpp"

namespace huygens {

/// The cubic spline (kernels.hpp) of a candidate at r = r2 ri (ri = 1/r, r2 < h2 where `in`): its value
/// shape w = 6 q^3 - 6 q^2 + 1 (q <= 1/2) or 2 (1 - q)^3 and its gradient shape f = 2 - 3 q or
/// (1 - q)^2 / q, q = r / h, both 0 where not `in` (branch-free: both sides computed, one selected).
inline void sph_cubic_shapes(bool in, float r2, float ri, float h, float ih, float& w, float& f) {
  const float q = r2 * ri * ih, om = 1.f - q;
  const bool inner = in & (q <= 0.5f), outer = in & (q > 0.5f);
  w = sph_keep(inner, (6.f * q - 6.f) * q * q + 1.f) + sph_keep(outer, 2.f * om * om * om);
  f = sph_keep(inner, 2.f - 3.f * q) + sph_keep(outer, om * om * h * ri);
}

/// The wall contact of one particle in a DFSPH step (dfsph.hpp header, "Walls"): the displacement d it is expected to
/// take (m; dt_prev v, at most h - r_c), the squared contact range r_c^2 (m^2) and (h^2 - r_c^2)^3 (m^6).
struct SphDfsphContact {
  float d[3];
  float rc2, q0c;
};

/// Boundary factor sums of particle (xi, yi, zi) over boundary candidates, each weighted by W (the mass
/// ratio): acc[0] value sum sum W w, acc[1..3] gradient sum sum W f x_ib, acc[4] the first moment sum W f r^2,
/// acc[5..7] the hydrostatic sum sum W f (g . x_bi) x_ib (g = gravity, m/s^2), acc[8] the candidates within h;
/// the contact at the expected position x_p = x_i + c.d over the candidates nearer than r_c to it, with q = h^2 -
/// r_pb^2: acc[9] the excess sum W (q^3 - (h^2 - r_c^2)^3) (m^6) and acc[10..12] sum W q^2 x_pb (m^5).
[[gnu::noinline]] inline void sph_dfsph_boundary_range(const SphView& v, std::uint32_t b, std::uint32_t e, float xi,
                                                       float yi, float zi, float h, float h2, float rmin,
                                                       const float g[3], const SphDfsphContact& c, float acc[13]) {
  const float rmin2 = rmin * rmin, ih = 1.f / h, rc2 = c.rc2, q0c = c.q0c;
  const float *X = v.X, *Y = v.Y, *Z = v.Z, *W = v.W;
  const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
  const float g0 = g[0], g1 = g[1], g2 = g[2], d0 = c.d[0], d1 = c.d[1], d2 = c.d[2];
  float sw = 0.f, gx = 0.f, gy = 0.f, gz = 0.f, sm = 0.f, hx = 0.f, hy = 0.f, hz = 0.f, sn = 0.f;
  float se = 0.f, ex = 0.f, ey = 0.f, ez = 0.f;
#pragma omp simd reduction(+ : sw, gx, gy, gz, sm, hx, hy, hz, sn, se, ex, ey, ez) aligned(X, Y, Z, W : 32)
  for (std::uint32_t j = b0; j < e0; ++j) {
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, j, xi, yi, zi);
    const bool range = (j >= b) & (j < e), in = (r2 < h2) & range;
    float w, f;
    sph_cubic_shapes(in, r2, sph_rsqrt(std::max(r2, rmin2)), h, ih, w, f);
    sn += sph_keep(in, 1.f);
    sw += w * W[j];
    const float gr = f * W[j];
    gx += gr * dx;
    gy += gr * dy;
    gz += gr * dz;
    sm += gr * r2;
    const float cg = -gr * (g0 * dx + g1 * dy + g2 * dz);
    hx += cg * dx;
    hy += cg * dy;
    hz += cg * dz;
    // the contact at the expected position: x_p - x_b = x_ib + d (poly6's shape: no square root)
    const float px = dx + d0, py = dy + d1, pz = dz + d2, p2 = px * px + py * py + pz * pz;
    const bool inc = (p2 < rc2) & range;
    const float q = sph_keep(inc, h2 - p2), qw = q * W[j];
    se += sph_keep(inc, (q * q * q - q0c) * W[j]);
    ex += qw * q * px;
    ey += qw * q * py;
    ez += qw * q * pz;
  }
  const float sums[13] = {sw, gx, gy, gz, sm, hx, hy, hz, sn, se, ex, ey, ez};
  for (int k = 0; k < 13; ++k) acc[k] += sums[k];
}

/// The DFSPH neighbour list of one step (SphSystem::dfsph_factors builds it with the factors, at the
/// positions both solves of the step use): the fluid neighbours j of particle i with rmin < r_ij < h
/// (i itself left out) in the slots [B[i], E[i]), 64-byte aligned and a multiple of 8 long (the tail
/// padded with j = i and a zero gradient): J the neighbour's sorted index, GX, GY, GZ = f(q) x_ij, so
/// grad W_ij = -48/(pi h^5) f x_ij (the cubic spline). The passes of the solves stream it (whole
/// vectors, the neighbours' values by gather): no cell search, no square root, no kernel.
struct SphDfsphList {
  const std::uint32_t *B, *E, *J;
  const float *GX, *GY, *GZ;
};

/// Appends the candidates j in [b, e) of the sorted positions with rmin2 < r^2 < h2 to J from slot k on
/// (branch-free: every candidate is written to slot k, and k advances where it qualifies, so slot k
/// must exist); counts the ones at r^2 <= rmin2 (i itself, coincident particles) in `near`.
inline void sph_dfsph_list_append(const float* X, const float* Y, const float* Z, std::uint32_t b, std::uint32_t e,
                                  float xi, float yi, float zi, float h2, float rmin2, std::uint32_t* J,
                                  std::uint32_t& k, std::uint32_t& near) {
  std::uint32_t kk = k, nn = near;
  for (std::uint32_t j = b; j < e; ++j) {
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, j, xi, yi, zi);
    J[kk] = j;
    kk += static_cast<std::uint32_t>((r2 < h2) & (r2 > rmin2));
    nn += static_cast<std::uint32_t>(r2 <= rmin2);
  }
  k = kk;
  near = nn;
}

/// Flags the gathered candidates t in [0, e) (contiguous copies X, Y, Z, padded to whole vectors) with
/// rmin2 < r^2 < h2 in F[t] (1 or 0) and counts the ones at r^2 <= rmin2 in `near`.
[[gnu::noinline]] inline void sph_dfsph_list_flags(const float* X, const float* Y, const float* Z, std::uint32_t e,
                                                   float xi, float yi, float zi, float h2, float rmin2,
                                                   std::uint32_t* F, std::uint32_t& near) {
  const std::uint32_t e0 = (e + 7u) & ~7u;
  std::uint32_t nn = 0;
#pragma omp simd reduction(+ : nn) aligned(X, Y, Z, F : 32)
  for (std::uint32_t t = 0; t < e0; ++t) {
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, t, xi, yi, zi);
    F[t] = static_cast<std::uint32_t>((r2 < h2) & (r2 > rmin2) & (t < e));
    nn += static_cast<std::uint32_t>((r2 <= rmin2) & (t < e));
  }
  near += nn;
}

/// Over the list slots [b, e) of particle (xi, yi, zi) (J filled, padding j = i): stores G = f x_ij and
/// adds the fluid factor sums to acc: acc[0] sum w, acc[1..3] sum f x_ij, acc[4] sum f^2 r^2, acc[5]
/// sum f r^2 (the pairs at r <= rmin, padding included, count 0).
[[gnu::noinline]] inline void sph_dfsph_list_factors(const float* X, const float* Y, const float* Z,
                                                     const std::uint32_t* J, float* GX, float* GY, float* GZ,
                                                     std::uint32_t b, std::uint32_t e, float xi, float yi, float zi,
                                                     float h, float h2, float rmin, float acc[6]) {
  const float rmin2 = rmin * rmin, ih = 1.f / h;
  float sw = 0.f, gx = 0.f, gy = 0.f, gz = 0.f, sq = 0.f, sm = 0.f;
#pragma omp simd reduction(+ : sw, gx, gy, gz, sq, sm) aligned(J, GX, GY, GZ : 32)
  for (std::size_t k = b; k < e; ++k) {  // a 64-bit index: GCC 12 does not vectorise this loop over a 32-bit one
    const std::uint32_t j = J[k];
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, j, xi, yi, zi);
    float w, f;
    sph_cubic_shapes((r2 < h2) & (r2 > rmin2), r2, sph_rsqrt(std::max(r2, rmin2)), h, ih, w, f);
    GX[k] = f * dx;
    GY[k] = f * dy;
    GZ[k] = f * dz;
    sw += w;
    gx += f * dx;
    gy += f * dy;
    gz += f * dz;
    sq += f * f * r2;
    sm += f * r2;
  }
  acc[0] += sw;
  acc[1] += gx;
  acc[2] += gy;
  acc[3] += gz;
  acc[4] += sq;
  acc[5] += sm;
}

/// sum_j f(q) (v_i - v_j) . x_ij over particle i's list (x -m 48/(pi h^5) = Drho_i/Dt, BK15 eq. 6).
[[gnu::noinline]] inline float sph_dfsph_list_divergence(const SphDfsphList& l, std::size_t i, const float* VX,
                                                         const float* VY, const float* VZ) {
  const std::uint32_t* J = l.J;
  const float* GX = l.GX;
  const float* GY = l.GY;
  const float* GZ = l.GZ;
  const float vxi = VX[i], vyi = VY[i], vzi = VZ[i];
  float s = 0.f;
#pragma omp simd reduction(+ : s) aligned(J, GX, GY, GZ : 32)
  for (std::uint32_t k = l.B[i]; k < l.E[i]; ++k) {
    const std::uint32_t j = J[k];
    s += GX[k] * (vxi - VX[j]) + GY[k] * (vyi - VY[j]) + GZ[k] * (vzi - VZ[j]);
  }
  return s;
}

/// Adds sum_j (K_i + K_j) f(q) x_ij over particle i's list to acc[0..2] (x dt m 48/(pi h^5) = the velocity
/// change of BK15 eq. 16, K = the change of kappa / rho).
[[gnu::noinline]] inline void sph_dfsph_list_kick(const SphDfsphList& l, std::size_t i, const float* K, float acc[3]) {
  const std::uint32_t* J = l.J;
  const float* GX = l.GX;
  const float* GY = l.GY;
  const float* GZ = l.GZ;
  const float Ki = K[i];
  float ax = 0.f, ay = 0.f, az = 0.f;
#pragma omp simd reduction(+ : ax, ay, az) aligned(J, GX, GY, GZ : 32)
  for (std::uint32_t k = l.B[i]; k < l.E[i]; ++k) {
    const float c = Ki + K[J[k]];
    ax += c * GX[k];
    ay += c * GY[k];
    az += c * GZ[k];
  }
  acc[0] += ax;
  acc[1] += ay;
  acc[2] += az;
}

/// Adds the viscous sum sum_j (v_j - v_i) (h - r) / rho_j over particle i's list to acc[0..2] (v: positions,
/// velocities, 1/rho in IR; as forces.hpp: the MCG03 viscosity Laplacian).
[[gnu::noinline]] inline void sph_dfsph_list_viscous(const SphDfsphList& l, std::size_t i, const SphView& v, float h,
                                                     float acc[3]) {
  const std::uint32_t* J = l.J;
  const float *X = v.X, *Y = v.Y, *Z = v.Z, *VX = v.VX, *VY = v.VY, *VZ = v.VZ, *IR = v.IR;
  const float xi = X[i], yi = Y[i], zi = Z[i], vxi = VX[i], vyi = VY[i], vzi = VZ[i];
  float ax = 0.f, ay = 0.f, az = 0.f;
#pragma omp simd reduction(+ : ax, ay, az) aligned(J : 32)
  for (std::uint32_t k = l.B[i]; k < l.E[i]; ++k) {
    const std::uint32_t j = J[k];
    const auto [dx, dy, dz, r2] = sph_offset(X, Y, Z, j, xi, yi, zi);
    // padding (j = i): r2 = 0, v_j - v_i = 0
    const float f = (h - r2 * sph_rsqrt(r2 + 1e-30f)) * IR[j];
    ax += f * (VX[j] - vxi);
    ay += f * (VY[j] - vyi);
    az += f * (VZ[j] - vzi);
  }
  acc[0] += ax;
  acc[1] += ay;
  acc[2] += az;
}

}  // namespace huygens
