// Tests of the solids pass and its geometry (viz/passes/solids_pass.hpp, solid_geometry.hpp,
// footprints.hpp): a hull at its pose, a mesh obstacle lit face by face and the surface beside it,
// a hull afloat on the waves.
#include <gtest/gtest.h>

#include "render_test_helpers.hpp"

using namespace huygens;
using namespace huygens::test;

// The ship hull is drawn at its position and heading: seen from straight above, the point
// 0.4 m ahead of the centre along the heading is hull, the point 0.4 m abeam is water.
TEST_F(VizRender, ShipHullAtItsPositionAndHeading) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  r.set_heights(std::vector<float>(kN * kN, 0.0f));
  const OrbitCamera cam = top_down(g.x0 + 2.0, g.y0 + 2.0, 2.0);
  RenderSettings s = plain_settings();
  s.draw_ship = true;
  s.ground = GroundPattern::uniform;
  const int W = 128, H = 128;
  const double m_per_px = cam.ortho_height / H;
  // pixel of world point (x, y): columns along +x, rows top-down along -y
  auto px = [&](double x, double y, int& i, int& j) {
    j = static_cast<int>(std::floor((x - cam.target.x) / m_per_px + 0.5 * W));
    i = static_cast<int>(std::floor(0.5 * H - (y - cam.target.y) / m_per_px));
  };
  const gl::Image8 none = render(r, cam, s, W, H);
  for (double heading : {0.0, 1.5707963267948966}) {
    ShipPose ship;
    ship.x = cam.target.x, ship.y = cam.target.y, ship.heading = heading;
    ship.length = 1.0, ship.beam = 0.3;
    r.set_ships(std::span<const ShipPose>(&ship, 1));
    const gl::Image8 img = render(r, cam, s, W, H);
    r.set_ships({});
    auto differs = [&](double x, double y) {
      int i, j;
      px(x, y, i, j);
      double d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(channel(img, j, i, c) - channel(none, j, i, c)));
      return d > 0.05;
    };
    const double c = std::cos(heading), sn = std::sin(heading);
    EXPECT_TRUE(differs(ship.x + 0.4 * c, ship.y + 0.4 * sn)) << "ahead, heading " << heading;
    EXPECT_TRUE(differs(ship.x - 0.4 * c, ship.y - 0.4 * sn)) << "astern, heading " << heading;
    EXPECT_FALSE(differs(ship.x - 0.4 * sn, ship.y + 0.4 * c)) << "abeam, heading " << heading;
    EXPECT_FALSE(differs(ship.x + 0.7 * c, ship.y + 0.7 * sn)) << "beyond the bow, heading " << heading;
  }
}

