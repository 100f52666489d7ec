// Tests of the plan and particle views (viz/passes/plan_pass.hpp, plot.hpp): pixels are the colour
// map of the values, ships and dry land, the colour bar's labels, the particles.
#include <gtest/gtest.h>

#include "render_test_helpers.hpp"

using namespace huygens;
using namespace huygens::test;

// The plan view shows exact values (docs/viz.md "Plan view"): with no lighting, the pixel at
// the centre of every grid cell's square is the colour map at that point's value on the
// colour bar's range (to 8-bit rounding), the range is symmetric about 0 for heights and holds
// the extremes.
TEST_F(VizRender, PlanViewPixelsAreTheColourMapOfTheValues) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  std::vector<float> v(kN * kN);
  for (std::size_t i = 0; i < kN; ++i)
    for (std::size_t j = 0; j < kN; ++j)
      v[i * kN + j] = static_cast<float>(0.003 * std::sin(0.05 * j) + 0.002 * std::cos(0.07 * i));  // m
  RenderTarget target(640, 360);
  r.render_plan(v, "height", 1000.0, "mm", true, "test", target);
  const gl::Image8 img = target.read();
  const PlanPlot& p = r.plan;
  EXPECT_DOUBLE_EQ(p.lo, -p.hi);
  double max_abs = 0;
  for (float x : v) max_abs = std::max(max_abs, 1000.0 * std::abs(x));
  EXPECT_GE(p.hi, max_abs) << "the colour bar holds the extremes";
  double worst = 0;
  int checked = 0;
  for (std::size_t i = 0; i < kN; i += 7)
    for (std::size_t j = 0; j < kN; j += 5) {
      const int x = static_cast<int>(p.x0 + (j + 0.5) * p.width / kN);
      const int y = static_cast<int>(p.y0 + p.height - (i + 0.5) * p.height / kN);
      const glm::vec3 c = plan_colour((1000.0 * v[i * kN + j] - p.lo) / (p.hi - p.lo), true);
      for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::abs(channel(img, x, y, ch) - c[ch]));
      ++checked;
    }
  std::printf("plan view: %d grid points, worst colour difference %.4f (1/255 = %.4f)\n", checked, worst, 1 / 255.0);
  EXPECT_LE(worst, 0.5 / 255.0 + 1e-6);
  if (worst > 0.5 / 255.0 + 1e-6) write_debug("plan_view.png", img);
  // NaN (dry land over terrain) is drawn sand, the rest as before
  for (std::size_t i = 0; i < kN; ++i)
    for (std::size_t j = 0; j < kN / 4; ++j) v[i * kN + j] = std::numeric_limits<float>::quiet_NaN();
  r.render_plan(v, "depth", 1000.0, "mm", false, "test", target);
  const gl::Image8 dry = target.read();
  EXPECT_GE(r.plan.hi, max_abs) << "the finite values still set the range";
  const int xd = static_cast<int>(r.plan.x0 + 0.1 * r.plan.width),
            yd = static_cast<int>(r.plan.y0 + 0.5 * r.plan.height);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(channel(dry, xd, yd, ch), kPlanDryLand[ch], 0.5 / 255.0 + 1e-6);
}

