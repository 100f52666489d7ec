// The DFSPH step of SphSystem (Bender and Koschier 2015): see huygens/sph/dfsph.hpp.
#include "huygens/sph/dfsph.hpp"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "huygens/common/finite.hpp"
#include "huygens/sph/system.hpp"

// A product rounded on its own, never fused into the sum it feeds: GCC contracts across statements
// (-ffp-contract=fast), so it needs the barrier; clang contracts within one expression only (its
// default -ffp-contract=on) and has no such builtin (the fuzz build).
#if defined(__has_builtin)
#if __has_builtin(__builtin_assoc_barrier)
#define HUYGENS_ROUNDED(x) __builtin_assoc_barrier(x)
#endif
#endif
#ifndef HUYGENS_ROUNDED
#define HUYGENS_ROUNDED(x) (x)
#endif

namespace huygens {

void SphSystem::dfsph_list_allocate(std::size_t slots) {
  if (slots > std::numeric_limits<std::uint32_t>::max()) throw std::length_error("DFSPH neighbour list");
  nlist_ = slots;
  nj_ = AlignedBuffer<std::uint32_t>(slots);
  for (auto* g : {&ngx_, &ngy_, &ngz_}) *g = AlignedBuffer<float>(slots);
}

// The pass writes at most the list's capacity (each thread in its own part of it) and reports an
// overflow; the list then doubles, outside the solves, and the pass runs again (allocate() gives 56 slots
// per particle at h = 2 dx, a mean of ~36 used at rest density: 32 neighbours and the padding).
void SphSystem::dfsph_factors() {
  while (!dfsph_factors_pass()) dfsph_list_allocate(2 * nlist_);
}

// Fluid neighbours from the cell rows into the list (positions stream, no kernel), then over the list:
// rho_i = m 8/(pi h^3) (sum_j w_j w(q) + the near count, w(0) = 1); G_i = sum_j m_j grad W_ij =
// -m 48/(pi h^5) (gf + gb); alpha_i = rho_i / (|G_i|^2 + (m 48/(pi h^5))^2 sum_fluid f^2 r^2) (BK15 eq. 11);
// l_i from the moment; the wall contact at the expected position x_i + dt_prev v_i (dfsph.hpp, "Walls").
bool SphSystem::dfsph_factors_pass() {
  const std::size_t n = n_;
  const SphView bv{bx_.data(), by_.data(), bz_.data(), nullptr, nullptr,
                   nullptr,    nullptr,    nullptr,    nullptr, bw_.data()};
  const SphView v{x_.data(), y_.data(), z_.data(), nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
  const float *X = v.X, *Y = v.Y, *Z = v.Z;
  const float h = h_, h2 = k_.h2, rmin = 1e-6f * h_, rmin2 = rmin * rmin;
  const float grav[3] = {g_[0], g_[1], g_[2]};
  // the contact range, and the longest expected displacement whose boundary particles within r_c the cells hold
  const float rc = std::min(std::max(p_.dfsph_contact_range, 0.f) * p_.spacing_m, 0.5f * h), dmax = h - rc;
  const float q0 = h2 - rc * rc, tp = static_cast<float>(dt_prev_);
  bool fits = true;
#pragma omp parallel if (n > kSphParallelMin) reduction(&& : fits)
  {
    const int t = omp_get_thread_num();
    const std::size_t part = (nlist_ / std::size_t(omp_get_num_threads())) & ~std::size_t(7);
    std::uint32_t pos = static_cast<std::uint32_t>(std::size_t(t) * part);
    const std::uint32_t lim = static_cast<std::uint32_t>(pos + part);
    SphCellGather::Cursor cur = sph_position_cursor(grid_, gather_, t, v, bv, nb_ > 0);
    const SphView sv = sph_gathered_fluid(cur), sbv = sph_gathered_boundary(cur);
    std::uint32_t* F = t < gather_.threads() ? nflag_.data() + std::size_t(t) * (gather_.capacity() + 16) : nullptr;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const float xi = X[i], yi = Y[i], zi = Z[i];
      const int cx = grid_.ix(xi), cy = grid_.iy(yi), cz = grid_.iz(zi);
      std::uint32_t k = pos, near = 0;
      SphDfsphContact c{{tp * vx_[i], tp * vy_[i], tp * vz_[i]}, rc * rc, q0 * q0 * q0};
      const float dl = std::sqrt(c.d[0] * c.d[0] + c.d[1] * c.d[1] + c.d[2] * c.d[2]);
      for (float& dd : c.d) dd *= dl > dmax ? dmax / dl : 1.f;
      float fb[13] = {};
      cur.visit(cx, cy, cz, [&](bool g, bool bnd, std::uint32_t b, std::uint32_t e) {
        if (bnd) {
          sph_dfsph_boundary_range(g ? sbv : bv, b, e, xi, yi, zi, h, h2, rmin, grav, c, fb);
        } else if (!fits || k + (e - b) + 8u > lim) {  // room for every candidate and the padding
          fits = false;
        } else if (g) {  // flags over the gathered copies, then the sorted indices of the flagged ones
          sph_dfsph_list_flags(sv.X, sv.Y, sv.Z, e, xi, yi, zi, h2, rmin2, F, near);
          std::uint32_t off = 0;
          grid_.for_each_row(cx, cy, cz, [&](std::uint32_t rb, std::uint32_t re, int) {
            for (std::uint32_t j = rb; j < re; ++j, ++off) {
              nj_[k] = j;
              k += F[off];
            }
            return true;
          });
        } else {
          sph_dfsph_list_append(X, Y, Z, b, e, xi, yi, zi, h2, rmin2, nj_.data(), k, near);
        }
      });
      if (!fits) k = pos;  // this pass is repeated with a larger list
      const std::uint32_t end = (k + 7u) & ~7u;
      for (std::uint32_t u = k; u < end; ++u) nj_[u] = static_cast<std::uint32_t>(i);
      nbeg_[i] = pos;
      nend_[i] = end;
      float f[6] = {};
      sph_dfsph_list_factors(X, Y, Z, nj_.data(), ngx_.data(), ngy_.data(), ngz_.data(), pos, end, xi, yi, zi, h, h2,
                             rmin, f);
      dfsph_store_factors(i, f, fb, near, k - pos, c.d);
      pos = end;
    }
  }
  return fits;
}

// rho_i, 1/rho_i, alpha_i, l_i, gb_i, the walls' hydrostatic push (into ax_), whether the particle takes part in the
// divergence-free solve, and its wall contact (dfsph.hpp, "Walls"): E*(v) = cex - dt cg . v, the excess expanded to
// first order about the expected position x_p = x_i + d, and ccd = 2 m 48/(pi h^5) cg . gb, so that the contact's
// kick dv_i = dt m 48/(pi h^5) 2 Kc gb_i changes E* by -dt^2 ccd Kc.
void SphSystem::dfsph_store_factors(std::size_t i, const float f[6], const float fb[13], std::uint32_t near,
                                    std::uint32_t nf, const float d[3]) {
  const float mk = mass_ * k_.cubic_k, mg = mass_ * k_.cubic_g, mg2 = mg * mg;
  const float mb = p_.dfsph_wall == SphDfsphWall::akinci ? 0.f : 1.f;
  const float ch = p_.dfsph_wall == SphDfsphWall::hydrostatic ? mg / p_.rest_density_kgpm3 : 0.f;
  const float rho = std::isfinite(x_[i] + y_[i] + z_[i]) ? mk * (f[0] + float(near) + fb[0])
                                                         : std::numeric_limits<float>::quiet_NaN();
  // the velocity change per kappa_i is along gf + 2 gb where the wall term mirrors p_i (counted twice)
  const float gx = f[1] + fb[1], gy = f[2] + fb[2], gz = f[3] + fb[3];
  const float gx2 = gx + mb * fb[1], gy2 = gy + mb * fb[2], gz2 = gz + mb * fb[3];
  const float den = mg2 * (std::max(gx * gx2 + gy * gy2 + gz * gz2, 0.f) + f[4]);
  rho_[i] = rho;
  irho_[i] = 1.f / rho;
  alpha_[i] = den > 1e-6f * rho * rho ? rho / den : 0.f;
  corr_[i] = gradient_correction(f[5] + fb[4]);
  gbx_[i] = fb[1];
  gby_[i] = fb[2];
  gbz_[i] = fb[3];
  // the walls' hydrostatic share, p_b - p_i = rho0 g . (x_b - x_i): m 48/(pi h^5) / rho0 x the sum
  ax_[i] = ch * fb[5];
  ay_[i] = ch * fb[6];
  az_[i] = ch * fb[7];
  dvok_[i] = float(nf) + fb[8] >= float(p_.dfsph_min_neighbours) ? 1.f : 0.f;
  // the contact excess m 315/(64 pi h^9) sum, its gradient -6 m 315/(64 pi h^9) sum q^2 x_pb = -cg; the contact pushes
  // along the wall term's gb, which must not be more than 75 degrees off cg
  const float m6 = mass_ * k_.poly6_k, cx = 6.f * m6 * fb[10], cy = 6.f * m6 * fb[11], cz = 6.f * m6 * fb[12];
  const float cd = 2.f * mg * (cx * fb[1] + cy * fb[2] + cz * fb[3]);
  const float cn =
      2.f * mg * std::sqrt((cx * cx + cy * cy + cz * cz) * (fb[1] * fb[1] + fb[2] * fb[2] + fb[3] * fb[3]));
  const bool contact = p_.dfsph_contact_range > 0.f && fb[9] > 0.f && cd > 0.26f * cn;  // cos 75 degrees
  cex_[i] = contact ? m6 * fb[9] + cx * d[0] + cy * d[1] + cz * d[2] : 0.f;
  cgx_[i] = cx;
  cgy_[i] = cy;
  cgz_[i] = cz;
  ccd_[i] = contact ? cd : 0.f;
}

// v_i += dt m 48/(pi h^5) (sum_j (K_i + K_j) f(q) x_ij + c K_i gb_i)  (BK15 eq. 16; wall: c = 2 with p_b = p_i +
// its hydrostatic part (applied in the advection), 1 with Akinci's single term); j over the step's list
void SphSystem::dfsph_kick(float dt) {
  const std::size_t n = n_;
  const SphDfsphList l{nbeg_.data(), nend_.data(), nj_.data(), ngx_.data(), ngy_.data(), ngz_.data()};
  const float c = dt * mass_ * k_.cubic_g, cb = p_.dfsph_wall == SphDfsphWall::akinci ? 1.f : 2.f;
  const float* K = kick_.data();
#pragma omp parallel for schedule(static) if (n > kSphParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    const float Ki = K[i];
    if (Ki == 0.f && alpha_[i] == 0.f) continue;  // no own change, and no neighbour to take one from
    float acc[3] = {cb * Ki * gbx_[i], cb * Ki * gby_[i], cb * Ki * gbz_[i]};
    sph_dfsph_list_kick(l, i, K, acc);
    vx_[i] += c * acc[0];
    vy_[i] += c * acc[1];
    vz_[i] += c * acc[2];
  }
}

