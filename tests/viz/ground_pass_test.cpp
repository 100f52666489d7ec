// Tests of the ground pass (viz/passes/ground_pass.hpp): the floor's tiles, the terrain under
// shallow water, the pool's walls seen through the water, the caustics' light on the floor.
#include <gtest/gtest.h>

#include "render_test_helpers.hpp"

using namespace huygens;
using namespace huygens::test;

// Water over terrain (WaterRenderer::set_bed): a bed ramp from 1 m below the rest level to 0.5 m
// above it along x, water at the rest level where the bed is below it and none (the height is the
// bed) where it is above. Seen from above with white opaque water and black ground, the middle
// row of the image is white over the wet two thirds (x below the shoreline) and black over the
// dry third, with one transition; all dry shows no water at all, all flooded only water.
TEST_F(VizRender, WaterOverTerrainLeavesDryLandVisible) {
  const GridPlacement g = test_grid();
  std::vector<float> bed(kN * kN), shore(kN * kN), dry(kN * kN), flooded(kN * kN, 1.0f);
  for (std::size_t i = 0; i < kN; ++i)
    for (std::size_t j = 0; j < kN; ++j) {
      const std::size_t k = i * kN + j;
      bed[k] = static_cast<float>(-1.0 + 1.5 * j / (kN - 1.0));
      shore[k] = std::max(bed[k], 0.0f);
      dry[k] = bed[k];
    }
  WaterRenderer r(g, -kDepth, 1);
  r.set_bed(bed);
  OrbitCamera cam = default_camera(g.x0, g.y0, kWidth, kWidth);
  cam.pitch = 1.5;  // nearly straight down
  cam.distance = 6.0;
  RenderSettings m = plain_settings();
  m.pool_deck = false;
  m.ground = GroundPattern::uniform;
  m.ground_uniform = glm::vec3(0.0f);
  m.absorption = true;
  m.absorb_rgb = glm::vec3(1e4f);  // opaque water of the water colour
  m.water_colour = glm::vec3(1.0f);
  const int W = 256, H = 256;
  auto row_counts = [&](const std::vector<float>& heights, int& white, int& black, int& transitions) {
    r.set_heights(heights);
    const gl::Image8 img = render(r, cam, m, W, H);
    white = black = transitions = 0;
    int last = -1;
    for (int x = 0; x < W; ++x) {
      const double v = channel(img, x, H / 2, 0);
      const int now = v > 0.5 ? 1 : v < 0.1 ? 0 : -1;
      if (now < 0) continue;
      (now ? white : black) += 1;
      if (last >= 0 && now != last) ++transitions;
      last = now;
    }
    if (transitions != 1) write_debug("terrain.png", img);
  };
  int white, black, transitions;
  row_counts(shore, white, black, transitions);
  std::printf("terrain: %d water and %d dry-land pixels in the middle row, %d transitions\n", white, black,
              transitions);
  EXPECT_EQ(transitions, 1) << "one shoreline";
  EXPECT_NEAR(static_cast<double>(white) / (white + black), 2.0 / 3.0, 0.05)
      << "the shoreline where the bed meets the rest level";
  row_counts(dry, white, black, transitions);
  EXPECT_EQ(white, 0) << "dry land everywhere: no water drawn";
  row_counts(flooded, white, black, transitions);
  EXPECT_GT(white, W / 3);
  EXPECT_EQ(transitions, 0) << "all flooded: water only";

  // With the pool's deck around it, dry land below the rest level reaches the region's outline:
  // seen straight down at the south edge (4 px per cell), every pixel inside the outline is the
  // terrain's black and every one outside it the deck's pale stone. Until 2026-12-04 the deck,
  // at the rest level, reached 1.5 cells inside and hid the lower land there.
  m.pool_deck = true;
  r.set_heights(dry);
  const OrbitCamera edge = top_down(g.x0 + 0.5 * kWidth, g.y(0), 1.0);
  const gl::Image8 img = render(r, edge, m, 128, 128);
  int inside = 0, hidden = 0;
  for (int i = 0; i < 128; ++i) {
    const double y = edge.target.y + (64.0 - i - 0.5) / 128.0;  // pixel centre (m)
    if (y < g.y(0) + 1.5 / 128.0) continue;                     // the outline's own pixels
    ++inside;
    hidden += channel(img, 64, i, 0) > 0.1;
  }
  EXPECT_GT(inside, 50);
  EXPECT_EQ(hidden, 0) << "pixels inside the outline where the deck hides the land";
  if (hidden) write_debug("terrain_edge.png", img);
}

