// SphMeshTree (huygens/sph/mesh_tree.hpp) gives the answers of the brute-force sums over every
// triangle: the inside test (winding number above 1/2) and the nearer-than test, on a torus (not
// convex, a hole through it) in both orientations, at points spread through its box and at points
// a hair off its surface; and the inside test agrees with the analytic torus away from its surface.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "huygens/sph/boundary.hpp"
#include "huygens/sph/mesh_tree.hpp"

using namespace huygens;

namespace {

using V3 = std::array<float, 3>;
constexpr double kR = 0.05, kr = 0.02;  // the torus' radii (m)

V3 torus_point(double u, double v, double dr) {
  const double rr = kr + dr;
  return {static_cast<float>((kR + rr * std::cos(v)) * std::cos(u)),
          static_cast<float>((kR + rr * std::cos(v)) * std::sin(u)), static_cast<float>(rr * std::sin(v))};
}

// nu x nv quads around the torus, two triangles each, counter-clockwise seen from outside
SphMesh torus(int nu, int nv, bool flip) {
  SphMesh m;
  const double tau = 2 * std::numbers::pi;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) m.vertices.push_back(torus_point(tau * i / nu, tau * j / nv, 0));
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const int a = i * nv + j, b = ((i + 1) % nu) * nv + j, c = ((i + 1) % nu) * nv + (j + 1) % nv,
                d = i * nv + (j + 1) % nv;
      m.triangles.push_back(flip ? std::array<int, 3>{a, c, b} : std::array<int, 3>{a, b, c});
      m.triangles.push_back(flip ? std::array<int, 3>{a, d, c} : std::array<int, 3>{a, c, d});
    }
  return m;
}

// distance from p to the torus' core circle (m)
double core_distance(const V3& p) {
  const double rho = std::hypot(p[0], p[1]);
  return std::hypot(rho - kR, p[2]);
}

}  // namespace

TEST(SphMeshTree, InsideAgreesWithTheSumOverEveryTriangle) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> box(-0.08, 0.08), angle(0, 2 * std::numbers::pi), hair(-2e-4, 2e-4);
  for (bool flip : {false, true}) {
    const SphMesh m = torus(64, 32, flip);
    const SphMeshTree tree(m, m.triangles);
    int inside = 0, near = 0;
    for (int i = 0; i < 4000; ++i) {
      const V3 p{static_cast<float>(box(rng)), static_cast<float>(box(rng)), static_cast<float>(0.4 * box(rng))};
      const bool in = tree.inside(p);
      ASSERT_EQ(in, sph_mesh_inside(m, p)) << "at " << p[0] << " " << p[1] << " " << p[2];
      inside += in;
      const double d = core_distance(p);  // the facets lie within 1.3e-4 m inside the round torus
      if (d < kr - 1e-3) {
        EXPECT_TRUE(in) << "core distance " << d;
      }
      if (d > kr + 1e-3) {
        EXPECT_FALSE(in) << "core distance " << d;
      }
    }
    for (int i = 0; i < 4000; ++i) {  // a hair off the surface, where the near triangles decide
      const V3 p = torus_point(angle(rng), angle(rng), hair(rng));
      const bool in = tree.inside(p);
      ASSERT_EQ(in, sph_mesh_inside(m, p)) << "at " << p[0] << " " << p[1] << " " << p[2];
      near += in;
    }
    int band = 0;
    for (const auto& t : m.triangles) {  // on an edge (winding number about 1/2): the undecided band, summed exactly
      const auto &a = m.vertices[t[0]], &c = m.vertices[t[2]];
      const V3 p{(a[0] + c[0]) / 2, (a[1] + c[1]) / 2, (a[2] + c[2]) / 2};
      const bool in = tree.inside(p);
      ASSERT_EQ(in, sph_mesh_inside(m, p)) << "on an edge at " << p[0] << " " << p[1] << " " << p[2];
      band += in;
    }
    EXPECT_GT(band, 0);  // measured 1678 and 1754 of 4096: both answers occur
    EXPECT_LT(band, static_cast<int>(m.triangles.size()));
    EXPECT_GT(inside, 200);  // both answers occur
    EXPECT_LT(inside, 3800);
    EXPECT_GT(near, 400);
    EXPECT_LT(near, 3600);
  }
}

TEST(SphMeshTree, NearerThanAgreesWithTheSmallestDistanceOfAnyTriangle) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> box(-0.09, 0.09), radius(0.0, 0.03);
  SphMesh m = torus(48, 24, false);
  std::vector<std::array<int, 3>> half;  // a subset, as the faces not buried in a wall
  for (const auto& t : m.triangles)
    if (m.vertices[t[0]][2] + m.vertices[t[1]][2] + m.vertices[t[2]][2] > 0) half.push_back(t);
  const SphMesh upper{m.vertices, half};
  for (const SphMesh* mesh : std::array<const SphMesh*, 2>{&m, &upper}) {
    const SphMeshTree tree(*mesh, mesh->triangles);
    int yes = 0;
    for (int i = 0; i < 4000; ++i) {
      const V3 p{static_cast<float>(box(rng)), static_cast<float>(box(rng)), static_cast<float>(0.5 * box(rng))};
      const float r = static_cast<float>(radius(rng)), d2 = sph_mesh_dist2(*mesh, p);
      ASSERT_EQ(tree.nearer_than(p, r * r), d2 < r * r) << "distance " << std::sqrt(d2) << " against " << r;
      ASSERT_FALSE(tree.nearer_than(p, d2)) << "the nearest triangle itself is not nearer than its distance";
      yes += d2 < r * r;
    }
    EXPECT_GT(yes, 400);
    EXPECT_LT(yes, 3600);
  }
}

TEST(SphMeshTree, AnEmptyTreeHoldsNothing) {
  const SphMesh m = torus(8, 4, false);
  const SphMeshTree tree(m, {});
  EXPECT_FALSE(tree.inside({0.05f, 0.f, 0.f}));
  EXPECT_FALSE(tree.nearer_than({0.05f, 0.f, 0.f}, 1.f));
}