namespace {

// m ? a : b (m all ones or zero) bit for bit, without a branch (whole vectors under -ftrapping-math)
inline float sph_select(std::uint32_t m, float a, float b) {
  return std::bit_cast<float>((std::bit_cast<std::uint32_t>(a) & m) | (std::bit_cast<std::uint32_t>(b) & ~m));
}
inline std::uint32_t sph_mask(bool c) { return 0u - static_cast<std::uint32_t>(c); }
// std::max(a, b) by value (a std::max of locals under omp simd kept them in per-lane arrays: no vectors)
inline float sph_max(float a, float b) { return a < b ? b : a; }

}  // namespace

// Drho_i/Dt = -m 48/(pi h^5) (sum_j f(q) v_ij . x_ij + v_i . gb_i)  (BK15 eq. 6, boundary at rest);
// density: kappa_i += (rho_i + dt Drho_i/Dt - rho0) alpha_i / dt^2 (eq. 12-13), error max(0, rho* - rho0) / rho0;
// divergence: kappa^v_i += Drho_i/Dt alpha_i / dt (eq. 17), error max(0, dt Drho_i/Dt) / rho0, Drho_i/Dt taken as 0
// for a particle with too few neighbours (dvok_ = 0); both kept >= 0;
// with the Chebyshev weight wc: kappa_i = max(0, wc (kappa_Jacobi - kappa_prev) + kappa_prev) (Wang 2015).
// Two passes: the sums over the neighbour list (into err_), then the update of each particle in whole vectors.
double SphSystem::dfsph_update(float dt, bool density, float wc) {
  const std::size_t n = n_;
  const SphDfsphList l{nbeg_.data(), nend_.data(), nj_.data(), ngx_.data(), ngy_.data(), ngz_.data()};
  const float *VX = vx_.data(), *VY = vy_.data(), *VZ = vz_.data();
  float* S = err_.data();
#pragma omp parallel for schedule(static) if (n > kSphParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    float s = VX[i] * gbx_[i] + VY[i] * gby_[i] + VZ[i] * gbz_[i];
    if (alpha_[i] != 0.f) s += sph_dfsph_list_divergence(l, i, VX, VY, VZ);
    S[i] = s;
  }
  const float mg = mass_ * k_.cubic_g, rho0 = p_.rest_density_kgpm3;
  float* kap = density ? kappa_.data() : kappav_.data();
  const float w = p_.dfsph_relaxation / (dt * dt);
  const bool oneside = p_.dfsph_compression_only;
  const float lo = oneside ? 0.f : -std::numeric_limits<float>::infinity();
  // the solve's kind, the Chebyshev weight's use and the two-sided error as masks (no bool read in the loop)
  const std::uint32_t md = sph_mask(density), mc = sph_mask(wc != 1.f), mt = sph_mask(!oneside);
  const float *R = rho_.data(), *A = alpha_.data(), *IR = irho_.data(), *D = dvok_.data();
  float *prev = tkappa_.data(), *K = kick_.data(), *E = err_.data();
  // branch-free (both sides computed, one selected bit for bit), so the loop runs in whole vectors