// The pool's walls seen through still water (shaders/ground_common.glsl, seen_under_water): a
// uniform ground of albedo a, sky light A and still-water sunlight S on the floor, the sun from
// the south, 40 degrees up. Every pixel is a closed form of its view ray d: it meets the rest
// level at P, refracts (Snell) to t and ends on the floor, a (A + S), or first on a wall of
// inward normal n_w, a (A / 2 + S max(n_w . (-s_w), 0) / (-s_w.z) + a (A + S) / 2), s_w the
// sun's ray refracted into the water (a vertical wall sees half the sky and half the lit floor).
// Seen from the south, 50 degrees up: the far (north) wall faces the sun, the side walls are
// edge-on to it. Until 2026-12-04 every wall had a (A + 0.3 S), the colour of its foot: a dark
// frame round every pool.
TEST_F(VizRender, PoolWallsSeenThroughTheWaterAreLitBySunSkyAndFloor) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  r.set_heights(std::vector<float>(kN * kN, 0.0f));
  OrbitCamera cam = default_camera(g.x0, g.y0, kWidth, kWidth);
  cam.distance = 1.6 * kWidth;
  RenderSettings s = plain_settings();
  s.pool_deck = true;
  s.exact_refraction = true;
  s.ground = GroundPattern::uniform;
  s.ground_uniform = glm::vec3(0.6f, 0.5f, 0.4f);
  s.ambient = 0.3f;
  s.sun_light = 0.5f;
  const double el = 40.0 * std::numbers::pi / 180.0, n = s.index;
  s.sun_dir = glm::vec3(0.0f, static_cast<float>(-std::cos(el)), static_cast<float>(std::sin(el)));
  const int W = 160, H = 120;
  const gl::Image8 img = render(r, cam, s, W, H);
  const glm::dvec3 s_w = glm::refract(-glm::normalize(glm::dvec3(s.sun_dir)), glm::dvec3(0, 0, 1), 1.0 / n);
  const double lo = g.x(0), hi = g.x(kN - 1), A = s.ambient, S = s.sun_light, margin = 0.1;
  // per pixel: what its ray meets (-1 not checked: the sky, the region's rims, a corner, a wall's
  // top or foot; 0 the floor; 1 + k wall k) and the light there
  std::vector<int> what(W * H, -1);
  std::vector<double> light(W * H, 0.0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      glm::dvec3 o, d;
      cam.ray_through((2.0 * x + 1.0) / W - 1.0, 1.0 - (2.0 * y + 1.0) / H, double(W) / H, o, d);
      if (d.z >= 0.0) continue;
      const glm::dvec3 P = o - o.z / d.z * d;
      if (P.x < lo + margin || P.x > hi - margin || P.y < lo + margin || P.y > hi - margin) continue;
      const glm::dvec3 t = glm::refract(d, glm::dvec3(0, 0, 1), 1.0 / n);
      const glm::dvec3 F = P + t * (-kDepth / t.z);
      // the fraction of P -> F at each wall plane it crosses, and that wall's inward normal
      std::vector<std::pair<double, int>> walls;
      if (F.x < lo) walls.push_back({(lo - P.x) / (F.x - P.x), 0});
      if (F.x > hi) walls.push_back({(hi - P.x) / (F.x - P.x), 1});
      if (F.y < lo) walls.push_back({(lo - P.y) / (F.y - P.y), 2});
      if (F.y > hi) walls.push_back({(hi - P.y) / (F.y - P.y), 3});
      std::sort(walls.begin(), walls.end());
      const std::size_t k = static_cast<std::size_t>(y) * W + x;
      if (walls.size() > 1 && walls[1].first - walls[0].first < 0.05) continue;  // a corner
      if (walls.empty()) {
        what[k] = 0, light[k] = A + S;
        continue;
      }
      const glm::dvec2 nw[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      const glm::dvec2 m = nw[walls[0].second];
      const double hit_z = -kDepth * walls[0].first;
      if (hit_z > -margin) continue;  // the wall's top
      what[k] = 1 + walls[0].second;
      light[k] = 0.5 * A + S * std::max(-(m.x * s_w.x + m.y * s_w.y), 0.0) / -s_w.z;
    }
  // checked: the pixels whose 3 x 3 neighbours all meet the same (the floor's edge is
  // anti-aliased over a pixel's footprint)
  int floor_px = 0, north_px = 0, side_px = 0;
  for (int y = 1; y + 1 < H; ++y)
    for (int x = 1; x + 1 < W; ++x) {
      const int w = what[static_cast<std::size_t>(y) * W + x];
      bool same = w >= 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) same = same && what[static_cast<std::size_t>(y + dy) * W + x + dx] == w;
      if (!same) continue;
      for (int c = 0; c < 3; ++c) {
        const double a = lin(s.ground_uniform[c]);  // the albedo in linear light
        const double expected =
            display(a * (light[static_cast<std::size_t>(y) * W + x] + (w == 0 ? 0.0 : 0.5 * a * (A + S))));
        EXPECT_NEAR(channel(img, x, y, c), expected, 2.0 / 255.0)
            << "pixel (" << x << ", " << y << ") channel " << c << (w == 0 ? ", floor" : ", wall");
      }
      floor_px += w == 0;
      north_px += w == 4;
      side_px += w == 1 || w == 2;
    }
  std::printf("pool walls: %d floor, %d north wall, %d side wall pixels checked\n", floor_px, north_px, side_px);
  EXPECT_GT(floor_px, 2000);
  EXPECT_GT(north_px, 300);
  EXPECT_GT(side_px, 100);
  if (::testing::Test::HasFailure()) write_debug("pool_walls.png", img);
}