// The plan view draws the ships where the frames put them (WaterRenderer::set_ships), their
// waterline (Wigley: half-width B/2 (1 - (2 x / L)^2)) grey like the obstacles, and leaves the
// hull's own dent out of the colour range (as an obstacle's cells): kelvin.json's and ocean.json's
// plans showed the wake with no ship. A 1 m x 0.3 m hull at 30 degrees over a 5 cm dent in 2 mm
// waves.
TEST_F(VizRender, PlanViewDrawsTheShipsAndLeavesTheirDentOutOfTheRange) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  ShipPose ship;
  ship.x = 3.0, ship.y = 3.0, ship.heading = std::numbers::pi / 6.0, ship.length = 1.0, ship.beam = 0.3;
  std::vector<float> v(kN * kN);
  for (std::size_t i = 0; i < kN; ++i)
    for (std::size_t j = 0; j < kN; ++j) {
      const double dx = g.x(j) - ship.x, dy = g.y(i) - ship.y;
      v[i * kN + j] = static_cast<float>(0.002 * std::sin(3.0 * g.x(j)) - 0.05 * std::exp(-(dx * dx + dy * dy) / 0.02));
    }
  r.set_ships(std::span(&ship, 1));
  RenderTarget target(640, 360);
  r.render_plan(v, "height", 1000.0, "mm", true, "ship", target);
  const gl::Image8 img = target.read();
  const PlanPlot& p = r.plan;
  auto at = [&](double x, double y, int ch) {
    return channel(img, static_cast<int>(p.x0 + (x - g.x0 + 0.5 * g.dx) / (kN * g.dx) * p.width),
                   static_cast<int>(p.y0 + p.height - (y - g.y0 + 0.5 * g.dx) / (kN * g.dx) * p.height), ch);
  };
  const double c = std::cos(ship.heading), sn = std::sin(ship.heading);
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(at(ship.x, ship.y, ch), 0.55, 0.5 / 255.0 + 1e-6) << "the hull's middle, channel " << ch;
    EXPECT_NEAR(at(ship.x + 0.35 * c, ship.y + 0.35 * sn, ch), 0.55, 0.5 / 255.0 + 1e-6)
        << "along the hull, channel " << ch;
    EXPECT_GT(std::abs(at(ship.x - 0.3 * sn, ship.y + 0.3 * c, ch) - 0.55), 0.02) << "beside the hull, channel " << ch;
  }
  EXPECT_LT(p.hi, 30.0) << "the dent under the hull (50 mm) sets no range";
  if (::testing::Test::HasFailure()) write_debug("plan_ship.png", img);
}

// Over terrain, the flow's plan views leave dry land out as the depth view does (sand): a thin
// film's speed is noise (flood.json at t = 12 s: 10-12 m/s speckles beyond its front) and dry
// land carries no dye or foam (the dye's bands ran on over the dry land). Left half wet (0.5 m
// at 1 m/s), right half dry (0.5 mm, "moving" at 5 m/s), dye and foam 1 everywhere.
TEST_F(VizRender, FlowPlanViewsLeaveDryLandOutOverTerrain) {
  SceneView view;
  view.grid.rows = 8, view.grid.cols = 16, view.grid.dx = 1.0, view.grid.x0 = view.grid.y0 = 0.5;
  view.plan_depth = true;
  const std::size_t R = 8, C = 16;
  view.bed.resize(R * C);
  std::vector<float> field(R * C), velocity(2 * R * C, 0.0f), ones(R * C, 1.0f);
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t j = 0; j < C; ++j) {
      const std::size_t k = i * C + j;
      const bool wet = j < C / 2;
      view.bed[k] = static_cast<float>(0.1 * j);  // a slope up to the right
      field[k] = view.bed[k] + (wet ? 0.5f : 0.0005f);
      velocity[2 * k] = wet ? 1.0f : 5.0f;
    }
  WaterRenderer r(view.grid, 0.0, 4);
  RenderTarget target(640, 360);
  auto pixel = [&](const gl::Image8& img, std::size_t i, std::size_t j, int ch) {
    return channel(img, static_cast<int>(r.plan.x0 + (j + 0.5) * r.plan.width / C),
                   static_cast<int>(r.plan.y0 + r.plan.height - (i + 0.5) * r.plan.height / R), ch);
  };
  const PlanData data{field, velocity, ones, ones, {}};
  for (PlanQuantity q : {PlanQuantity::speed, PlanQuantity::dye, PlanQuantity::foam}) {
    render_plan_view(r, view, data, q, 12.0, "terrain", target);
    const gl::Image8 img = target.read();
    const double wet = q == PlanQuantity::speed ? 100.0 : 1.0;  // 1 m/s in cm/s; dye and foam 1
    const double wet_t = (wet - r.plan.lo) / (r.plan.hi - r.plan.lo);
    // the dye from white to the colour the perspective view tints the water with (the same dye
    // reads the same in both views), speed and foam on viridis
    const glm::vec3 want = q == PlanQuantity::dye
                               ? glm::mix(glm::vec3(1.0f), RenderSettings{}.dye_colour, static_cast<float>(wet_t))
                               : plan_colour(wet_t, false);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(pixel(img, 4, 12, ch), kPlanDryLand[ch], 0.5 / 255.0 + 1e-6)
          << "dry land, quantity " << static_cast<int>(q) << " channel " << ch;
      EXPECT_NEAR(pixel(img, 4, 3, ch), want[ch], 0.5 / 255.0 + 1e-6)
          << "water, quantity " << static_cast<int>(q) << " channel " << ch;
    }
    if (q == PlanQuantity::speed) {
      EXPECT_LT(r.plan.hi, 500.0) << "the dry film's 5 m/s sets no range (cm/s)";
    }
    if (::testing::Test::HasFailure()) write_debug("terrain_flow_plan.png", img);
  }
}

