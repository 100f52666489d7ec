// The density and force passes of SphSystem over the cell grid, and their all-pairs reference
// (pair sums: huygens/sph/forces.hpp; equations: huygens/sph/system.hpp).
#include "huygens/sph/forces.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "huygens/sph/system.hpp"

namespace huygens {

// p = max(0, B ((rho/rho0)^gamma - 1)) (Tait), gamma = 7 by three multiplications
float SphSystem::pressure_of(float rho) const {
  const float ratio = rho / p_.rest_density_kgpm3;
  float rg;
  if (p_.tait_gamma == 7.f) {
    const float r2 = ratio * ratio, r4 = r2 * r2;
    rg = r4 * r2 * ratio;
  } else {
    rg = std::pow(ratio, p_.tait_gamma);
  }
  return std::max(B_ * (rg - 1.f), 0.f);
}

// rho_i = m 315/(64 pi h^9) sum_j w_j (h^2 - r^2)^3 over the fluid (w = 1) and boundary neighbours
// (w = m_b / m); then p_i, 1/rho_i, l_i/rho_i and P_i = l_i p_i / rho_i^2. The contact density
// rho_c = max(rho_i, rho0 + m 315/(64 pi h^9) sum_b w_b max(0, (h^2 - r^2)^3 - (h^2 - r_c^2)^3))
// (sph_contact_range; r_c = SphParams::wall_contact_range dx) gives Pc_i = l_i p(rho_c) / rho_c^2,
// the P_i of the pairs with boundary particles: a particle stands for water at least at rest
// density (the clamped equation of state's own premise), and a boundary particle nearer than r_c
// compresses it by the excess of its kernel value over the one at r_c. rho_c = rho_i wherever the
// summation density already holds that compression (docs/sph.md, "Convex edges").
void SphSystem::compute_density(bool fresh_moment) {
  const std::size_t n = n_;
  const SphView v{x_.data(),  y_.data(), z_.data(),    vx_.data(),   vy_.data(),
                  vz_.data(), P_.data(), irho_.data(), lirho_.data()};
  const SphView bv{bx_.data(), by_.data(), bz_.data(), nullptr, nullptr,
                   nullptr,    nullptr,    nullptr,    nullptr, bw_.data()};
  const float h = h_, h2 = k_.h2, mk = mass_ * k_.poly6_k, rho0 = p_.rest_density_kgpm3;
  const float q0 = std::max(h2 - contact_r2(), 0.f), q0c = q0 * q0 * q0;
#pragma omp parallel if (n > kSphParallelMin)
  {
    SphCellGather::Cursor cur = sph_position_cursor(grid_, gather_, omp_get_thread_num(), v, bv, nb_ > 0);
    const SphView sv = sph_gathered_fluid(cur), sbv = sph_gathered_boundary(cur);
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const float xi = v.X[i], yi = v.Y[i], zi = v.Z[i];
      float sum = 0.f, msum = 0.f, csum = 0.f;
      // the direct path always sums the moment
      const bool gathered =
          cur.visit(grid_.ix(xi), grid_.iy(yi), grid_.iz(zi), [&](bool g, bool bnd, std::uint32_t b, std::uint32_t e) {
            const SphView& w = bnd ? (g ? sbv : bv) : (g ? sv : v);
            if (bnd) sph_contact_range(w, b, e, xi, yi, zi, h2, q0c, csum);
            if (fresh_moment || !g) {
              if (bnd)
                sph_poly6_range<true, true>(w, b, e, xi, yi, zi, h, h2, sum, msum);
              else
                sph_poly6_range<false, true>(w, b, e, xi, yi, zi, h, h2, sum, msum);
            } else {
              if (bnd)
                sph_poly6_range<true, false>(w, b, e, xi, yi, zi, h, h2, sum, msum);
              else
                sph_poly6_range<false, false>(w, b, e, xi, yi, zi, h, h2, sum, msum);
            }
          });
      // a non-finite position is masked out of every neighbour sum: make its own density say so
      const float rho = std::isfinite(xi + yi + zi) ? mk * sum : std::numeric_limits<float>::quiet_NaN();
      rho_[i] = rho;
      const float p = pressure_of(rho);
      p_arr_[i] = p;
      // the correction of the previous force pass (positions one step older) or a fresh one
      const float l = fresh_moment || !gathered ? gradient_correction(msum) : corr_[i];
      corr_[i] = l;
      irho_[i] = 1.f / rho;
      lirho_[i] = l / rho;
      P_[i] = l * p / (rho * rho);
      const float rc = std::max(rho, rho0 + mk * csum);
      Pc_[i] = rc > rho ? l * pressure_of(rc) / (rc * rc) : P_[i];
    }
  }
}

