// The SPH pair sums and the density/force passes (huygens/sph/forces.hpp; Mueller, Charypar and
// Gross 2003 eq. 3, 10, 14; Monaghan 1992 eq. 4.1-4.2): the vector loops equal a scalar sum over
// exactly [b, e), 1/r by Newton steps, the grid path equals all pairs, the impact viscosity.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "huygens/common/fft.hpp"
#include "huygens/sph/forces.hpp"
#include "huygens/sph/system.hpp"

using namespace huygens;

namespace {

struct Arrays {
  explicit Arrays(std::size_t n) {
    for (auto* b : {&x, &y, &z, &vx, &vy, &vz, &pp, &ir, &lr, &w, &nx, &ny, &nz}) *b = AlignedBuffer<float>(n + 8);
    std::uint32_t s = 777;
    auto rnd = [&]() { return (s = s * 1664525u + 1013904223u) / 4294967296.f; };
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = 0.1f * rnd(), y[i] = 0.1f * rnd(), z[i] = 0.1f * rnd();
      vx[i] = rnd() - 0.5f, vy[i] = rnd() - 0.5f, vz[i] = rnd() - 0.5f;
      pp[i] = rnd(), ir[i] = 1e-3f * (0.9f + 0.2f * rnd()), lr[i] = ir[i], w[i] = 0.5f + rnd();
      const float a = rnd() - 0.5f, b = rnd() - 0.5f, c = rnd() - 0.5f, l = std::sqrt(a * a + b * b + c * c);
      nx[i] = a / l, ny[i] = b / l, nz[i] = c / l;
    }
  }
  SphView view() const {
    return {x.data(),  y.data(),  z.data(), vx.data(), vy.data(), vz.data(), pp.data(),
            ir.data(), lr.data(), w.data(), nx.data(), ny.data(), nz.data()};
  }
  AlignedBuffer<float> x, y, z, vx, vy, vz, pp, ir, lr, w, nx, ny, nz;
};

}  // namespace

TEST(SphForces, RsqrtWithinFiveMillionths) {
  for (double x = 1e-12; x < 1e12; x *= 1.37) {
    const double want = 1.0 / std::sqrt(double(float(x)));
    EXPECT_NEAR(sph_rsqrt(float(x)) / want, 1.0, 5e-6) << x;
  }
}

TEST(SphForces, DensitySumCoversExactlyTheRangeWeightedForBoundaries) {
  const Arrays a(100);
  const float h = 0.04f, h2 = h * h;
  for (const auto& [b, e] : {std::pair{3u, 61u}, std::pair{0u, 100u}, std::pair{17u, 18u}, std::pair{40u, 40u}}) {
    for (const bool bnd : {false, true}) {
      float sum = 0.f, msum = 0.f;
      if (bnd)
        sph_poly6_range<true, true>(a.view(), b, e, 0.05f, 0.05f, 0.05f, h, h2, sum, msum);
      else
        sph_poly6_range<false, true>(a.view(), b, e, 0.05f, 0.05f, 0.05f, h, h2, sum, msum);
      double want = 0, wantm = 0;
      for (std::uint32_t j = b; j < e; ++j) {
        const double dx = 0.05 - a.x[j], dy = 0.05 - a.y[j], dz = 0.05 - a.z[j];
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= h2) continue;
        const double w = bnd ? a.w[j] : 1.0;
        want += w * std::pow(h2 - r2, 3);
        wantm += w * (h - std::sqrt(r2)) * (h - std::sqrt(r2)) * std::sqrt(r2);
      }
      EXPECT_NEAR(sum, want, 1e-5 * want + 1e-20) << b << " " << e;
      EXPECT_NEAR(msum, wantm, 1e-4 * wantm + 1e-12) << b << " " << e;
    }
  }
}

// The wall sums of Adami et al. 2012 eq. 27: sum W, sum p W, sum rho (x_b - x_f) W, sum l W.
TEST(SphForces, WallSumsAreTheShepardSumsOfTheRange) {
  const Arrays a(100);
  const float h = 0.04f, h2 = h * h, xb = 0.05f, yb = 0.04f, zb = 0.06f;
  float s[6] = {0, 0, 0, 0, 0, 0};
  sph_wall_range(a.view(), 7, 93, xb, yb, zb, h2, s);
  double want[6] = {0, 0, 0, 0, 0, 0};
  for (std::uint32_t j = 7; j < 93; ++j) {
    const double d[3] = {xb - a.x[j], yb - a.y[j], zb - a.z[j]};
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (r2 >= h2) continue;
    const double w = std::pow(h2 - r2, 3);
    want[0] += w;
    want[1] += a.pp[j] * w;
    for (int k = 0; k < 3; ++k) want[2 + k] += a.ir[j] * d[k] * w;
    want[5] += a.lr[j] * w;
  }
  ASSERT_GT(want[0], 0.0);
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(s[k], want[k], 1e-4 * std::fabs(want[0] * (k == 1 ? 1 : 1e-3)) + 1e-4 * std::fabs(want[k]) + 1e-30)
        << k;
}