// The colour bar beside a plan too short for its labels (sph_dam_break's 4 x 128 slab, 1:32, a
// plot 32 px high at 1280x720): its tick labels (glyphs 7 text units high) are spaced at least
// 9 units apart (before: the bar was the plot's height, 6.4 px between labels, which overlapped
// into one smear), the bar is drawn where its layout says, inside the image; a square plot's bar
// is the plot's height, as before.
TEST_F(VizRender, ColourBarOfAShortPlanKeepsItsTickLabelsApart) {
  GridPlacement g;
  g.rows = 4, g.cols = 128, g.dx = 0.457 / 128, g.x0 = g.y0 = 0.5 * g.dx;
  WaterRenderer r(g, 0.0, 4);
  std::vector<float> v(g.rows * g.cols);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = static_cast<float>(0.025 * (k % g.cols) / (g.cols - 1.0));  // m
  const int W = 1280, H = 720;
  const double s = std::round(H / 300.0);  // the plot's text scale
  RenderTarget target(W, H);
  r.render_plan(v, "depth", 100.0, "cm", false, "strip", target);
  const gl::Image8 img = target.read();
  PlotSpec spec;
  plot_range(0.0, 100.0 * v.back(), false, spec);  // render_plan's range of these values: 0 to 3 cm by 0.5
  ASSERT_DOUBLE_EQ(r.plan.lo, spec.lo);
  ASSERT_DOUBLE_EQ(r.plan.hi, spec.hi);
  const ColourBar b = colour_bar_layout(r.plan, spec, H);
  const double pitch = b.height / ((spec.hi - spec.lo) / spec.step);
  std::printf("strip plan: plot %.1f px high, colour bar %.1f px, %.1f px between tick labels (text scale %.0f)\n",
              r.plan.height, b.height, pitch, s);
  EXPECT_LT(r.plan.height, 40.0) << "the case: a plot too short for the labels";
  EXPECT_GE(pitch, 9.0 * s) << "tick labels overlap";
  EXPECT_GE(b.y, 0.0);
  EXPECT_LE(b.y + b.height, H);
  // the bar's pixels are the map where the layout puts them: the top row near 1, the bottom near 0
  const int xb = static_cast<int>(b.x + 0.5 * b.width);
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(channel(img, xb, static_cast<int>(b.y + 1), ch), plan_colour(1.0, false)[ch], 0.03) << ch;
    EXPECT_NEAR(channel(img, xb, static_cast<int>(b.y + b.height - 2), ch), plan_colour(0.0, false)[ch], 0.03) << ch;
  }
  if (::testing::Test::HasFailure()) write_debug("strip_plan.png", img);
  // a square plot: the bar beside it, as tall as the plot
  WaterRenderer sq(test_grid(), -kDepth, 4);
  std::vector<float> w(kN * kN, 0.0f);
  w[0] = 0.01f;
  sq.render_plan(w, "height", 1000.0, "mm", true, "square", target);
  PlotSpec sq_spec;
  plot_range(-10.0, 10.0, true, sq_spec);
  const ColourBar bs = colour_bar_layout(sq.plan, sq_spec, H);
  EXPECT_DOUBLE_EQ(bs.y, sq.plan.y0);
  EXPECT_DOUBLE_EQ(bs.height, sq.plan.height);
}

