// DFSPH (huygens/sph/dfsph.hpp, Bender and Koschier 2015): a small hydrostatic column stays at rest
// with the density held within 0.1 % of rho0.
#include <gtest/gtest.h>

#include <string>

#include "huygens/validation/sph_cases.hpp"

using namespace huygens;

namespace {

// The rows of a 6 x 6 x 12 column (1 s damped, 2 s free, held 0.5 s) that this test asserts:
// mean density error below the surface layer within 0.1 %, max compression within 1 %, max speed
// within 1 % of sqrt(g H). (The bottom-pressure rows are reported by `huygens validate
// sph_hydrostatic_dfsph`, not asserted here: docs/sph.md, "DFSPH".)
void expect_at_rest() {
  int asserted = 0;
  for (const auto& r : sph_hydrostatic_rows(6, 12, 1.0, 2.0, 0.5, SphMethod::dfsph))
    if (r.quantity.find("mean |rho/rho0 - 1|") != std::string::npos ||
        r.quantity.find("max compression") != std::string::npos || r.quantity.find("max speed") != std::string::npos) {
      EXPECT_TRUE(r.pass) << r.quantity << ": measured " << r.measured << ", tolerance " << r.tolerance;
      ++asserted;
    }
  EXPECT_EQ(asserted, 3);
}

}  // namespace

TEST(SphDfsph, HydrostaticColumnStaysAtRestWithinATenthOfAPercent) { expect_at_rest(); }
