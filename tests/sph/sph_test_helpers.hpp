#pragma once
// Shared by the SPH test files: a fluid block filling the floor of a box, and the check that
// validation rows pass.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "huygens/sph/params.hpp"
#include "huygens/validation/validation.hpp"

namespace huygens::test {

/// nx x nx x nz particles of spacing dx (m) on the floor of an nx x nx x 2 nz box.
inline SphParams box_params(int nx, int nz, float dx = 0.005f) {
  SphParams p;
  p.spacing_m = dx;
  p.container_m = {nx * dx, nx * dx, 2.f * nz * dx};
  p.fluid.push_back({{0, 0, 0}, {nx * dx, nx * dx, nz * dx}});
  return p;
}

inline void expect_rows_pass(const std::vector<ValidationRow>& rows) {
  ASSERT_FALSE(rows.empty());
  for (const auto& r : rows)
    EXPECT_TRUE(r.pass) << r.case_name << ": " << r.quantity << " measured " << r.measured << " expected " << r.expected
                        << " error " << r.error << " tolerance " << r.tolerance;
}

}  // namespace huygens::test