// The particle view (plot.hpp, render_particles): particles seen from the side (-y) as discs
// coloured by speed on the colour bar's range, the nearer particle over the farther one (and the
// farther shaded darker), an obstacle as a grey silhouette between them; the plot keeps the
// container's aspect. Synthetic particles: their pixels are known exactly.
TEST_F(VizRender, ParticleViewDrawsSpeedsNearestFirstAndObstacles) {
  const std::array<double, 3> box{2.0, 1.0, 1.0};
  // x, y, z, speed: slow near the left; fast at the right; at x = 1, a far particle and a near
  // one at the same spot; a particle behind the obstacle at x = 1.5
  const std::vector<float> parts{0.25f, 0.0f, 0.5f, 0.0f, 1.75f, 0.0f, 0.5f, 3.0f, 1.0f, 0.9f,
                                 0.5f,  3.0f, 1.0f, 0.1f, 0.5f,  0.0f, 1.5f, 0.9f, 0.5f, 3.0f};
  RenderObstacle box_obstacle;
  box_obstacle.kind = RenderObstacle::Kind::box;
  box_obstacle.min_m = {1.4, 0.5, 0.0};
  box_obstacle.max_m = {1.6, 0.6, 0.8};
  RenderTarget target(640, 360);
  const PlanPlot p = render_particles(parts, box, 0.05, std::span(&box_obstacle, 1), "test", 0.0, target);
  const gl::Image8 img = target.read();
  EXPECT_NEAR(p.width / p.height, 2.0, 0.02) << "the container's aspect";
  EXPECT_EQ(p.lo, 0.0);
  EXPECT_DOUBLE_EQ(p.hi, 3.0) << "the fastest, 3 m/s, ends the bar (in m/s: cm/s only below 2 m/s)";
  auto at = [&](double x, double z, int ch) {
    return channel(img, static_cast<int>(p.x0 + x / box[0] * p.width),
                   static_cast<int>(p.y0 + p.height - z / box[2] * p.height), ch);
  };
  auto expect_colour = [&](double x, double z, glm::vec3 c, const char* what) {
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(at(x, z, ch), c[ch], 1.0 / 255.0 + 1e-6) << what << " channel " << ch;
  };
  const glm::vec3 fast = plan_colour(1.0, false), slow = plan_colour(0.0, false);
  expect_colour(0.25, 0.5, slow, "the resting particle, nearest (y = 0): unshaded");
  expect_colour(1.75, 0.5, fast, "the fast particle");
  expect_colour(1.0, 0.5, slow * static_cast<float>(1.0 - 0.45 * 0.1), "the nearer particle covers the farther");
  expect_colour(1.5, 0.5, glm::vec3(0.55f), "the obstacle covers the particle behind it");
  expect_colour(0.6, 0.2, glm::vec3(236, 240, 244) / 255.0f, "the tank where no particle is");
  if (::testing::Test::HasFailure()) write_debug("particle_view.png", img);
  // a mesh obstacle: its triangles, lit, not its bounding box (a face toward the viewer, -y)
  RenderObstacle tri;
  tri.kind = RenderObstacle::Kind::mesh;
  tri.min_m = {0.9, 0.05, 0.0};
  tri.max_m = {1.3, 0.05, 0.3};
  tri.triangles_m = {0.9f, 0.05f, 0.0f, 1.3f, 0.05f, 0.0f, 1.1f, 0.05f, 0.3f};
  render_particles(parts, box, 0.05, std::span(&tri, 1), "test", 0.0, target);
  const gl::Image8 mesh_img = target.read();
  const double lit = 0.35 + 0.65 / std::sqrt(0.3 * 0.3 + 1.0 + 0.8 * 0.8);  // n = -y, light (-0.3, -1, 0.8)
  for (int ch = 0; ch < 3; ++ch) {
    const double c = glm::vec3(0.62f, 0.60f, 0.57f)[ch] * lit;
    EXPECT_NEAR(channel(mesh_img, static_cast<int>(p.x0 + 1.1 / box[0] * p.width),
                        static_cast<int>(p.y0 + p.height - 0.1 / box[2] * p.height), ch),
                c, 1.0 / 255.0 + 1e-6)
        << "inside the triangle, lit, channel " << ch;
    EXPECT_NEAR(channel(mesh_img, static_cast<int>(p.x0 + 0.95 / box[0] * p.width),
                        static_cast<int>(p.y0 + p.height - 0.25 / box[2] * p.height), ch),
                glm::vec3(236, 240, 244)[ch] / 255.0, 1e-6)
        << "the bounding box's corner outside the triangle, channel " << ch;
  }
  if (::testing::Test::HasFailure()) write_debug("particle_view_mesh.png", mesh_img);
}
