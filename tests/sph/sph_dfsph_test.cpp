// DFSPH (huygens/sph/dfsph.hpp, Bender and Koschier 2015): a small hydrostatic column stays at rest
// with the density held within 0.1 % of rho0, and its pressure is rho0 g (H - z) within 2 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "huygens/sph/system.hpp"
#include "huygens/validation/sph_cases.hpp"
#include "sph_test_helpers.hpp"

using namespace huygens;

namespace {

// The rows of a 6 x 6 x 12 column (1 s damped, 10 s free, held 1 s) from 4 starts (the lattice and 3
// moved by up to 1e-7 m; each row the worst start's), run once for both tests. The column leaves its
// start lattice in events of up to ~0.012 sqrt(g H) below the surface layer until t ~ 10 s at this size;
// over the hold the starts read 0.0033 (the lattice), 0.0052, 0.0006, 0.0042.
const std::vector<ValidationRow>& column_rows() {
  static const std::vector<ValidationRow> rows = sph_hydrostatic_rows(6, 12, 1.0, 10.0, 1.0, SphMethod::dfsph, 4);
  return rows;
}

// Asserts the rows whose quantity contains one of `keys`; expects `count` of them.
void expect_rows(const std::vector<std::string>& keys, int count) {
  int asserted = 0;
  for (const auto& r : column_rows())
    for (const auto& k : keys)
      if (r.quantity.find(k) != std::string::npos) {
        EXPECT_TRUE(r.pass) << r.quantity << ": measured " << r.measured << ", tolerance " << r.tolerance;
        ++asserted;
      }
  EXPECT_EQ(asserted, count);
}

}  // namespace

// mean density error below the surface layer within 0.1 %, max compression within 1 %, max speed
// below the surface layer within 1 % of sqrt(g H) (the worst of the 4 starts)
TEST(SphDfsph, HydrostaticColumnStaysAtRestWithinATenthOfAPercent) {
  expect_rows({"mean |rho/rho0 - 1|", "max compression", "max speed below the surface layer over"}, 3);
}

// The stillness row is the worst of the column's starts: one reported row per start, the judged row's
// figure their largest, and the 1e-7 m moves change the runs (not every start reads the same).
TEST(SphDfsph, StillnessRowIsTheWorstOfFourPerturbedStarts) {
  std::vector<double> starts;
  double judged = -1;
  for (const auto& r : column_rows()) {
    if (r.quantity.find("max speed below the surface layer") == std::string::npos) continue;
    if (r.judged)
      judged = r.measured;
    else
      starts.push_back(r.measured);
  }
  ASSERT_EQ(starts.size(), 4u);
  EXPECT_EQ(judged, *std::max_element(starts.begin(), starts.end()));
  EXPECT_NE(*std::min_element(starts.begin(), starts.end()), judged);
}

// bottom pressure of the p(z) fit against the weight per floor area (rho0 g H to 3e-5 with the cubic
// spline's mass), and the gradient against rho0 g, each within 2 % (the boundary's hydrostatic
// pressure, dfsph.hpp)
TEST(SphDfsph, HydrostaticPressureIsRho0GDepthWithinTwoPercent) {
  expect_rows({"bottom pressure", "pressure gradient"}, 2);
}

// The step's neighbour list (dfsph.hpp SphDfsphList) holds every fluid pair within the support: the
// density it sums equals the all-pairs cubic spline sum m (sum_j W_ij + sum_b w_b W_ib), also for a block
// compressed to 0.6 dx, whose ~150 neighbours per particle overflow the list's 56 slots, so the list
// grows and the pass runs again.
TEST(SphDfsph, NeighbourListHoldsEveryPairAndGrowsWhenItOverflows) {
  for (const float s : {1.f, 0.6f}) {
    SphParams p = test::box_params(8, 8);
    p.method = SphMethod::dfsph;
    SphSystem sys(p);
    const float dx = p.spacing_m * s;
    std::vector<float> px, py, pz;
    for (int k = 0; k < 8; ++k)
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
          px.push_back((i + 0.5f) * dx + 0.1f * p.spacing_m);
          py.push_back((j + 0.5f) * dx + 0.1f * p.spacing_m);
          pz.push_back((k + 0.5f) * dx);
        }
    sys.set_particles(px, py, pz);
    const SphKernels& kr = sys.kernels();
    const auto x = sys.x(), y = sys.y(), z = sys.z();
    const auto bx = sys.boundary_x(), by = sys.boundary_y(), bz = sys.boundary_z(), bw = sys.boundary_mass_ratio();
    double worst = 0;
    for (std::size_t i = 0; i < sys.count(); ++i) {
      double sum = 0;
      for (std::size_t j = 0; j < sys.count(); ++j) sum += kr.cubic(std::hypot(x[i] - x[j], y[i] - y[j], z[i] - z[j]));
      for (std::size_t b = 0; b < sys.boundary_count(); ++b)
        sum += bw[b] * kr.cubic(std::hypot(x[i] - bx[b], y[i] - by[b], z[i] - bz[b]));
      worst = std::max(worst, std::fabs(sys.density()[i] / (sys.mass() * sum) - 1.0));
    }
    EXPECT_LT(worst, 1e-4) << "compression " << s;
  }
}

namespace huygens {
// One DFSPH stage on its own (SphSystem's friend): the factors at the current positions, then the
// divergence-free solve of the current velocities with step dt.
struct SphSystemProbe {
  static int divergence_solve(SphSystem& s, float dt) {
    s.sort_particles();
    s.dfsph_factors();
    return s.dfsph_solve(dt, false);
  }
};
}  // namespace huygens