// p_b = max(0, (sum p_f W + g . sum rho_f (x_b - x_f) W) / sum W), rho_f = max(rho_f, rho0) (the
// density of p_f by the clamped equation of state; sph_wall_range) (Adami et al. 2012 eq. 27, wall at
// rest), l_b = sum l_f W / sum W (the fluid's gradient correction, as the pair term uses l_j), rho_b
// = rho0 (1 + p_b / B)^(1/gamma) (eq. 28), P_b = l_b p_b / rho_b^2; 0 without fluid in the support.
void SphSystem::set_boundary_pressure(std::size_t b, const float s[6]) {
  float p = 0.f, l = 1.f;
  if (s[0] > 0.f) {
    p = std::max((s[1] + g_[0] * s[2] + g_[1] * s[3] + g_[2] * s[4]) / s[0], 0.f);
    l = s[5] / s[0];
  }
  const float rho =
      p > 0.f ? p_.rest_density_kgpm3 * std::pow(1.f + p / B_, 1.f / p_.tait_gamma) : p_.rest_density_kgpm3;
  bp_[b] = p;
  bP_[b] = l * p / (rho * rho);
}

void SphSystem::compute_boundary_pressure() {
  const std::size_t nb = nb_;
  // fluid arrays read: positions, p in PP, rho in IR, l in LR
  const SphView v{x_.data(), y_.data(), z_.data(), nullptr, nullptr, nullptr, p_arr_.data(), rho_.data(), corr_.data()};
  const float h2 = k_.h2, rho0 = p_.rest_density_kgpm3;
#pragma omp parallel if (nb > kSphParallelMin && n_ > kSphParallelMin)
  {
    const float* src[6] = {v.X, v.Y, v.Z, v.PP, v.IR, v.LR};
    SphCellGather::Cursor cur(grid_, gather_, omp_get_thread_num(), src, 6);
    const SphView sv{cur.scratch(0), cur.scratch(1), cur.scratch(2), nullptr,       nullptr,
                     nullptr,        cur.scratch(3), cur.scratch(4), cur.scratch(5)};
#pragma omp for schedule(static)
    for (std::size_t b = 0; b < nb; ++b) {
      const float xb = bx_[b], yb = by_[b], zb = bz_[b];
      float s[6] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
      cur.visit(grid_.ix(xb), grid_.iy(yb), grid_.iz(zb), [&](bool g, bool, std::uint32_t lo, std::uint32_t hi) {
        sph_wall_range(g ? sv : v, lo, hi, xb, yb, zb, h2, s, rho0);
      });
      set_boundary_pressure(b, s);
    }
  }
}