// Issue 5, defect 2 (short dark lines on the ground): the whole chain, caustics pass (MIP
// mode, 8-bit target, accumulation-buffer emulation: the app's defaults) and the lit ground seen
// through the water. A gentle plane wave over the visible field, the default oblique sun,
// uniform ground, seen straight down: light varies smoothly (about 0.85-1.2 of still water),
// so no pixel may fall below 0.85 of the median of its 5 x 5 neighbourhood (a pixel is
// albedo (0.35 + 0.65 light); the unlit texels the caustics texture used to have along its
// edge, which the oblique sun moves into the view, gave about 0.5). Still water: uniform.
TEST_F(VizRender, CausticsLightTheGroundWithoutDarkLines) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  const OrbitCamera cam = top_down(g.x0 + 2.0, g.y0 + 2.0, 3.6);
  // huygens-viz's default (explicit area, float) and the paper's MIP mode, 8-bit, emulated blur
  for (const CausticsMode mode : {CausticsMode::conserving, CausticsMode::mip_paper}) {
    RenderSettings s = plain_settings();
    s.caustics = true;
    s.caustics_mode = mode;
    s.ambient = 0.35f;
    s.sun_light = 0.65f;
    s.ground = GroundPattern::uniform;
    s.ground_uniform = glm::vec3(0.8f);
    const int W = 256, H = 256;
    // plane wave, 3 wavelengths across, amplitude 4.5 mm: (1 - 1/n) D A k^2 = 0.05 (sun overhead)
    const double k = 2 * M_PI / (kWidth / 3.0), A = 0.0045;
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<float> eta(kN * kN, 0.0f);
      if (pass == 1) {
        for (std::size_t i = 0; i < kN; ++i)
          for (std::size_t j = 0; j < kN; ++j)
            eta[i * kN + j] = static_cast<float>(A * std::sin(k * (0.8 * g.x(j) + 0.6 * g.y(i)) + 0.3));
      }
      r.set_heights(eta);
      const gl::Image8 img = render(r, cam, s, W, H);
      double worst = 1e30, lo = 1e30, hi = 0;
      int wx = 0, wy = 0;
      for (int y = 2; y < H - 2; ++y)
        for (int x = 2; x < W - 2; ++x) {
          double nb[25];
          int m = 0;
          for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) nb[m++] = lum(img, x + dx, y + dy);
          std::nth_element(nb, nb + 12, nb + 25);
          const double v = lum(img, x, y);
          lo = std::min(lo, v), hi = std::max(hi, v);
          if (v / nb[12] < worst) worst = v / nb[12], wx = x, wy = y;
        }
      std::printf(
          "caustics on the ground (mode %d, %s): pixel range [%.3f, %.3f], worst pixel / 5x5 median %.3f at (%d, %d)\n",
          static_cast<int>(mode), pass ? "plane wave" : "still water", lo, hi, worst, wx, wy);
      if (worst < 0.85) write_debug(pass ? "caustics_wave.png" : "caustics_still.png", img);
      EXPECT_GE(worst, 0.85) << (pass ? "plane wave" : "still water") << ": a dark pixel at (" << wx << ", " << wy
                             << ")";
      if (pass == 0) {
        EXPECT_LE(hi - lo, 2.5 / 255.0) << "still water lights the ground uniformly";
      }
    }
  }
}