// A mesh obstacle (RenderObstacle::Kind::mesh, an SPH scene's OBJ) is drawn as its triangles,
// not as its bounding box: seen from straight above, a tetrahedron standing out of shallow water
// covers its triangular footprint and leaves the corner of its bounding box outside the
// triangle as it was; its faces are lit (two faces turned differently differ in shade).
TEST_F(VizRender, MeshObstacleIsDrawnAsItsTrianglesLit) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  // 10 cm of water: a solid under the surface is not seen through it (the refraction shows the floor)
  r.set_heights(std::vector<float>(kN * kN, static_cast<float>(0.1 - kDepth)));
  const OrbitCamera cam = top_down(g.x0 + 2.0, g.y0 + 2.0, 4.0);
  RenderSettings s = plain_settings();
  s.ground = GroundPattern::uniform;
  s.sun_dir = glm::vec3(0.3f, 0.5f, 0.8f);
  const int W = 128, H = 128;
  const double m_per_px = cam.ortho_height / H;
  auto pixel = [&](const gl::Image8& img, double x, double y, int c) {
    const int j = static_cast<int>(std::floor((x - cam.target.x) / m_per_px + 0.5 * W));
    const int i = static_cast<int>(std::floor(0.5 * H - (y - cam.target.y) / m_per_px));
    return channel(img, j, i, c);
  };
  auto differ = [&](const gl::Image8& a, const gl::Image8& b, double x, double y) {
    double d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(pixel(a, x, y, c) - pixel(b, x, y, c)));
    return d;
  };
  const gl::Image8 none = render(r, cam, s, W, H);
  // base triangle (cx - 1, cy - 1), (cx + 1, cy - 1), (cx, cy + 1) on the floor, apex above the water
  const float cx = static_cast<float>(cam.target.x), cy = static_cast<float>(cam.target.y), fz = -kDepth;
  const std::array<float, 3> A{cx - 1, cy - 1, fz}, B{cx + 1, cy - 1, fz}, C{cx, cy + 1, fz}, D{cx, cy - 0.4f, 1.0f};
  RenderObstacle tet;
  tet.kind = RenderObstacle::Kind::mesh;
  tet.min_m = {cx - 1.0, cy - 1.0, fz};
  tet.max_m = {cx + 1.0, cy + 1.0, 1.0};
  for (const auto& t : {std::array{A, C, B}, std::array{A, B, D}, std::array{B, C, D}, std::array{C, A, D}})
    for (const auto& v : t) tet.triangles_m.insert(tet.triangles_m.end(), v.begin(), v.end());
  r.set_obstacles(std::span(&tet, 1));
  const gl::Image8 img = render(r, cam, s, W, H);
  EXPECT_GT(differ(img, none, cx, cy - 0.7), 0.05) << "the face toward -y";
  EXPECT_GT(differ(img, none, cx + 0.3, cy + 0.2), 0.05) << "the face toward +x, +y";
  EXPECT_LT(differ(img, none, cx - 0.85, cy + 0.85), 1e-6) << "the bounding box's corner, outside the triangle";
  EXPECT_LT(differ(img, none, cx + 1.3, cy), 1e-6) << "beyond the footprint";
  auto luminance = [&](double x, double y) {
    return (pixel(img, x, y, 0) + pixel(img, x, y, 1) + pixel(img, x, y, 2)) / 3;
  };
  EXPECT_GT(std::abs(luminance(cx, cy - 0.7) - luminance(cx + 0.3, cy + 0.2)), 0.02)
      << "two faces turned differently are shaded differently";
  if (::testing::Test::HasFailure()) write_debug("mesh_obstacle.png", img);

  // On a dry floor (the SPH look leaves water thinner than 2 mm out) the surface next to the solid
  // is not raised to its top: outside the footprint the picture is the bare floor's. A steep
  // tetrahedron whose base edge y = e runs half a grid cell from the grid points, seen from
  // 12.5 cm (32 px per cell), absorption on (water shows, tinted). Until 2026-12-04 the first
  // point inside took the solid's top and a ring of water sloped down from it to the first point
  // outside, half a cell beyond the edge (1920 pixels here).
  s.hide_dry = true;
  s.absorption = true;
  const float e = static_cast<float>(cy - 1.0 + 0.5 * g.dx);
  RenderObstacle steep = tet;
  steep.triangles_m.clear();
  const std::array<float, 3> A2{cx - 1, e, fz}, B2{cx + 1, e, fz}, D2{cx, e + 0.1f, 1.0f};
  for (const auto& t : {std::array{A2, C, B2}, std::array{A2, B2, D2}, std::array{B2, C, D2}, std::array{C, A2, D2}})
    for (const auto& v : t) steep.triangles_m.insert(steep.triangles_m.end(), v.begin(), v.end());
  const std::vector<float> dry_heights(kN * kN, static_cast<float>(-kDepth));
  const OrbitCamera edge = top_down(cx, e, 0.125);
  WaterRenderer fine(g, -kDepth, 1);  // a mesh vertex at every grid point, as an SPH surface has
  fine.set_heights(dry_heights);
  const gl::Image8 bare = render(fine, edge, s, W, H);
  fine.set_obstacles(std::span(&steep, 1));
  fine.set_heights(dry_heights);
  const gl::Image8 dry = render(fine, edge, s, W, H);
  int outside = 0, wet = 0;
  for (int i = 0; i < H; ++i)
    for (int j = 0; j < W; ++j) {
      const double y = edge.target.y + (0.5 * H - i - 0.5) * edge.ortho_height / H;  // pixel centre (m)
      if (y > e - 1.5 * edge.ortho_height / H) continue;                             // the footprint and its edge pixel
      ++outside;
      double d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(channel(dry, j, i, c) - channel(bare, j, i, c)));
      wet += d > 1.5 / 255.0;
    }
  EXPECT_GT(outside, W * H / 3);
  EXPECT_EQ(wet, 0) << "pixels beside a solid on a dry floor that differ from the bare floor";
  if (::testing::Test::HasFailure()) write_debug("mesh_obstacle_dry.png", dry);
}

