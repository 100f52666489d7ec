// SPH walls and obstacles (huygens/sph/boundary.hpp): the mirror images at faces, edges and
// corners with the hydrostatic image pressure of Adami, Hu and Adams 2012 eq. 27, the obstacles'
// signed distance and ghost tables, and the rest density and energy of a fluid in a closed box.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "huygens/sph/boundary.hpp"
#include "huygens/sph/system.hpp"

using namespace huygens;

TEST(SphBoundary, MirrorImagesAtFacesEdgesAndCorners) {
  const std::array<float, 3> box{1.f, 1.f, 1.f}, g{0.f, 0.f, -9.81f};
  const float h = 0.1f;
  SphImage im[8];
  EXPECT_EQ(sph_container_images(0.5f, 0.5f, 0.5f, h, box, g, im), 0);
  // one face (x = 0): d = x_i - x_j' with x_j' = -X_j, so o_x = x_i, s = (+1, -1, -1)
  ASSERT_EQ(sph_container_images(0.05f, 0.5f, 0.5f, h, box, g, im), 1);
  EXPECT_FLOAT_EQ(im[0].o[0], 0.05f);
  EXPECT_EQ(im[0].s[0], 1.f);
  EXPECT_EQ(im[0].s[1], -1.f);
  EXPECT_EQ(im[0].s[2], -1.f);
  EXPECT_EQ(im[0].floor, 0);
  EXPECT_EQ(im[0].G0, 0.f);  // g has no x component: no hydrostatic difference across x planes
  // the far face x = 1: x_j' = 2 - X_j
  ASSERT_EQ(sph_container_images(0.95f, 0.5f, 0.5f, h, box, g, im), 1);
  EXPECT_FLOAT_EQ(im[0].o[0], 0.95f - 2.f);
  // an edge: 3 images (two faces and the edge)
  EXPECT_EQ(sph_container_images(0.05f, 0.95f, 0.5f, h, box, g, im), 3);
  // a floor corner: 7 images, the 4 across the floor flagged
  ASSERT_EQ(sph_container_images(0.05f, 0.05f, 0.05f, h, box, g, im), 7);
  int floors = 0;
  for (int k = 0; k < 7; ++k) floors += im[k].floor;
  EXPECT_EQ(floors, 4);
  // the lid z = 1: p_j' - p_j = rho_j g . (x_j' - x_j) = rho_j g_z (2 - 2 Z_j) = rho_j (G0 + gs_z Z_j)
  ASSERT_EQ(sph_container_images(0.5f, 0.5f, 0.95f, h, box, g, im), 1);
  const float Zj = 0.97f;
  EXPECT_NEAR(im[0].G0 + im[0].gs[2] * Zj, -9.81f * (2.f - 2.f * Zj), 1e-5f);
}

TEST(SphBoundary, ObstacleSignedDistanceAndNormal) {
  SphObstacle box;
  box.min_m = {0.4f, 0.4f, 0.4f};
  box.max_m = {0.6f, 0.6f, 0.6f};
  float n[3];
  EXPECT_NEAR(box.distance(0.5f, 0.5f, 0.7f, n), 0.1f, 1e-6f);
  EXPECT_EQ(n[2], 1.f);
  EXPECT_NEAR(box.distance(0.5f, 0.5f, 0.55f, n), -0.05f, 1e-6f);
  EXPECT_EQ(n[2], 1.f);
  EXPECT_NEAR(box.distance(0.7f, 0.7f, 0.5f, n), std::sqrt(0.02f), 1e-6f);  // outside an edge
  EXPECT_NEAR(n[0], std::sqrt(0.5f), 1e-6f);
  EXPECT_TRUE(box.near(0.65f, 0.5f, 0.5f, 0.1f));
  EXPECT_FALSE(box.near(0.75f, 0.5f, 0.5f, 0.1f));
  SphObstacle cyl;
  cyl.type = SphObstacle::Type::cylinder;
  cyl.centre_m = {0.5f, 0.5f};
  cyl.radius_m = 0.1f;
  cyl.z0_m = 0.f;
  cyl.z1_m = 1.f;
  EXPECT_NEAR(cyl.distance(0.7f, 0.5f, 0.5f, n), 0.1f, 1e-6f);
  EXPECT_EQ(n[0], 1.f);
  EXPECT_NEAR(cyl.distance(0.5f, 0.45f, 0.5f, n), -0.05f, 1e-6f);
  EXPECT_NEAR(n[1], -1.f, 1e-6f);
  EXPECT_NEAR(cyl.distance(0.5f, 0.5f, 1.2f, n), 0.2f, 1e-6f);  // above the top
  EXPECT_EQ(n[2], 1.f);
}

