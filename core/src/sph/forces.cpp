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

// rho_i = m 315/(64 pi h^9) sum_j (h^2 - r^2)^3 over the neighbours and their wall images, plus the
// obstacles' ghost density; then p_i, 1/rho_i, l_i/rho_i and P_i = l_i p_i / rho_i^2.
void SphSystem::compute_density(bool fresh_moment) {
  const std::size_t n = n_;
  const SphView v{x_.data(),  y_.data(), z_.data(),    vx_.data(),   vy_.data(),
                  vz_.data(), P_.data(), irho_.data(), lirho_.data()};
  const float h = h_, h2 = k_.h2, mk = mass_ * k_.poly6_k;
#pragma omp parallel if (n > kSphParallelMin)
  {
    const float* src[3] = {v.X, v.Y, v.Z};
    SphCellGather::Cursor cur(grid_, gather_, omp_get_thread_num(), src, 3);
    const SphView sv{cur.scratch(0), cur.scratch(1), cur.scratch(2), nullptr, nullptr,
                     nullptr,        nullptr,        nullptr,        nullptr};
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const float xi = v.X[i], yi = v.Y[i], zi = v.Z[i];
      SphImage im[8];
      im[0] = sph_self_image(xi, yi, zi);
      const int ni = sph_container_images(xi, yi, zi, h, p_.container_m, g_, im + 1);
      float sum = 0.f, msum = 0.f;
      // an image across the floor pairs only with candidates of the bottom cell layer (z_i + z_j < h);
      // the direct path always sums the moment
      const bool gathered =
          cur.visit(grid_.ix(xi), grid_.iy(yi), grid_.iz(zi),
                    [&](bool g, std::uint32_t b, std::uint32_t e, std::uint32_t floor_end) {
                      const SphView& w = g ? sv : v;
                      if (fresh_moment || !g) {
                        sph_poly6_range<false, true>(w, b, e, im[0], h, h2, sum, msum);
                        for (int k = 1; k <= ni; ++k)
                          sph_poly6_range<true, true>(w, b, im[k].floor ? floor_end : e, im[k], h, h2, sum, msum);
                      } else {
                        sph_poly6_range<false, false>(w, b, e, im[0], h, h2, sum, msum);
                        for (int k = 1; k <= ni; ++k)
                          sph_poly6_range<true, false>(w, b, im[k].floor ? floor_end : e, im[k], h, h2, sum, msum);
                      }
                    });
      // a non-finite position is masked out of every neighbour sum: make its own density say so
      float rho = std::isfinite(xi + yi + zi) ? mk * sum : std::numeric_limits<float>::quiet_NaN();
      walls_.add_density(xi, yi, zi, rho);
      rho_[i] = rho;
      const float p = pressure_of(rho);
      p_arr_[i] = p;
      // the correction of the previous force pass (positions one step older) or a fresh one
      const float l = fresh_moment || !gathered ? gradient_correction(msum) : corr_[i];
      corr_[i] = l;
      irho_[i] = 1.f / rho;
      lirho_[i] = l / rho;
      P_[i] = l * p / (rho * rho);
    }
  }
}

