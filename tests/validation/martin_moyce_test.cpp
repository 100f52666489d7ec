// The Martin & Moyce (1952) table compiled into the validation library, and its parser.
#include "huygens/validation/reference/martin_moyce.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace huygens;

TEST(MartinMoyce, EmbeddedTableHoldsBothSeries) {
  const auto pts = martin_moyce_1952();
  ASSERT_EQ(pts.size(), 25u);
  int small = 0, large = 0;
  for (const auto& p : pts) {
    small += p.series == "1.125";
    large += p.series == "2.25";
    EXPECT_GT(p.T, 0.0);
    EXPECT_GE(p.Z, 1.0);  // the front starts at the column's width
  }
  EXPECT_EQ(small, 10);
  EXPECT_EQ(large, 15);
  EXPECT_EQ(pts.front().T, 0.849);
  EXPECT_EQ(pts.front().Z, 1.245);
  EXPECT_EQ(pts.back().T, 9.237);
  EXPECT_EQ(pts.back().Z, 13.970);
}

TEST(MartinMoyce, ParserSkipsCommentsHeaderAndEmptyLines) {
  const auto pts = parse_martin_moyce("# comment\na_in,T,Z\n\n1.125,0.5,1.1\n2.25,1.5,2.25");
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[0].series, "1.125");
  EXPECT_EQ(pts[0].T, 0.5);
  EXPECT_EQ(pts[1].Z, 2.25);
}

TEST(MartinMoyce, ParserRefusesABadNumber) { EXPECT_THROW(parse_martin_moyce("1.125,x,1.0\n"), std::invalid_argument); }