// a_i = g + m 45/(pi h^6) (pressure sum) + nu rho0 m 45/(pi h^6) / rho_i (viscous sum), the boundary
// particles among the neighbours; also the spiky first moment for the next step's gradient
// correction, and max |a|, max |v|.
void SphSystem::compute_forces() {
  const std::size_t n = n_;
  const SphView v{x_.data(),  y_.data(), z_.data(),    vx_.data(),   vy_.data(),
                  vz_.data(), P_.data(), irho_.data(), lirho_.data()};
  const SphView bv{bx_.data(), by_.data(), bz_.data(), nullptr,     nullptr,     nullptr,    bP_.data(),
                   nullptr,    nullptr,    bw_.data(), bnx_.data(), bny_.data(), bnz_.data()};
  const float h = h_, h2 = k_.h2, rmin = 1e-6f * h_;
  const float pik = pik_, pbk = pbk_, pikw = pikw_;
  const float cp = mass_ * k_.spiky_k;                                // m 45/(pi h^6)
  const float cv = nu_ * p_.rest_density_kgpm3 * mass_ * k_.spiky_k;  // nu rho0 m 45/(pi h^6)
  const float gx = g_[0], gy = g_[1], gz = g_[2];
  float amax2 = 0.f, vmax2 = 0.f;
#pragma omp parallel if (n > kSphParallelMin) reduction(max : amax2, vmax2)
  {
    const float* src[9] = {v.X, v.Y, v.Z, v.VX, v.VY, v.VZ, v.PP, v.IR, v.LR};
    const float* bsrc[8] = {bv.X, bv.Y, bv.Z, bv.PP, bv.W, bv.NX, bv.NY, bv.NZ};
    SphCellGather::Cursor cur(grid_, gather_, omp_get_thread_num(), src, 9, bsrc, nb_ > 0 ? 8 : 0);
    const SphView sv{cur.scratch(0), cur.scratch(1), cur.scratch(2), cur.scratch(3), cur.scratch(4),
                     cur.scratch(5), cur.scratch(6), cur.scratch(7), cur.scratch(8)};
    const SphView sbv{cur.scratch(9),  cur.scratch(10), cur.scratch(11), nullptr, nullptr,
                      nullptr,         cur.scratch(12), nullptr,         nullptr, cur.scratch(13),
                      cur.scratch(14), cur.scratch(15), cur.scratch(16)};
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const float xi = v.X[i], yi = v.Y[i], zi = v.Z[i], Pi = v.PP[i], Pci = Pc_[i];
      const float vi[3] = {v.VX[i], v.VY[i], v.VZ[i]};
      float acc[7] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
      cur.visit(grid_.ix(xi), grid_.iy(yi), grid_.iz(zi), [&](bool g, bool bnd, std::uint32_t b, std::uint32_t e) {
        if (bnd)
          sph_force_range<true>(g ? sbv : bv, b, e, xi, yi, zi, vi, Pci, h, h2, rmin, pikw, pbk, acc);
        else
          sph_force_range<false>(g ? sv : v, b, e, xi, yi, zi, vi, Pi, h, h2, rmin, pik, pbk, acc);
      });
      const float vis = cv * v.IR[i];
      const float ax = gx + cp * acc[0] + vis * acc[3];
      const float ay = gy + cp * acc[1] + vis * acc[4];
      const float az = gz + cp * acc[2] + vis * acc[5];
      ax_[i] = ax;
      ay_[i] = ay;
      az_[i] = az;
      corr_[i] = gradient_correction(acc[6]);
      amax2 = std::max(amax2, ax * ax + ay * ay + az * az);
      vmax2 = std::max(vmax2, vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]);
    }
  }
  amax_ = std::sqrt(amax2);
  vmax_ = std::sqrt(vmax2);
}

// ---------------------------------------------------------------------------------------------
// reference paths for the benchmark: the grid step's physics, and an O(n^2) all-pairs version

void SphSystem::grid_accelerations(std::span<float> ax, std::span<float> ay, std::span<float> az,
                                   std::span<float> rho) {
  sort_particles();
  compute_density(true);
  compute_boundary_pressure();
  compute_forces();
  std::copy(ax_.data(), ax_.data() + n_, ax.begin());
  std::copy(ay_.data(), ay_.data() + n_, ay.begin());
  std::copy(az_.data(), az_.data() + n_, az.begin());
  std::copy(rho_.data(), rho_.data() + n_, rho.begin());
}