// A hull afloat (float_ship): on a tilted plane eta = 0.1 + 0.02 x - 0.01 y it takes the plane's
// height at its centre and its slopes along and across its heading (30 deg); on waves a quarter
// of its length long it stays nearly level (heave and slopes under 5 % of the waves' amplitude and
// slope); on a plane steeper than 0.3 its slope is held at 0.3; with its rings off the grid it is
// level at 0.
TEST(VizLook, HullFloatsOnThePlaneOfTheWavesLongerThanItself) {
  GridPlacement g;
  g.rows = g.cols = 201;
  g.dx = 0.1;
  const double xs = 10.3, ys = 9.7, h = std::numbers::pi / 6;
  const auto field = [&](auto f) {
    std::vector<float> eta(g.rows * g.cols);
    for (std::size_t i = 0; i < g.rows; ++i)
      for (std::size_t j = 0; j < g.cols; ++j) eta[i * g.cols + j] = static_cast<float>(f(g.x(j), g.y(i)));
    return eta;
  };
  ShipPose s;
  s.x = xs, s.y = ys, s.heading = h, s.length = 4.0, s.beam = 1.0;
  float_ship(g, field([](double x, double y) { return 0.1 + 0.02 * x - 0.01 * y; }), s);
  EXPECT_NEAR(s.heave, 0.1 + 0.02 * xs - 0.01 * ys, 1e-6);
  EXPECT_NEAR(s.slope_along, 0.02 * std::cos(h) - 0.01 * std::sin(h), 1e-6);
  EXPECT_NEAR(s.slope_across, -0.02 * std::sin(h) - 0.01 * std::cos(h), 1e-6);
  const double k = 2 * std::numbers::pi / 1.0, a = 0.05;  // 1 m waves under a 4 m hull
  float_ship(g, field([&](double x, double y) { return a * std::cos(k * (0.8 * x + 0.6 * y)); }), s);
  EXPECT_LT(std::abs(s.heave), 0.05 * a);
  EXPECT_LT(std::hypot(s.slope_along, s.slope_across), 0.05 * k * a);
  float_ship(g, field([](double x, double) { return 0.5 * x; }), s);
  EXPECT_DOUBLE_EQ(s.slope_along, 0.3) << "0.5 cos 30 deg = 0.433, held at 0.3";
  EXPECT_NEAR(s.slope_across, -0.5 * std::sin(h), 1e-6) << "-0.25: within the bound";
  s.x = -100.0;
  float_ship(g, field([](double, double) { return 1.0; }), s);
  EXPECT_EQ(s.heave, 0.0);
  EXPECT_EQ(s.slope_along, 0.0);
}

