// The analytic Stoker dam break: the middle state satisfies the fan invariant and the
// Rankine-Hugoniot relations, the profile is continuous through the fan, and a weak dam
// tends to a sound wave.
#include "huygens/lbm/stoker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace huygens;

TEST(Stoker, MiddleStateSatisfiesShockAndFanRelations) {
  const double g = 9.81;
  for (double ratio : {1.5, 2.0, 5.0, 10.0, 100.0}) {
    const double hl = 2.0, hr = hl / ratio;
    const auto s = stoker_solve({hl, hr, g});
    const double hm = s.middle_depth_m, um = s.middle_velocity_mps, sh = s.shock_speed_mps;
    ASSERT_GT(hm, hr);
    ASSERT_LT(hm, hl);
    // Riemann invariant through the left-going fan: u + 2c = 2 c_L.
    EXPECT_NEAR(um + 2 * std::sqrt(g * hm), 2 * std::sqrt(g * hl), 1e-10) << ratio;
    // Mass and momentum across the shock (still water ahead of it).
    EXPECT_NEAR(sh * (hm - hr), hm * um, 1e-10 * hl * um) << ratio;
    EXPECT_NEAR(sh * hm * um, hm * um * um + 0.5 * g * (hm * hm - hr * hr), 1e-9 * g * hl * hl) << ratio;
    // The shock outruns the sound speed ahead and is subsonic relative to the flow behind it.
    EXPECT_GT(sh, std::sqrt(g * hr));
    EXPECT_LT(sh - um, std::sqrt(g * hm));
  }
}

TEST(Stoker, ProfileIsContinuousThroughTheFan) {
  const auto s = stoker_solve({1.0, 0.2, 9.81});
  const double eps = 1e-9;
  EXPECT_NEAR(s.depth(s.fan_head_speed_mps - eps), s.depth(s.fan_head_speed_mps + eps), 1e-7);
  EXPECT_NEAR(s.depth(s.fan_tail_speed_mps - eps), s.depth(s.fan_tail_speed_mps + eps), 1e-7);
  EXPECT_NEAR(s.velocity(s.fan_tail_speed_mps - eps), s.velocity(s.fan_tail_speed_mps + eps), 1e-7);
  EXPECT_DOUBLE_EQ(s.depth(-100.0), 1.0);
  EXPECT_DOUBLE_EQ(s.depth(100.0), 0.2);
  EXPECT_DOUBLE_EQ(s.velocity(100.0), 0.0);
  // The shock is a jump from h_m to h_R.
  EXPECT_DOUBLE_EQ(s.depth(s.shock_speed_mps - eps), s.middle_depth_m);
}

TEST(Stoker, WeakDamBecomesASoundWave) {
  const double g = 9.81, h = 1.0;
  const auto s = stoker_solve({h * (1 + 1e-6), h, g});
  EXPECT_NEAR(s.shock_speed_mps, std::sqrt(g * h), 1e-5);
  EXPECT_NEAR(s.middle_depth_m, h * (1 + 0.5e-6), 1e-9);
}

TEST(Stoker, RejectsInvalidDepths) {
  EXPECT_THROW(stoker_solve({1.0, 1.0, 9.81}), std::invalid_argument);
  EXPECT_THROW(stoker_solve({1.0, 0.0, 9.81}), std::invalid_argument);
  EXPECT_THROW(stoker_solve({0.5, 1.0, 9.81}), std::invalid_argument);
}