// a_i = g + m 45/(pi h^6) (pressure sum) + nu rho0 m 45/(pi h^6) / rho_i (viscous sum) + obstacles;
// also the spiky first moment for the next step's gradient correction, and max |a|, max |v|.
void SphSystem::compute_forces() {
  const std::size_t n = n_;
  const SphView v{x_.data(),  y_.data(), z_.data(),    vx_.data(),   vy_.data(),
                  vz_.data(), P_.data(), irho_.data(), lirho_.data()};
  const float h = h_, h2 = k_.h2, rmin = 1e-6f * h_;
  const float pik = pik_, pbk = pbk_;
  const float cp = mass_ * k_.spiky_k;                                // m 45/(pi h^6)
  const float cv = nu_ * p_.rest_density_kgpm3 * mass_ * k_.spiky_k;  // nu rho0 m 45/(pi h^6)
  const float gx = g_[0], gy = g_[1], gz = g_[2];
  float amax2 = 0.f, vmax2 = 0.f;
#pragma omp parallel if (n > kSphParallelMin) reduction(max : amax2, vmax2)
  {
    const float* src[SphCellGather::kMaxArrays] = {v.X, v.Y, v.Z, v.VX, v.VY, v.VZ, v.PP, v.IR, v.LR};
    SphCellGather::Cursor cur(grid_, gather_, omp_get_thread_num(), src, SphCellGather::kMaxArrays);
    const SphView sv{cur.scratch(0), cur.scratch(1), cur.scratch(2), cur.scratch(3), cur.scratch(4),
                     cur.scratch(5), cur.scratch(6), cur.scratch(7), cur.scratch(8)};
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const float xi = v.X[i], yi = v.Y[i], zi = v.Z[i], Pi = v.PP[i];
      const float vi[3] = {v.VX[i], v.VY[i], v.VZ[i]};
      SphImage im[8];
      im[0] = sph_self_image(xi, yi, zi);
      const int ni = sph_container_images(xi, yi, zi, h, p_.container_m, g_, im + 1);
      float acc[7] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
      cur.visit(grid_.ix(xi), grid_.iy(yi), grid_.iz(zi),
                [&](bool g, std::uint32_t b, std::uint32_t e, std::uint32_t floor_end) {
                  const SphView& w = g ? sv : v;
                  sph_force_range<false>(w, b, e, im[0], vi, Pi, h, h2, rmin, pik, pbk, acc);
                  for (int k = 1; k <= ni; ++k)
                    sph_force_range<true>(w, b, im[k].floor ? floor_end : e, im[k], vi, Pi, h, h2, rmin, pik, pbk, acc);
                });
      const float vis = cv * v.IR[i];
      float ax = gx + cp * acc[0] + vis * acc[3];
      float ay = gy + cp * acc[1] + vis * acc[4];
      float az = gz + cp * acc[2] + vis * acc[5];
      walls_.add_force(xi, yi, zi, Pi, ax, ay, az);
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
  compute_forces();
  std::copy(ax_.data(), ax_.data() + n_, ax.begin());
  std::copy(ay_.data(), ay_.data() + n_, ay.begin());
  std::copy(az_.data(), az_.data() + n_, az.begin());
  std::copy(rho_.data(), rho_.data() + n_, rho.begin());
}

void SphSystem::brute_force_accelerations(std::span<float> ax, std::span<float> ay, std::span<float> az,
                                          std::span<float> rho) {
  // the same physics with every particle (and every wall image) tested against every other
  const std::size_t n = n_;
  const float h = h_, h2 = k_.h2, mk = mass_ * k_.poly6_k, rmin = 1e-6f * h_;
  const float pik = pik_, pbk = pbk_;
  float* R = rho.data();
  float* Pa = tx_.data();  // scratch: p / rho^2
  float* Ia = ty_.data();  // scratch: 1 / rho
  float* La = tz_.data();  // scratch: l / rho
  const auto un = static_cast<std::uint32_t>(n);
  const SphView v{x_.data(), y_.data(), z_.data(), vx_.data(), vy_.data(), vz_.data(), Pa, Ia, La};
#pragma omp parallel for schedule(static) if (n > kSphParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    SphImage im[8];
    im[0] = sph_self_image(v.X[i], v.Y[i], v.Z[i]);
    const int ni = sph_container_images(v.X[i], v.Y[i], v.Z[i], h, p_.container_m, g_, im + 1);
    float sum = 0.f, msum = 0.f;
    sph_poly6_range<false, true>(v, 0, un, im[0], h, h2, sum, msum);
    for (int k = 1; k <= ni; ++k) sph_poly6_range<true, true>(v, 0, un, im[k], h, h2, sum, msum);
    float r = mk * sum;
    walls_.add_density(v.X[i], v.Y[i], v.Z[i], r);
    R[i] = r;
    const float p = pressure_of(r);
    const float l = gradient_correction(msum);
    Ia[i] = 1.f / r;
    La[i] = l / r;
    Pa[i] = l * p / (r * r);
  }
  const float cp = mass_ * k_.spiky_k, cv = nu_ * p_.rest_density_kgpm3 * mass_ * k_.spiky_k;
#pragma omp parallel for schedule(static) if (n > kSphParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    SphImage im[8];
    im[0] = sph_self_image(v.X[i], v.Y[i], v.Z[i]);
    const int ni = sph_container_images(v.X[i], v.Y[i], v.Z[i], h, p_.container_m, g_, im + 1);
    const float vi[3] = {v.VX[i], v.VY[i], v.VZ[i]};
    float acc[7] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
    sph_force_range<false>(v, 0, un, im[0], vi, Pa[i], h, h2, rmin, pik, pbk, acc);
    for (int k = 1; k <= ni; ++k) sph_force_range<true>(v, 0, un, im[k], vi, Pa[i], h, h2, rmin, pik, pbk, acc);
    float a0 = g_[0] + cp * acc[0] + cv * Ia[i] * acc[3];
    float a1 = g_[1] + cp * acc[1] + cv * Ia[i] * acc[4];
    float a2 = g_[2] + cp * acc[2] + cv * Ia[i] * acc[5];
    walls_.add_force(v.X[i], v.Y[i], v.Z[i], Pa[i], a0, a1, a2);
    ax[i] = a0;
    ay[i] = a1;
    az[i] = a2;
  }
}

}  // namespace huygens