namespace {

// The SPH continuity equation Drho_i/Dt = sum_j m (v_i - v_j) . grad W_ij + sum_b m_b v_i . grad W_ib
// (BK15 eq. 6, walls at rest), all pairs, with the cubic spline's gradient written out here:
// grad W = -48 / (pi h^5) f(q) x_ij, f = 2 - 3q (q <= 1/2), (1 - q)^2 / q (q < 1).
std::vector<double> density_rate(const SphSystem& s) {
  const double h = s.support(), m = s.mass(), c = -48.0 / (M_PI * std::pow(h, 5));
  const auto grad = [&](double dx, double dy, double dz, double out[3]) {
    const double q = std::sqrt(dx * dx + dy * dy + dz * dz) / h;
    const double f = q <= 0.5 ? 2 - 3 * q : q < 1 ? (1 - q) * (1 - q) / q : 0.0;
    out[0] = c * f * dx, out[1] = c * f * dy, out[2] = c * f * dz;
  };
  const auto x = s.x(), y = s.y(), z = s.z(), vx = s.vx(), vy = s.vy(), vz = s.vz();
  const auto bx = s.boundary_x(), by = s.boundary_y(), bz = s.boundary_z(), bw = s.boundary_mass_ratio();
  std::vector<double> rate(s.count(), 0.0);
  for (std::size_t i = 0; i < s.count(); ++i) {
    double g[3], r = 0;
    for (std::size_t j = 0; j < s.count(); ++j) {
      if (j == i) continue;
      grad(x[i] - x[j], y[i] - y[j], z[i] - z[j], g);
      r += m * ((vx[i] - vx[j]) * g[0] + (vy[i] - vy[j]) * g[1] + (vz[i] - vz[j]) * g[2]);
    }
    for (std::size_t b = 0; b < s.boundary_count(); ++b) {
      grad(x[i] - bx[b], y[i] - by[b], z[i] - bz[b], g);
      r += m * bw[b] * (vx[i] * g[0] + vy[i] * g[1] + vz[i] * g[2]);
    }
    rate[i] = r;
  }
  return rate;
}

// mean over the particles of max(0, dt Drho/Dt) / rho0, the compression one step of dt would make; all
// particles, and those at least one spacing inside the box (`inner`) (unit: 1)
struct Compression {
  double all = 0, inner = 0;
};
Compression mean_compression(const SphSystem& s, double dt) {
  const auto rate = density_rate(s);
  const float dx = s.params().spacing_m, L = s.params().container_m[0];
  Compression c;
  int inner = 0;
  for (std::size_t i = 0; i < s.count(); ++i) {
    const double e = std::max(0.0, dt * rate[i]) / s.params().rest_density_kgpm3;
    c.all += e;
    const float lo = std::min({s.x()[i], s.y()[i], s.z()[i]}), hi = std::max({s.x()[i], s.y()[i], s.z()[i]});
    if (lo > dx && hi < L - dx) c.inner += e, ++inner;
  }
  c.all /= static_cast<double>(s.count());
  c.inner /= inner;
  return c;
}

}  // namespace

// The divergence-free solve (BK15 section 4.2, Algorithm 2) on an 8^3 block at rest density filling its
// box, without gravity, given the converging velocity v = -a (x - x_c): one step of dt would compress
// the inner 6^3 particles by 3 a dt = 1 % (the continuity equation, summed independently here over
// all pairs; the layer at the walls moves away from them and expands). After the solve the velocities
// must predict at most the solve's tolerance (dfsph_divergence_error, 1e-3) of compression, inside
// and overall; and the solve moves the fluid only by pressure kicks between pairs and from the walls,
// so the block's centre-of-mass velocity stays 0 by symmetry.
TEST(SphDfsph, DivergenceFreeSolveRemovesTheCompressionOfAConvergingFlow) {
  SphParams p = test::box_params(8, 8);
  p.method = SphMethod::dfsph;
  p.gravity_mps2 = {0.f, 0.f, 0.f};
  p.container_m[2] = 8 * p.spacing_m;  // the block fills its box: walls on all six sides
  SphSystem sys(p);
  sys.refresh();
  const float dt = 1e-3f, a = 0.01f / (3 * dt), c = 4 * p.spacing_m;
  std::vector<float> vx(sys.count()), vy(sys.count()), vz(sys.count());
  for (std::size_t i = 0; i < sys.count(); ++i) {
    vx[i] = -a * (sys.x()[i] - c), vy[i] = -a * (sys.y()[i] - c), vz[i] = -a * (sys.z()[i] - c);
  }
  sys.set_velocities(vx, vy, vz);
  const Compression before = mean_compression(sys, dt);
  const int iterations = SphSystemProbe::divergence_solve(sys, dt);
  const Compression after = mean_compression(sys, dt);
  EXPECT_NEAR(before.inner, 3 * a * dt, 0.05 * 3 * a * dt);
  EXPECT_LE(after.inner, p.dfsph_divergence_error) << iterations << " iterations";
  EXPECT_LE(after.all, p.dfsph_divergence_error) << "before " << before.all;
  EXPECT_LT(iterations, p.dfsph_max_iterations);
  double mx = 0, my = 0, mz = 0;
  for (std::size_t i = 0; i < sys.count(); ++i) mx += sys.vx()[i], my += sys.vy()[i], mz += sys.vz()[i];
  const double n = static_cast<double>(sys.count());
  EXPECT_LT(std::hypot(mx, my, mz) / n, 1e-3 * a * c) << "mean velocity after the solve";
  std::printf("compression before %.3g (inner %.3g), after %.3g (inner %.3g), %d iterations\n", before.all,
              before.inner, after.all, after.inner, iterations);
}