#pragma omp parallel for simd schedule(static) if (n > kSphParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    const float drho = -mg * S[i];  // Drho_i/Dt (kg/m^3/s)
    // dt Drho_i/Dt rounded on its own, not fused into rho_i + dt Drho_i/Dt (as the branchy scalar loop had it)
    const float dd = HUYGENS_ROUNDED(dt * drho);
    // the divergence-free solve leaves out the particles with too few neighbours (dvok_ = 0)
    const float res = sph_select(md, R[i] + dd - rho0, dd * D[i]);
    const float inc = sph_max(res, lo) * A[i] * w;
    const float kj = sph_max(kap[i] + inc, 0.f);
    const float k = sph_select(mc, sph_max(wc * (kj - prev[i]) + prev[i], 0.f), kj);
    prev[i] = kap[i];
    K[i] = (k - kap[i]) * IR[i];
    kap[i] = k;
    // the residual of the complementarity p >= 0, rho* <= rho0, p (rho* - rho0) = 0: |res| where pushed
    E[i] = sph_select(sph_mask(k > 0.f) & mt, std::fabs(res), sph_max(res, 0.f)) / rho0;
  }
  double sum = 0;  // serial: the same iteration count for any thread count
  for (std::size_t i = 0; i < n; ++i) sum += err_[i];
  return n ? sum / double(n) : 0.0;
}

