// The SPH particle system (huygens/sph/system.hpp): fluid placement, bitwise determinism across
// thread counts, non-finite values stopped with the stage named, interaction. The physics of
// `huygens validate` at test size is in sph_physics_test.cpp.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "huygens/common/finite.hpp"
#include "huygens/sph/system.hpp"
#include "huygens/validation/sph_cases.hpp"
#include "sph_test_helpers.hpp"

using namespace huygens;
using huygens::test::box_params;
using huygens::test::expect_rows_pass;

TEST(SphSystem, FluidBlocksFillTheLatticeOfCellCentresOutsideObstacles) {
  SphParams p;
  p.spacing_m = 0.01f;
  p.container_m = {0.1f, 0.1f, 0.1f};
  p.fluid.push_back({{0.f, 0.f, 0.f}, {0.04f, 0.03f, 0.02f}});
  const SphSystem s(p);
  ASSERT_EQ(s.count(), 4u * 3u * 2u);
  for (std::size_t i = 0; i < s.count(); ++i) {
    const float fx = s.x()[i] / 0.01f - 0.5f, fy = s.y()[i] / 0.01f - 0.5f, fz = s.z()[i] / 0.01f - 0.5f;
    EXPECT_NEAR(fx, std::round(fx), 1e-4f);
    EXPECT_NEAR(fy, std::round(fy), 1e-4f);
    EXPECT_NEAR(fz, std::round(fz), 1e-4f);
  }
  // a cylinder through the block removes the particles within half a spacing of it
  SphObstacle cyl;
  cyl.type = SphObstacle::Type::cylinder;
  cyl.centre_m = {0.05f, 0.05f};
  cyl.radius_m = 0.02f;
  cyl.z1_m = 0.1f;
  p.fluid[0].max_m = {0.1f, 0.1f, 0.02f};
  p.obstacles.push_back(cyl);
  const SphSystem t(p);
  // 10 x 10 x 2 centres; within r < 0.025 m of the axis lie the 4 x 4 centres at offsets
  // +-0.005 and +-0.015 m in each layer (the next ring, r^2 = 6.5e-4 > 6.25e-4 m^2, stays)
  EXPECT_EQ(t.count(), 200u - 2u * 16u);
  for (std::size_t i = 0; i < t.count(); ++i) EXPECT_FALSE(cyl.blocks(t.x()[i], t.y()[i], t.z()[i], 0.005f));
}

TEST(SphSystem, DeterministicAcrossThreadCounts) {
  auto run = [](int threads) {
    omp_set_num_threads(threads);
    SphSystem s(box_params(16, 10));  // 2560 particles: above the size where the step goes parallel
    s.add_velocity_splash(0.04f, 0.04f, 0.02f, 0.5f);
    for (int k = 0; k < 40; ++k) s.step();
    std::vector<float> pos(3 * s.count());
    s.positions_by_id(pos);
    std::uint64_t hsh = 1469598103934665603ull;
    for (float v : pos) {
      std::uint32_t u;
      std::memcpy(&u, &v, 4);
      hsh = (hsh ^ u) * 1099511628211ull;
    }
    return hsh;
  };
  const auto h1 = run(1), h2 = run(2);
  omp_set_num_threads(2);
  EXPECT_EQ(h1, h2);
}
TEST(SphSystem, NonFiniteStopsWithTheStageNamed) {
  SphSystem s(box_params(4, 4));
  std::vector<float> X(s.x().begin(), s.x().end()), Y(s.y().begin(), s.y().end()), Z(s.z().begin(), s.z().end());
  X[3] = std::numeric_limits<float>::quiet_NaN();
  s.set_particles(X, Y, Z);
  try {
    s.step();
    FAIL() << "no NonFiniteError";
  } catch (const NonFiniteError& e) {
    EXPECT_EQ(e.stage(), "density");
  }
}
TEST(SphSystem, SplashAndGravityInteraction) {
  SphSystem s(box_params(8, 6));
  s.add_velocity_splash(0.02f, 0.02f, 0.01f, 1.f);
  float vmin = 0;
  for (float v : s.vz()) vmin = std::min(vmin, v);
  EXPECT_LT(vmin, -0.5f);
  s.set_gravity({1.f, 0.f, -9.81f});
  EXPECT_FLOAT_EQ(s.gravity()[0], 1.f);
}
