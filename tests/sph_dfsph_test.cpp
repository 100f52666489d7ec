// DFSPH (huygens/sph/dfsph.hpp, Bender and Koschier 2015): a small hydrostatic column stays at rest
// with the density held within 0.1 % of rho0, and its pressure is rho0 g (H - z) within 2 %.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "huygens/sph/system.hpp"
#include "huygens/validation/sph_cases.hpp"
#include "sph_test_helpers.hpp"

using namespace huygens;

namespace {

// The rows of a 6 x 6 x 12 column (1 s damped, 2 s free, held 0.5 s), run once for both tests.
const std::vector<ValidationRow>& column_rows() {
  static const std::vector<ValidationRow> rows = sph_hydrostatic_rows(6, 12, 1.0, 2.0, 0.5, SphMethod::dfsph);
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
// within 1 % of sqrt(g H)
TEST(SphDfsph, HydrostaticColumnStaysAtRestWithinATenthOfAPercent) {
  expect_rows({"mean |rho/rho0 - 1|", "max compression", "max speed"}, 3);
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