// The wall contact after a kick of the constant-density solve (dfsph.hpp, "Walls"), particle by particle (a
// Gauss-Seidel step after the Jacobi step of kappa): Kc_i = max(0, Kc_i + E*_i / (dt^2 ccd_i)), E*_i = cex - dt cg .
// v_i the predicted contact excess (kg/m^3), and v_i += dt m 48/(pi h^5) 2 dKc gb_i (the wall term, as kappa's), which
// sets E*_i to 0 where Kc_i > 0. Returns the particles with Kc > 0.
std::size_t SphSystem::dfsph_contact(float dt) {
  const std::size_t n = n_;
  const float c = 2.f * dt * mass_ * k_.cubic_g, idt2 = 1.f / (dt * dt);
  std::size_t active = 0;
#pragma omp parallel for schedule(static) if (n > kSphParallelMin) reduction(+ : active)
  for (std::size_t i = 0; i < n; ++i) {
    if (ccd_[i] == 0.f) continue;
    const float e = cex_[i] - dt * (cgx_[i] * vx_[i] + cgy_[i] * vy_[i] + cgz_[i] * vz_[i]);
    const float k = std::max(kc_[i] + e * idt2 / ccd_[i], 0.f), dk = c * (k - kc_[i]);
    kc_[i] = k;
    vx_[i] += dk * gbx_[i];
    vy_[i] += dk * gby_[i];
    vz_[i] += dk * gbz_[i];
    active += k > 0.f;
  }
  return active;
}

