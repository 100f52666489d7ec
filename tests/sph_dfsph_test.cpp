// DFSPH (huygens/sph/dfsph.hpp, Bender and Koschier 2015): a small hydrostatic column stays at rest
// with the density held within 0.1 % of rho0, and its pressure is rho0 g (H - z) within 2 %.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "huygens/validation/sph_cases.hpp"

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

// bottom pressure of the p(z) fit against the weight per floor area and rho0 g H, and the
// gradient against rho0 g, each within 2 % (the boundary's hydrostatic pressure, dfsph.hpp)
TEST(SphDfsph, HydrostaticPressureIsRho0GDepthWithinTwoPercent) {
  expect_rows({"bottom pressure", "pressure gradient"}, 3);
}