// sph_keep, the branch-free select of the vectorised loops: x or +0, bit for bit, for any x.
TEST(SphForces, KeepSelectsBitForBit) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  for (const float x : {1.5f, -2.f, 0.f, -0.f, 1e-40f, nan, inf, -inf}) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(sph_keep(true, x)), std::bit_cast<std::uint32_t>(x)) << x;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(sph_keep(false, x)), 0u) << x;
  }
}

// A candidate with a non-finite position lies outside the support: the density sum equals the one
// with that candidate far away (SphSystem flags the particle itself).
TEST(SphForces, NonFiniteCandidateLeavesTheDensitySum) {
  Arrays a(64), far(64);
  a.x[10] = std::numeric_limits<float>::quiet_NaN();
  far.x[10] = 1e3f;
  const float h = 0.04f, h2 = h * h;
  float sum = 0.f, msum = 0.f, sum_far = 0.f, msum_far = 0.f;
  sph_poly6_range<false, false>(a.view(), 0, 64, 0.05f, 0.05f, 0.05f, h, h2, sum, msum);
  sph_poly6_range<false, false>(far.view(), 0, 64, 0.05f, 0.05f, 0.05f, h, h2, sum_far, msum_far);
  EXPECT_GT(sum, 0.f);
  EXPECT_EQ(sum, sum_far);
}

TEST(SphForces, ForceSumIsPressureViscosityAndImpactOfTheRange) {
  const Arrays a(64);
  const float h = 0.05f, h2 = h * h, pik = 0.3f, pbk = 0.7f, Pi = 0.4f;
  const float xi = 0.05f, yi = 0.05f, zi = 0.05f, vi[3] = {0.1f, -0.2f, 0.3f};
  for (const bool bnd : {false, true}) {
    float acc[7] = {0, 0, 0, 0, 0, 0, 0};
    if (bnd)
      sph_force_range<true>(a.view(), 5, 59, xi, yi, zi, vi, Pi, h, h2, 1e-6f * h, pik, pbk, acc);
    else
      sph_force_range<false>(a.view(), 5, 59, xi, yi, zi, vi, Pi, h, h2, 1e-6f * h, pik, pbk, acc);
    double want[7] = {0, 0, 0, 0, 0, 0, 0};
    for (std::uint32_t j = 5; j < 59; ++j) {
      const double d[3] = {xi - a.x[j], yi - a.y[j], zi - a.z[j]};
      const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (r >= h) continue;
      // a boundary candidate: weighted by W, no viscous term, the impact term on the velocity
      // 2 (v_i . n) n relative to particle i's mirror image
      const double vj[3] = {a.vx[j], a.vy[j], a.vz[j]};
      const double w = bnd ? a.w[j] : 1.0;
      const double n[3] = {a.nx[j], a.ny[j], a.nz[j]};
      const double vn = vi[0] * n[0] + vi[1] * n[1] + vi[2] * n[2], dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
      const double vr = bnd ? 2 * vn * dn : (vi[0] - vj[0]) * d[0] + (vi[1] - vj[1]) * d[1] + (vi[2] - vj[2]) * d[2];
      const double mu = std::max(-vr, 0.0) / (r * r + 0.01 * h2);
      const double fp = w * (Pi + a.pp[j] + (pik + pbk * mu) * mu) * (h - r) * (h - r) / r;
      for (int k = 0; k < 3; ++k) {
        want[k] += fp * d[k];
        if (!bnd) want[3 + k] += (h - r) * a.ir[j] * (vj[k] - vi[k]);
      }
      want[6] += w * (h - r) * (h - r) * r;
    }
    for (int k = 0; k < 7; ++k) EXPECT_NEAR(acc[k], want[k], 1e-4 * std::fabs(want[k]) + 1e-9) << k << " " << bnd;
  }
}