void SphSystem::brute_force_accelerations(std::span<float> ax, std::span<float> ay, std::span<float> az,
                                          std::span<float> rho) {
  // the same physics with every particle tested against every fluid and boundary particle
  const std::size_t n = n_, nb = nb_;
  const float h = h_, h2 = k_.h2, mk = mass_ * k_.poly6_k, rmin = 1e-6f * h_;
  const float pik = pik_, pbk = pbk_, pikw = pikw_;
  float* R = rho.data();
  float* Pa = tx_.data();   // scratch: l p / rho^2
  float* Ia = ty_.data();   // scratch: 1 / rho
  float* La = tz_.data();   // scratch: l / rho
  float* Pr = tvx_.data();  // scratch: p
  float* Lc = tvy_.data();  // scratch: l
  float* Pc = tvz_.data();  // scratch: l p(rho_c) / rho_c^2 (compute_density)
  const float rho0 = p_.rest_density_kgpm3;
  const float q0 = std::max(h2 - contact_r2(), 0.f), q0c = q0 * q0 * q0;
  const auto un = static_cast<std::uint32_t>(n), ub = static_cast<std::uint32_t>(nb);
  const SphView v{x_.data(), y_.data(), z_.data(), vx_.data(), vy_.data(), vz_.data(), Pa, Ia, La};
  const SphView bv{bx_.data(), by_.data(), bz_.data(), nullptr,     nullptr,     nullptr,    bP_.data(),
                   nullptr,    nullptr,    bw_.data(), bnx_.data(), bny_.data(), bnz_.data()};
#pragma omp parallel for schedule(static) if (n > kSphParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    float sum = 0.f, msum = 0.f, csum = 0.f;
    sph_poly6_range<false, true>(v, 0, un, v.X[i], v.Y[i], v.Z[i], h, h2, sum, msum);
    sph_poly6_range<true, true>(bv, 0, ub, v.X[i], v.Y[i], v.Z[i], h, h2, sum, msum);
    sph_contact_range(bv, 0, ub, v.X[i], v.Y[i], v.Z[i], h2, q0c, csum);
    const float r = mk * sum;
    R[i] = r;
    const float p = pressure_of(r);
    const float l = gradient_correction(msum);
    Pr[i] = p;
    Lc[i] = l;
    Ia[i] = 1.f / r;
    La[i] = l / r;
    Pa[i] = l * p / (r * r);
    const float rc = std::max(r, rho0 + mk * csum);
    Pc[i] = rc > r ? l * pressure_of(rc) / (rc * rc) : Pa[i];
  }
  const SphView pv{x_.data(), y_.data(), z_.data(), nullptr, nullptr, nullptr, Pr, R, Lc};
  for (std::size_t b = 0; b < nb; ++b) {
    float s[6] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
    sph_wall_range(pv, 0, un, bx_[b], by_[b], bz_[b], h2, s, p_.rest_density_kgpm3);
    set_boundary_pressure(b, s);
  }
  const float cp = mass_ * k_.spiky_k, cv = nu_ * p_.rest_density_kgpm3 * mass_ * k_.spiky_k;
#pragma omp parallel for schedule(static) if (n > kSphParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    const float vi[3] = {v.VX[i], v.VY[i], v.VZ[i]};
    float acc[7] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
    sph_force_range<false>(v, 0, un, v.X[i], v.Y[i], v.Z[i], vi, Pa[i], h, h2, rmin, pik, pbk, acc);
    sph_force_range<true>(bv, 0, ub, v.X[i], v.Y[i], v.Z[i], vi, Pc[i], h, h2, rmin, pikw, pbk, acc);
    ax[i] = g_[0] + cp * acc[0] + cv * Ia[i] * acc[3];
    ay[i] = g_[1] + cp * acc[1] + cv * Ia[i] * acc[4];
    az[i] = g_[2] + cp * acc[2] + cv * Ia[i] * acc[5];
  }
}

}  // namespace huygens