// Warm start (BK15 section 4.3: the last step's kappa, scaled by dfsph_warm_start, applied first), then Jacobi
// iterations until the mean error is at most the tolerance (at least 2 density / 1 divergence iterations, BK15 Alg.
// 2-3), accelerated by Chebyshev's semi-iteration (Wang 2015, dfsph.hpp).
int SphSystem::dfsph_solve(float dt, bool density) {
  // timed as the solve's stage, less the wall contact's time (the boundary stage)
  StageStat &st = stats_[density ? sid_.density_solve : sid_.divergence_solve], &bst = stats_[sid_.boundary];
  const std::uint64_t contact_ns = bst.ns;
  int it = 0;
  {
    StageTimer t(st);
    it = dfsph_iterate(dt, density);
  }
  st.ns -= std::min(st.ns, bst.ns - contact_ns);
  return it;
}

int SphSystem::dfsph_iterate(float dt, bool density) {
  float* kap = density ? kappa_.data() : kappav_.data();
  const float wf = p_.dfsph_warm_start;
  bool warm = false;
  for (std::size_t i = 0; i < n_; ++i) {
    kap[i] *= density ? wf : wf * dvok_[i];  // no warm start where the divergence is not solved
    kick_[i] = kap[i] * irho_[i];
    warm = warm || kap[i] != 0.f;
  }
  if (warm) dfsph_kick(dt);
  if (density) std::fill(kc_.data(), kc_.data() + n_, 0.f);  // the contact starts from 0 in each step
  const double eta = density ? p_.dfsph_density_error : p_.dfsph_divergence_error;
  const int min_iter = density ? 2 : 1;
  int it = 0;
  double err = 0;
  // Chebyshev weights (Wang 2015) from the third iteration: w = 2 / (2 - r^2), then 4 / (4 - r^2 w)
  const float r2 = p_.dfsph_chebyshev_rho * p_.dfsph_chebyshev_rho;
  float wc = 1.f;
  std::copy(kap, kap + n_, tkappa_.data());  // the previous iterate (the sort buffer is free during a solve)
  do {
    if (r2 > 0.f && it >= 2) wc = it == 2 ? 2.f / (2.f - r2) : 4.f / (4.f - r2 * wc);
    err = dfsph_update(dt, density, wc);
    dfsph_kick(dt);
    if (density) {
      StageTimer t(stats_[sid_.boundary]);
      contacts_ = dfsph_contact(dt);
    }
    ++it;
  } while ((err > eta || it < min_iter) && it < p_.dfsph_max_iterations);
  if (density) total_contacts_ += static_cast<std::int64_t>(contacts_);
  return it;
}

