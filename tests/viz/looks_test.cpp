// Tests of the looks and the start-up camera (viz/app/looks.hpp, scene_view.hpp).
#include "looks.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "huygens/pipeline/render_request.hpp"
#include "render_test_helpers.hpp"

using namespace huygens;
using namespace huygens::test;

// The start-up camera of a pool, shallow or SPH pool scene frames the whole region: its four
// corners at the rest level project inside the image with the 15 % margin (NDC within 1/1.15),
// and it is not farther than it needs (one corner on that margin). Regions 1:1 (default, ring,
// pond, dam_break, pool), 2:1 (channel, flood) and 1:2, images 16:9, 1:1 and 9:16. Before
// 2026-12-03 the distance counted the region's depth as foreshortened by sin(pitch) only, as if
// seen from infinitely far: at 1280x720 a square region's near edge fell at NDC y = -1.25 (its
// near sixth cut off by the bottom of the image) and the channel's near corners at x = -1.10.
TEST(VizCamera, StartUpViewFramesTheWholeRegion) {
  for (const auto& [cols, rows] : {std::pair{385, 385}, std::pair{321, 161}, std::pair{161, 321}})
    for (const double aspect : {16.0 / 9.0, 1.0, 9.0 / 16.0}) {
      SceneView view;
      view.grid.rows = rows, view.grid.cols = cols, view.grid.dx = 0.03, view.grid.x0 = 1.0, view.grid.y0 = -2.0;
      const OrbitCamera cam = start_camera(view, aspect, nullptr);
      const glm::dmat4 m = cam.projection(aspect) * cam.view();
      double worst = 0.0;
      for (const double x : {view.grid.x(0), view.grid.x(cols - 1)})
        for (const double y : {view.grid.y(0), view.grid.y(rows - 1)}) {
          glm::dvec4 p = m * glm::dvec4(x, y, 0.0, 1.0);
          p /= p.w;
          worst = std::max({worst, std::abs(p.x), std::abs(p.y)});
        }
      std::printf("region %dx%d, aspect %.2f: distance %.2f m, corners out to NDC %.4f\n", cols, rows, aspect,
                  cam.distance, worst);
      EXPECT_LE(worst, 1.0 / 1.15 + 1e-6) << cols << "x" << rows << " at aspect " << aspect << ": a corner outside";
      EXPECT_GE(worst, 1.0 / 1.15 - 1e-3) << cols << "x" << rows << " at aspect " << aspect << ": farther than needed";
    }
}

TEST(VizCamera, FollowedShipNearAnEdgeKeepsTheViewOnTheWater) {
  // A 100 m region seen from 56 m (half height of the view at the target: 56 tan(22.5 deg) =
  // 23.2 m): the target stays that far inside the region, and the ship within that of the target.
  SceneView view;
  view.grid.rows = view.grid.cols = 513;
  view.grid.dx = 100.0 / 512.0;
  OrbitCamera cam;
  cam.distance = 56.0;
  const double half = cam.distance * std::tan(0.5 * cam.fov_y);
  ShipPose corner;
  corner.x = 2.0;
  corner.y = 97.0;
  corner.heading = 0.0;
  follow_ship(view, corner, cam);
  EXPECT_NEAR(cam.target.x, half, 1e-9);
  EXPECT_NEAR(cam.target.y, 100.0 - half, 1e-9);
  EXPECT_LE(std::abs(corner.x - cam.target.x), half);
  EXPECT_LE(std::abs(corner.y - cam.target.y), half);
  ShipPose middle;
  middle.x = 60.0;
  middle.y = 50.0;
  middle.heading = 0.5 * std::numbers::pi;  // towards +y: the target 0.35 d behind it
  follow_ship(view, middle, cam);
  EXPECT_NEAR(cam.target.x, 60.0, 1e-9);
  EXPECT_NEAR(cam.target.y, 50.0 - 0.35 * cam.distance, 1e-9);
}

TEST(VizLook, SphLabTankWaterShowsThePoolsColourAtItsRestDepth) {
  // A tank 0.1 m deep at rest: its water transmits exp(-a_eff 0.1 m) per channel, what the pool
  // look's 3 m of clear water transmit, exp(-a 3 m). A pool look and SPH water over 3 m deep keep a.
  const RenderSettings clear;
  OrbitCamera cam;
  SceneView view;
  view.grid.rows = view.grid.cols = 65;
  view.grid.dx = 0.01;
  view.look = Look::sph;
  view.height_offset = 0.1;
  const RenderSettings lab = look_settings(view, RenderRequest{}, cam);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(std::exp(-lab.absorb_rgb[c] * 0.1), std::exp(-clear.absorb_rgb[c] * SceneView::kDeepGround), 1e-6);
  view.height_offset = 5.0;
  EXPECT_EQ(look_settings(view, RenderRequest{}, cam).absorb_rgb, clear.absorb_rgb);
  view.look = Look::pool;
  view.height_offset = 0.1;
  EXPECT_EQ(look_settings(view, RenderRequest{}, cam).absorb_rgb, clear.absorb_rgb);
}

// Every look is one unit (looks.hpp): each LookRequest has exactly one, in order, and the scene's
// "render.look" name of a unit parses to that unit's look. A look changes what it says it does:
// the ocean draws no floor and the open sea, the SPH tank hides dry floor and dyes its water, the
// basins keep their deck and caustics unless seen as a slab.
TEST(VizLook, EveryLookIsOneUnitNamedAsTheSceneNamesIt) {
  const auto units = look_units();
  ASSERT_EQ(units.size(), 4u);
  for (std::size_t i = 0; i < units.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(units[i].look), i) << units[i].name;
    const nlohmann::json j = nlohmann::json::parse(std::string(R"({"render": {"look": ")") + units[i].name + "\"}}");
    EXPECT_EQ(parse_render_request(JsonIn(j, "$")).look, units[i].look) << units[i].name;
    EXPECT_EQ(&look_unit(units[i].look), &units[i]);
  }
  SceneView view;
  view.grid = GridPlacement{};
  view.grid.rows = view.grid.cols = 64, view.grid.dx = 0.1;
  view.height_offset = 0.3;
  OrbitCamera cam;
  auto settings = [&](Look look) {
    RenderSettings s;
    look_unit(look).settings(view, cam, s);
    return s;
  };
  const RenderSettings ocean = settings(Look::ocean), pool = settings(Look::pool), sph = settings(Look::sph);
  EXPECT_TRUE(ocean.deep_water && !ocean.caustics && look_unit(Look::ocean).open_sea);
  EXPECT_TRUE(pool.pool_deck && pool.caustics && !pool.deep_water && !pool.hide_dry);
  EXPECT_TRUE(sph.hide_dry && sph.pool_deck);
  EXPECT_FLOAT_EQ(sph.absorb_rgb.r, RenderSettings{}.absorb_rgb.r * 10.0f) << "3 m over 0.3 m";
  view.slab = true;
  const RenderSettings slab = settings(Look::shallow);
  EXPECT_TRUE(!slab.pool_deck && !slab.caustics && slab.ground == GroundPattern::uniform);
}