// The surface closes around solids (footprints.hpp): a box's grid points show the height of the
// nearest point outside (breadth-first over the 4-neighbourhood), a mesh's points are kept at least
// at its top less dx/4 where the water beside it is higher, and left alone where the water beside
// it is lower (a solid on a dry floor); the plan view greys the box and the mesh's outline.
TEST(VizSolids, FootprintsCloseTheSurfaceAroundSolids) {
  GridPlacement g;
  g.rows = g.cols = 9, g.dx = 1.0, g.x0 = g.y0 = 0.0;
  RenderObstacle box;
  box.kind = RenderObstacle::Kind::box;
  box.min_m = {2.5, 2.5, 0.0}, box.max_m = {4.5, 4.5, 1.0};  // grid points 3-4 in x and y
  Footprints fp;
  fp.build(g, std::span(&box, 1), 0.0f);
  std::vector<float> eta(81);
  for (std::size_t k = 0; k < eta.size(); ++k) eta[k] = static_cast<float>(k);
  const std::vector<float> before = eta;
  fp.apply(eta, g.dx);
  for (std::size_t i = 0; i < 9; ++i)
    for (std::size_t j = 0; j < 9; ++j) {
      const std::size_t k = i * 9 + j;
      const bool in = i >= 3 && i <= 4 && j >= 3 && j <= 4;
      EXPECT_EQ(fp.solid(k), in) << i << "," << j;
      if (!in) {
        EXPECT_EQ(eta[k], before[k]);
      }
    }
  // the search starts from every outside point in row-major order, so (3, 3) and (3, 4) take the
  // points above them, (4, 3) its left neighbour, (4, 4) its right one
  EXPECT_EQ(eta[30], before[21]);
  EXPECT_EQ(eta[31], before[22]);
  EXPECT_EQ(eta[39], before[38]);
  EXPECT_EQ(eta[40], before[41]);
  // a flat mesh square at z = 0.5 over points 2-6: the water at -1 beside it stays (dry floor), at 2
  // it is kept at 0.5 - 0.25 over the footprint
  RenderObstacle mesh;
  mesh.kind = RenderObstacle::Kind::mesh;
  mesh.triangles_m = {1.5f, 1.5f, 0.5f, 6.5f, 1.5f, 0.5f, 6.5f, 6.5f, 0.5f,
                      1.5f, 1.5f, 0.5f, 6.5f, 6.5f, 0.5f, 1.5f, 6.5f, 0.5f};
  fp.build(g, std::span(&mesh, 1), 0.0f);
  std::vector<float> low(81, -1.0f), high(81, 2.0f);
  for (std::size_t k = 0; k < 81; ++k) high[k] = (k / 9 >= 2 && k / 9 <= 6 && k % 9 >= 2 && k % 9 <= 6) ? -1.0f : 2.0f;
  fp.apply(low, g.dx);
  fp.apply(high, g.dx);
  EXPECT_EQ(low[40], -1.0f) << "a solid on a dry floor keeps its footprint's own height";
  EXPECT_EQ(high[40], 0.25f) << "water beside it is higher: the surface runs over its top less dx/4";
  EXPECT_TRUE(fp.solid(2 * 9 + 2) && fp.solid(2 * 9 + 4) && !fp.solid(40)) << "the outline, not the inside";
}

// The tank's walls (solid_geometry.hpp): of the four side walls, those the eye is outside of are
// left out (the wall between the eye and the water), each a quad from the floor to the lid.
TEST(VizSolids, TankWallsLeaveOutTheWallsBetweenTheEyeAndTheWater) {
  SolidsFrame f;
  f.ground_z = -0.3, f.offset = 0.3;
  const std::array<double, 3> box{2.0, 1.0, 0.5};
  EXPECT_EQ(tank_walls(box, f, glm::dvec3(1.0, 0.5, 3.0)).size(), 4u * 18u) << "above: all four";
  const std::vector<float> from_south = tank_walls(box, f, glm::dvec3(1.0, -5.0, 0.2));
  ASSERT_EQ(from_south.size(), 3u * 18u) << "from the south the south wall is left out";
  for (std::size_t v = 0; v < from_south.size(); v += 3) {
    EXPECT_TRUE(from_south[v + 2] == -0.3f || std::abs(from_south[v + 2] - 0.2f) < 1e-6f) << "floor to the lid";
    EXPECT_FALSE(from_south[v + 1] == 0.0f && from_south[v] > 0.0f && from_south[v] < 2.0f)
        << "no vertex on y = 0 but corners";
  }
  EXPECT_TRUE(tank_walls({0.0, 0.0, 0.0}, f, glm::dvec3(0.0)).empty()) << "no tank";
}
