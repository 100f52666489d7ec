// Stage statistics (common/stats.hpp): registration, lookup, counting a timed call and
// resetting the counts while keeping what was registered.
#include "huygens/common/stats.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

using namespace huygens;

TEST(StageStats, RegistersAndFindsStagesInOrder) {
  StageStats s;
  EXPECT_EQ(s.add("propagate", 1024), 0);
  EXPECT_EQ(s.add("height"), 1);
  ASSERT_EQ(s.all().size(), 2u);
  EXPECT_EQ(s.find("propagate"), 0);
  EXPECT_EQ(s.find("height"), 1);
  EXPECT_EQ(s.find("ships"), -1);
  EXPECT_EQ(s[0].name, "propagate");
  EXPECT_EQ(s[0].bytes, 1024u);
  EXPECT_EQ(s[1].bytes, 0u);
  EXPECT_EQ(s[1].calls, 0u);
  EXPECT_EQ(s[1].ns, 0u);
  EXPECT_EQ(s[1].transforms, 0u);
}

// A StageTimer counts one call and adds at least the time its scope lasted.
TEST(StageTimer, CountsACallAndItsWallTime) {
  StageStats s;
  const int i = s.add("sleep");
  const auto wait = std::chrono::milliseconds(20);
  for (int k = 0; k < 2; ++k) {
    StageTimer t(s[i]);
    std::this_thread::sleep_for(wait);
  }
  EXPECT_EQ(s[i].calls, 2u);
  EXPECT_GE(s[i].ns, 2u * static_cast<std::uint64_t>(std::chrono::nanoseconds(wait).count()));
  EXPECT_LT(s[i].ns, 10u * 1000u * 1000u * 1000u);  // and not absurdly more (10 s)
}

// reset_counts() zeroes calls, time and transforms; names and owned bytes stay.
TEST(StageStats, ResetKeepsNamesAndBytes) {
  StageStats s;
  const int i = s.add("spectrum", 4096);
  { StageTimer t(s[i]); }
  s[i].transforms += 3;
  s.reset_counts();
  EXPECT_EQ(s[i].name, "spectrum");
  EXPECT_EQ(s[i].bytes, 4096u);
  EXPECT_EQ(s[i].calls, 0u);
  EXPECT_EQ(s[i].ns, 0u);
  EXPECT_EQ(s[i].transforms, 0u);
}