// The floor is a ruler: its tiles are the 1-2-5 length nearest an eighth of the visible region's
// longer side (WaterRenderer::tile_m), and a headless perspective picture says so in its caption
// (scene, time, region, tiles; HeadlessOptions::caption), drawn as white text on a dark band in the
// top-left corner, left out with caption = false.
TEST_F(VizRender, FloorTilesAreARoundLengthTheCaptionGives) {
  const auto tile = [](std::size_t n, double dx) {
    GridPlacement g;
    g.rows = n, g.cols = n, g.dx = dx;
    return WaterRenderer(g, -1.0, 4).tile_m();
  };
  EXPECT_DOUBLE_EQ(tile(384, 15.0 / 512), 1.0);  // default.json: 11.25 m, 1.41 m wanted
  EXPECT_DOUBLE_EQ(tile(416, 0.1), 5.0);         // kelvin.json: 41.6 m, 5.2 m wanted
  EXPECT_DOUBLE_EQ(tile(40, 0.005), 0.02);       // pool.json: 0.2 m, 0.025 m wanted
  EXPECT_DOUBLE_EQ(tile(100, 0.032), 0.5);       // 3.2 m, 0.4 m wanted
  const auto [with, without] =
      render_twice("kelvin.json", 0.1, 320, 180, [](HeadlessOptions& o) { o.caption = false; });
  long white = 0, band = 0, differ = 0;
  for (int y = 0; y < 13; ++y)
    for (int x = 0; x < 200; ++x) {
      const std::uint8_t* p = &with.pixels[4 * (static_cast<std::size_t>(y) * with.width + x)];
      white += p[0] == 255 && p[1] == 255 && p[2] == 255;
      band += std::abs(p[0] - 31) <= 1 && std::abs(p[1] - 36) <= 1 && std::abs(p[2] - 43) <= 1;
    }
  for (std::size_t k = 4 * 13 * static_cast<std::size_t>(with.width); k < with.pixels.size(); ++k)
    differ += with.pixels[k] != without.pixels[k];
  EXPECT_GT(white, 100) << "the caption's text";
  EXPECT_GT(band, 1000) << "its band";
  EXPECT_EQ(differ, 0) << "below the band the picture is the same";
  if (::testing::Test::HasFailure()) write_debug("caption.png", with);
}