// a_i = g + a_h,i + nu rho0 m 45/(pi h^6) / rho_i sum_j (v_j - v_i) (h - r) / rho_j (MCG03 eq. 14, as the
// WCSPH viscous term; free-slip walls: no boundary term; a_h: the walls' hydrostatic push, left in ax_ by
// dfsph_factors); also max |a| and max |v|.
void SphSystem::dfsph_advection_forces() {
  const std::size_t n = n_;
  const SphView v{x_.data(), y_.data(), z_.data(), vx_.data(), vy_.data(), vz_.data(), nullptr, irho_.data(), nullptr};
  const SphDfsphList l{nbeg_.data(), nend_.data(), nj_.data(), ngx_.data(), ngy_.data(), ngz_.data()};
  const float h = h_, cv = nu_ * p_.rest_density_kgpm3 * mass_ * k_.spiky_k;
  const float gx = g_[0], gy = g_[1], gz = g_[2];
  float amax2 = 0.f, vmax2 = 0.f;
#pragma omp parallel for schedule(static) if (n > kSphParallelMin) reduction(max : amax2, vmax2)
  for (std::size_t i = 0; i < n; ++i) {
    float acc[3] = {0.f, 0.f, 0.f};
    sph_dfsph_list_viscous(l, i, v, h, acc);
    const float vis = cv * v.IR[i];
    const float ax = ax_[i] + gx + vis * acc[0], ay = ay_[i] + gy + vis * acc[1], az = az_[i] + gz + vis * acc[2];
    ax_[i] = ax;
    ay_[i] = ay;
    az_[i] = az;
    amax2 = std::max(amax2, ax * ax + ay * ay + az * az);
    vmax2 = std::max(vmax2, v.VX[i] * v.VX[i] + v.VY[i] * v.VY[i] + v.VZ[i] * v.VZ[i]);
  }
  amax_ = std::sqrt(amax2);
  vmax_ = std::sqrt(vmax2);
}

void SphSystem::dfsph_pressure() {
  for (std::size_t i = 0; i < n_; ++i) p_arr_[i] = rho_[i] * (kappa_[i] + kappav_[i]) / corr_[i];
}

// BK15 Algorithm 1, entered at the neighbour search: the divergence-free solve of the last step's
// velocities (the factors at the new positions), advection, dt, the constant-density solve, positions.
double SphSystem::step_dfsph() {
  {
    StageTimer t(stats_[sid_.neighbours]);
    sort_particles();
  }
  {
    StageTimer t(stats_[sid_.density]);
    dfsph_factors();
  }
  if (!all_finite(density())) throw NonFiniteError("density", steps_);
  div_iter_ = dt_prev_ > 0 ? dfsph_solve(static_cast<float>(dt_prev_), false) : 0;
  double dt;
  {
    StageTimer t(stats_[sid_.forces]);
    dfsph_advection_forces();
    // dt = min(dfsph_cfl dx / v_max, force sqrt(h / a_max), viscous h^2 / nu, dt_max) (BK15 section 4.3)
    dt = sph_choose_dt(p_, h_, 0.f, nu_, 0.f, amax_, dts_.limiter);
    if (vmax_ > 0.f && p_.dfsph_cfl * p_.spacing_m / vmax_ < dt) {
      dt = p_.dfsph_cfl * p_.spacing_m / vmax_;
      dts_.limiter = "cfl";
    }
    const float fdt = static_cast<float>(dt);
    for (std::size_t i = 0; i < n_; ++i) {
      vx_[i] += fdt * ax_[i];
      vy_[i] += fdt * ay_[i];
      vz_[i] += fdt * az_[i];
    }
  }
  dens_iter_ = dfsph_solve(static_cast<float>(dt), true);
  if (!all_finite(vx()) || !all_finite(vy()) || !all_finite(vz())) throw NonFiniteError("pressure solve", steps_);
  {
    StageTimer t(stats_[sid_.integration]);
    const float fdt = static_cast<float>(dt), damp = 1.f / (1.f + damping_ * fdt);
    for (std::size_t i = 0; i < n_; ++i) {
      vx_[i] *= damp, vy_[i] *= damp, vz_[i] *= damp;
      x_[i] += fdt * vx_[i];
      y_[i] += fdt * vy_[i];
      z_[i] += fdt * vz_[i];
    }
    dfsph_pressure();
  }
  if (!all_finite(x()) || !all_finite(y()) || !all_finite(z())) throw NonFiniteError("integration", steps_);
  total_iter_ += div_iter_ + dens_iter_;
  dt_prev_ = dt;
  record_dt(dt);
  return dt;
}

}  // namespace huygens
