#include "huygens/common/finite.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

using namespace huygens;

TEST(Finite, DetectsNaNAndInfinityAnywhere) {
  std::vector<float> v(1027, 1.5f);
  EXPECT_TRUE(all_finite(v));
  for (std::size_t at : {std::size_t{0}, std::size_t{513}, std::size_t{1026}}) {
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                      -std::numeric_limits<float>::infinity()}) {
      auto w = v;
      w[at] = bad;
      EXPECT_FALSE(all_finite(w)) << at;
    }
  }
  std::vector<cfloat> c(10, cfloat(1, 2));
  EXPECT_TRUE(all_finite(c));
  c[7] = cfloat(0, std::numeric_limits<float>::infinity());
  EXPECT_FALSE(all_finite(c));
}
