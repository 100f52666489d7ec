// The SPH time step and integration (huygens/sph/integration.hpp): dt is the smallest of the CFL,
// force, viscous and dt_max conditions and names it; symplectic Euler, and no position clamp.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "huygens/sph/integration.hpp"
#include "huygens/sph/system.hpp"
#include "sph_test_helpers.hpp"

using namespace huygens;
using huygens::test::box_params;

TEST(SphIntegration, DtIsTheSmallestConditionAndNamesIt) {
  SphParams p;  // cfl 0.15, force 0.18, viscous 0.03, dt_max 1e-3
  const float h = 0.02f;
  const char* lim = "";
  EXPECT_EQ(sph_choose_dt(p, h, 1.f, 0.f, 0.f, 0.f, lim), double(p.dt_max_s));
  EXPECT_STREQ(lim, "dt_max");
  EXPECT_NEAR(sph_choose_dt(p, h, 10.f, 0.f, 2.f, 0.f, lim), 0.15 * 0.02 / 12.0, 1e-9);
  EXPECT_STREQ(lim, "cfl");
  EXPECT_NEAR(sph_choose_dt(p, h, 1.f, 0.f, 0.f, 1e4f, lim), 0.18 * std::sqrt(0.02 / 1e4), 1e-9);
  EXPECT_STREQ(lim, "force");
  EXPECT_NEAR(sph_choose_dt(p, h, 1.f, 1.f, 0.f, 1.f, lim), 0.03 * 0.02 * 0.02 / 1.0, 1e-12);
  EXPECT_STREQ(lim, "viscous");
}

TEST(SphIntegration, SymplecticEulerWithoutAClamp) {
  // 0: free; 1: crosses the floor plane: no clamp moves it back (the boundary particles' pressure
  // keeps fluid inside, not the integrator)
  float x[2] = {0.2f, 0.2f}, y[2] = {0.2f, 0.2f}, z[2] = {0.5f, 0.002f};
  float vx[2] = {1.f, 0.5f}, vy[2] = {0.f, 0.f}, vz[2] = {0.f, -1.f};
  const float ax[2] = {0.f, 0.f}, ay[2] = {0.f, 0.f}, az[2] = {-10.f, -10.f};
  sph_integrate(0.f, 0.01f, SphMotion{x, y, z, vx, vy, vz, ax, ay, az, 2});
  EXPECT_FLOAT_EQ(vz[0], -0.1f);  // v += a dt, then x += v dt with the new v
  EXPECT_FLOAT_EQ(z[0], 0.5f - 0.001f);
  EXPECT_FLOAT_EQ(x[0], 0.21f);
  EXPECT_FLOAT_EQ(vz[1], -1.1f);
  EXPECT_FLOAT_EQ(z[1], 0.002f - 0.011f);
}

TEST(SphIntegration, DampingSlowsEveryParticle) {
  float x = 0.1f, y = 0.1f, z = 0.1f, vx = 1.f, vy = 0.f, vz = 0.f;
  const float a = 0.f;
  sph_integrate(100.f, 0.01f, SphMotion{&x, &y, &z, &vx, &vy, &vz, &a, &a, &a, 1});
  EXPECT_FLOAT_EQ(vx, 0.5f);  // v / (1 + damping dt)
}

TEST(SphIntegration, AdaptiveTimeStepIsReportedAndBounded) {
  SphSystem s(box_params(6, 8));
  for (int k = 0; k < 50; ++k) s.step();
  const auto& d = s.dt_stats();
  EXPECT_EQ(d.count, 50);
  EXPECT_LE(d.max, s.params().cfl * s.support() / s.sound_speed() * (1 + 1e-6));
  EXPECT_GT(d.min, 0);
  EXPECT_EQ(s.dt_history().size(), 50u);
  EXPECT_NEAR(s.time(), d.sum, 1e-12);
}