TEST(SphForces, GridPathEqualsBruteForceAllPairs) {
  SphParams p;
  const float a = 0.05715f, dx = a / 8;
  p.spacing_m = dx;
  p.container_m = {4 * a, 4 * dx, 3 * a};
  p.fluid.push_back({{0, 0, 0}, {a, 4 * dx, 2 * a}});
  SphSystem s(p);
  for (int i = 0; i < 60; ++i) s.step();  // a moving state
  const std::size_t n = s.count();
  std::vector<float> a1(n), b1(n), c1(n), r1(n), a2(n), b2(n), c2(n), r2(n);
  s.grid_accelerations(a1, b1, c1, r1);
  s.brute_force_accelerations(a2, b2, c2, r2);
  double amax = 0;
  for (std::size_t i = 0; i < n; ++i) amax = std::max(amax, double(std::hypot(a1[i], b1[i], c1[i])));
  // densities are sums of positive terms: equal to float rounding, so no neighbour is missed or doubled.
  // Accelerations are sums of pair terms up to ~100 x the net value that cancel; in another summation
  // order float rounding moves them by up to ~30 terms x 6e-8 x 100 amax ~ 2e-4 amax.
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_NEAR(r1[i], r2[i], 1e-5 * p.rest_density_kgpm3);
    worst = std::max(worst, double(std::hypot(a1[i] - a2[i], b1[i] - b2[i], c1[i] - c2[i])));
  }
  EXPECT_LT(worst, 1e-3 * amax);
}

// Impact viscosity (Monaghan 1992): for two particles alone, far from walls (p = 0, so only the
// viscous terms act), switching (alpha, beta) on adds exactly a_i = m 45/(pi h^6) Pi_ij (h - r)^2 / r x_ij
// with Pi_ij = (alpha c0 mu + beta mu^2) / rho0, mu = h (-v_ij . x_ij) / (r^2 + h^2/100), when they
// approach, and nothing when they recede.
TEST(SphForces, ImpactViscosityActsOnlyOnApproachingPairs) {
  auto pair_ax = [](float alpha, float beta, float u, float& ax_left) {
    SphParams p;
    p.spacing_m = 0.01f;
    p.container_m = {0.5f, 0.5f, 0.5f};
    p.sound_speed_mps = 10.f;
    p.impact_alpha = alpha;
    p.impact_beta = beta;
    SphSystem s(p);
    const float r = 0.7f * s.support();
    const std::vector<float> X{0.25f - r / 2, 0.25f + r / 2}, Y{0.25f, 0.25f}, Z{0.25f, 0.25f};
    s.set_particles(X, Y, Z);
    std::vector<float> vx(2), vy(2, 0.f), vz(2, 0.f);
    for (std::size_t i = 0; i < 2; ++i) vx[i] = s.x()[i] < 0.25f ? u : -u;  // u > 0: approaching
    s.set_velocities(vx, vy, vz);
    std::vector<float> ax(2), ay(2), az(2), rho(2);
    s.grid_accelerations(ax, ay, az, rho);
    ax_left = s.x()[0] < 0.25f ? ax[0] : ax[1];
    return s;
  };
  const float u = 0.3f;
  for (const auto& [alpha, beta] : {std::pair{0.1f, 0.f}, std::pair{0.f, 4.f}, std::pair{0.1f, 4.f}}) {
    float a0, a1, b0, b1;
    const SphSystem s = pair_ax(0.f, 0.f, u, a0);
    pair_ax(alpha, beta, u, a1);
    const double h = s.support(), r = 0.7 * h, c0 = s.sound_speed();
    const double mu = h * (2.0 * u * r) / (r * r + 0.01 * h * h);  // -v_ij . x_ij = 2 u r (left particle)
    const double Pi = (alpha * c0 * mu + beta * mu * mu) / s.params().rest_density_kgpm3;
    const double expected = s.mass() * 45.0 / (std::numbers::pi * std::pow(h, 6)) * Pi * (h - r) * (h - r) / r * (-r);
    EXPECT_LT(expected, 0.0);  // pushes the left particle back (to -x)
    EXPECT_NEAR(a1 - a0, expected, 2e-4 * std::fabs(expected)) << "alpha " << alpha << " beta " << beta;
    pair_ax(0.f, 0.f, -u, b0);
    pair_ax(alpha, beta, -u, b1);
    EXPECT_EQ(b1, b0) << "receding pair, alpha " << alpha << " beta " << beta;
  }
}