TEST(SphBoundary, ObstacleGhostDensityAndForceActOnlyNearTheSurface) {
  SphObstacle box;
  box.min_m = {0.4f, 0.4f, 0.f};
  box.max_m = {0.6f, 0.6f, 1.f};
  const float dx = 0.01f, h = 2 * dx;
  const SphKernels k(h);
  const SphObstacleWalls walls({box}, k, dx, 1e-3f);
  float rho = 1000.f;
  walls.add_density(0.2f, 0.5f, 0.5f, rho);  // farther than h
  EXPECT_EQ(rho, 1000.f);
  walls.add_density(0.6f + 0.5f * dx, 0.5f, 0.5f, rho);  // half a spacing from the +x face
  EXPECT_GT(rho, 1000.f);
  float ax = 0, ay = 0, az = 0;
  walls.add_force(0.6f + 0.5f * dx, 0.5f, 0.5f, 1.f, ax, ay, az);
  EXPECT_GT(ax, 0.f);  // pushed out along the face normal
  EXPECT_EQ(ay, 0.f);
  EXPECT_EQ(az, 0.f);
  float bx = 0, by = 0, bz = 0;
  walls.add_force(0.6f + 0.5f * dx, 0.5f, 0.5f, 0.f, bx, by, bz);  // no pressure, no force
  EXPECT_EQ(bx, 0.f);
}

TEST(SphBoundary, RestLatticeInAClosedBoxHasRestDensityEverywhere) {
  // mirror images at the walls, edges and corners complete every particle's density
  SphParams p;
  p.spacing_m = 0.005f;
  p.container_m = {0.04f, 0.03f, 0.035f};
  p.fluid.push_back({{0, 0, 0}, p.container_m});
  SphSystem s(p);
  for (float r : s.density()) EXPECT_NEAR(r, p.rest_density_kgpm3, 1e-3f * p.rest_density_kgpm3);
}

TEST(SphBoundary, ClosedBoxDoesNotPumpEnergy) {
  // a 1 % compressed block in a closed box: total energy must not grow (the mirrored-pressure wall
  // force and too little viscosity both made it grow to 10 m/s)
  SphParams p;
  p.spacing_m = 0.005f;
  p.container_m = {0.04f, 0.04f, 0.04f};
  p.gravity_mps2 = {0, 0, 0};
  p.fluid.push_back({{0, 0, 0}, p.container_m});
  SphSystem s(p);
  std::vector<float> X(s.x().begin(), s.x().end()), Y(s.y().begin(), s.y().end()), Z(s.z().begin(), s.z().end());
  for (std::size_t i = 0; i < X.size(); ++i) {
    X[i] = 0.02f + (X[i] - 0.02f) * 0.99f;
    Y[i] = 0.02f + (Y[i] - 0.02f) * 0.99f;
  }
  s.set_particles(X, Y, Z);
  auto energy = [&]() {
    double e = 0;
    const double B = p.rest_density_kgpm3 * s.sound_speed() * s.sound_speed() / 7.0;
    for (std::size_t i = 0; i < s.count(); ++i) {
      e += 0.5 * (s.vx()[i] * s.vx()[i] + s.vy()[i] * s.vy()[i] + s.vz()[i] * s.vz()[i]);
      const double r = s.density()[i] / p.rest_density_kgpm3;
      if (r > 1) e += B / p.rest_density_kgpm3 * (std::pow(r, 6) / 6 + 1 / r - 7.0 / 6);
    }
    return e;
  };
  const double e0 = energy();
  ASSERT_GT(e0, 0);
  for (int k = 0; k < 800; ++k) s.step();
  EXPECT_LT(energy(), e0);
  EXPECT_LT(s.max_speed(), 0.5f);
}
