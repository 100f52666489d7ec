// Tests of the sky pass (viz/passes/sky_pass.hpp): the open sea beyond the region with the
// ambient sea's slopes, the horizon under a graded sky, the far sea's glitter against Cox and
// Munk's slope variance, the far sea computed only for a picture that draws it.
#include <gtest/gtest.h>

#include "render_test_helpers.hpp"

using namespace huygens;
using namespace huygens::test;

// The open ocean goes on beyond the simulated region with the ambient sea's slopes
// (WaterRenderer::set_ambient_sea): at 640 x 360, t = 1 s, from the start-up camera 15 deg up
// (the region's west edge crosses rows 150-190 at x 186-126), a crop of the sea left of the
// region (x 50-120, y 150-190) against one inside it on the same rows (x 195-265), glints (mean
// channel >= 80) left out. Texture: the mean |difference| of horizontal neighbours, measured
// 2.70 beyond and 4.25 inside (the beyond has no Stokes part and is mip-averaged), 0.041 with
// the flat sea of before (ambient_sea off, as when the wind is switched off); brightness 57.1
// beyond and 53.9 inside.
// (Until 2026-12-03 the camera stood 40 deg up: crops x 10-120 and 500-600 on rows 20-120,
// texture 1.75 beyond, 3.58 inside, 0.025 flat.)
TEST_F(VizRender, OceanGoesOnBeyondTheRegionWithTheAmbientSea) {
  struct Crop {
    double mean = 0, texture = 0;
  };
  const auto crop = [](const gl::Image8& img, int x0, int x1, int y0, int y1) {
    const auto v = [&](int x, int y) {
      double m = 0;
      for (int c = 0; c < 3; ++c) m += img.pixels[4 * (static_cast<std::size_t>(y) * img.width + x) + c] / 3.0;
      return m;
    };
    Crop r;
    long n = 0, nd = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        if (v(x, y) >= 80) continue;
        r.mean += v(x, y), ++n;
        if (x + 1 < x1 && v(x + 1, y) < 80) r.texture += std::fabs(v(x + 1, y) - v(x, y)), ++nd;
      }
    r.mean /= static_cast<double>(n);
    r.texture /= static_cast<double>(nd);
    return r;
  };
  const auto [sea, flat] =
      render_twice("ocean.json", 1.0, 640, 360, [](HeadlessOptions& o) { o.settings.ambient_sea = false; });
  const Crop beyond = crop(sea, 50, 120, 150, 190), inside = crop(sea, 195, 265, 150, 190);
  const Crop flat_beyond = crop(flat, 50, 120, 150, 190);
  EXPECT_LT(flat_beyond.texture, 0.1) << "the flat sea";
  EXPECT_GT(beyond.texture, 0.3 * inside.texture)
      << "the sea beyond has waves: " << beyond.texture << " against " << inside.texture << " inside";
  EXPECT_NEAR(beyond.mean, inside.mean, 0.1 * inside.mean) << "no step in tone at the region's edge";
  std::printf("texture beyond %.3f (flat %.3f), inside %.3f; brightness beyond %.1f, inside %.1f\n", beyond.texture,
              flat_beyond.texture, inside.texture, beyond.mean, inside.mean);
  if (::testing::Test::HasFailure()) write_debug("ocean_beyond.png", sea), write_debug("ocean_flat.png", flat);
}

// The open sea reaches the horizon and the sky above it is graded (shaders/background.frag).
// Still deep water (no glint, Schlick Fresnel) seen from 0.84 m up, 8 degrees down: every pixel
// is a closed form of its view ray d, the water mix(0.7 W, S(r), F(-d_z)) below the horizon (the
// region and the sea beyond alike, deep_water_colour of a level normal under a sun at any height)
// and the sky S(d) above; S(v) = u_sky (uniform) or mix(sky, zenith, sqrt(v_z)) (graded), r the
// mirrored ray (r_z = -d_z). The rows within 2.8 degrees of the horizon meet the sea beyond the
// deck, 2 region sizes (8 m) past the region, that the sea used to end with: those rows showed
// the uniform sky colour.
TEST_F(VizRender, OpenSeaReachesTheHorizonUnderAGradedSky) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  r.set_heights(std::vector<float>(kN * kN, 0.0f));
  OrbitCamera cam;
  cam.target = glm::dvec3(g.x0 + 0.5 * kWidth, g.y0 + 0.5 * kWidth, 0.0);
  cam.pitch = 8.0 * std::numbers::pi / 180.0;
  cam.distance = 6.0;
  RenderSettings s = deep_sea_settings(false);
  const int W = 96, H = 180;
  const double n = s.index, f0 = std::pow((n - 1) / (n + 1), 2);
  struct Ray {
    glm::dvec3 o, d;
    double y_plane;  // y where the ray meets the rest level (m)
  };
  const auto ray = [&](int y) {  // the ray through the centre column's pixel y (row 0 at the top)
    Ray r;
    cam.ray_through((2.0 * (W / 2) + 1.0) / W - 1.0, 1.0 - (2.0 * y + 1.0) / H, double(W) / H, r.o, r.d);
    r.y_plane = r.o.y - r.o.z / r.d.z * r.d.y;
    return r;
  };
  const double old_end = g.y0 + 3.0 * kWidth;  // where the sea's and the deck's quads end (m)
  for (bool graded : {false, true}) {
    s.sky_gradient = graded;
    const gl::Image8 img = render(r, cam, s, W, H);
    int sea_rows = 0, far_rows = 0;
    for (int y = 0; y < H; ++y) {
      const auto [o, d, py] = ray(y);
      if (std::fabs(d.z) < 0.01) continue;  // the pixel the horizon cuts
      const double F = f0 + (1 - f0) * std::pow(1.0 - std::max(-d.z, 0.0), 5);
      for (int c = 0; c < 3; ++c) {
        const auto S = [&](double rz) {                                     // the sky in a direction of height rz
          const double h = lin(s.sky_colour[c]), z = lin(s.sky_zenith[c]);  // in linear light
          return graded ? h + (z - h) * std::sqrt(rz) : h;
        };
        const double sky = S(std::max(d.z, 0.0)),
                     sea = (1 - F) * 0.7 * lin(s.water_colour[c]) + F * S(std::max(-d.z, 0.0));
        EXPECT_NEAR(channel(img, W / 2, y, c), display(d.z > 0 ? sky : sea), 1.5 / 255.0)
            << (graded ? "graded" : "uniform") << " sky, row " << y << " channel " << c << ", d_z " << d.z;
      }
      sea_rows += d.z < 0;
      far_rows += d.z < 0 && py > old_end;
    }
    EXPECT_GT(far_rows, 5) << "rows that meet the sea beyond the old deck";
    EXPECT_GT(sea_rows, far_rows + 20);
    if (::testing::Test::HasFailure()) write_debug(graded ? "horizon_graded.png" : "horizon.png", img);
  }
  // the pool's deck, a uniform ground lit by ambient 1: its colour mix(ground, pale stone, 0.6)
  // wherever the ray meets the rest level outside the region, out to the horizon (it used to end
  // 2 region sizes out with the sky behind)
  s.deep_water = false, s.pool_deck = true, s.sky_gradient = false;
  s.ground = GroundPattern::uniform;
  s.ground_uniform = glm::vec3(0.8f, 0.6f, 0.2f);
  const gl::Image8 img = render(r, cam, s, W, H);
  int far_deck_rows = 0;
  for (int y = 0; y < H; ++y) {
    const auto [o, d, py] = ray(y);
    // left out: the pixel the horizon cuts, and the region with its rims (the water's near side
    // is a pixel high at this view)
    if (std::fabs(d.z) < 0.01 || (d.z < 0 && py >= g.y0 - 0.2 && py <= g.y0 + kWidth + 0.2)) continue;
    for (int c = 0; c < 3; ++c) {
      const double a = lin(s.ground_uniform[c]), stone = lin(glm::vec3(0.85f, 0.84f, 0.80f)[c]);
      const double deck = display(a + 0.6 * (stone - a));
      EXPECT_NEAR(channel(img, W / 2, y, c), d.z > 0 ? s.sky_colour[c] : deck, 1.5 / 255.0)
          << "deck, row " << y << " channel " << c << ", d_z " << d.z;
    }
    far_deck_rows += d.z < 0 && py > old_end;
  }
  EXPECT_GT(far_deck_rows, 5);
  if (::testing::Test::HasFailure()) write_debug("horizon_deck.png", img);
}

// Far away, where a pixel holds many of the ambient sea's waves, the glint has the sea's slope
// statistics (Bruneton, Neyret & Holzschuch 2010): the mipmap averages the slopes and their
// squares' sum, and the variance in the texel widens the glint. Seen straight down from above
// (orthographic, 16 x 16 pixels of 125 m each, far from the region: every pixel's texel is the
// 1 x 1 level, mean slope 0), with the sun 55 degrees up, every pixel is the closed form with m2 =
// a^2 / 8 + the resolved mean square slope + the unresolved one, that is a^2 / 8 + Cox & Munk's
// 0.003 + 5.12e-3 U for the 6 m/s wind: the sea's own statistics, however much of it the grid
// resolves. Without the texel's variance it would be the unresolved part alone. Over the region
// itself the glint takes what the region's central differences leave unresolved.
TEST_F(VizRender, FarSeaGlitterHasCoxAndMunksSlopeVariance) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  r.set_heights(std::vector<float>(kN * kN, 0.0f));
  WindParams wind;
  wind.speed_mps = 6.0, wind.fetch_m = 10000.0, wind.seed = 7;
  const RenderAmbientSea sea{std::make_shared<AmbientSeaSlopes>(wind, Water{}, 64, 100.0), wind.speed_mps};
  r.set_ambient_sea(sea);
  const double cox_munk = 0.003 + 5.12e-3 * wind.speed_mps;
  ASSERT_GT(r.unresolved_slope_var(), 0.1 * cox_munk) << "a grid that leaves part of the slopes unresolved";
  ASSERT_LT(r.unresolved_slope_var(), 0.9 * cox_munk) << "and resolves part of them";
  const OrbitCamera cam = top_down(3000.0, 3000.0, 2000.0);
  RenderSettings s = deep_sea_settings(true);
  s.sun_irradiance = 40.0f;  // a glint near normal incidence reflects 2 % (Fresnel)
  const double el = 55.0 * std::numbers::pi / 180.0;
  const glm::dvec3 sun(std::cos(el), 0.0, std::sin(el)), d(0.0, 0.0, -1.0);
  s.sun_dir = glm::vec3(sun);
  r.set_sea_time(3.0);
  const gl::Image8 img = render(r, cam, s, 16, 16);
  const double n = s.index, f0 = std::pow((n - 1) / (n + 1), 2);
  const double glint =
      glint_closed_form(d, sun, s.sun_irradiance, s.sun_radius_rad * s.sun_radius_rad / 8.0 + cox_munk, n);
  const double unresolved_only = glint_closed_form(
      d, sun, s.sun_irradiance, s.sun_radius_rad * s.sun_radius_rad / 8.0 + r.unresolved_slope_var(), n);
  EXPECT_GT(std::fabs(glint - unresolved_only), 10.0 / 255.0) << "the two differ in what the test sees";
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) {
        const double expect =
            display((1 - f0) * 0.7 * lin(s.water_colour[c]) + f0 * lin(s.sky_colour[c]) + glint * lin(s.sun_colour[c]));
        EXPECT_NEAR(channel(img, x, y, c), expect, 1.5 / 255.0) << "pixel " << x << ", " << y << " channel " << c;
      }
  std::printf("glint %.4f (unresolved only %.4f), pixel (8, 8): %.4f\n", glint, unresolved_only, lum(img, 8, 8));
  if (::testing::Test::HasFailure()) write_debug("far_glitter.png", img);
  // the region (still here) adds what its central differences do not resolve: seen from above,
  // every pixel is the closed form with m2 = a^2 / 8 + region_unresolved_slope_var
  const double region_var = r.region_unresolved_slope_var();
  EXPECT_GT(region_var, r.unresolved_slope_var() + 0.002) << "central differences resolve less";
  const gl::Image8 region = render(r, top_down(g.x0 + 0.5 * kWidth, g.y0 + 0.5 * kWidth, 0.5 * kWidth), s, 16, 16);
  const double in_region =
      glint_closed_form(d, sun, s.sun_irradiance, s.sun_radius_rad * s.sun_radius_rad / 8.0 + region_var, n);
  EXPECT_GT(std::fabs(in_region - unresolved_only), 5.0 / 255.0) << "the region's own term is seen";
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) {
        const double expect = display((1 - f0) * 0.7 * lin(s.water_colour[c]) + f0 * lin(s.sky_colour[c]) +
                                      in_region * lin(s.sun_colour[c]));
        EXPECT_NEAR(channel(region, x, y, c), expect, 1.5 / 255.0) << "region pixel " << x << ", " << y;
      }
  std::printf("region: unresolved %.4f (beyond %.4f), glint %.4f\n", region_var, r.unresolved_slope_var(), in_region);
}

// The ambient sea's slopes (one n x n inverse FFT per display time) are computed only for a
// picture that draws them: with the wind switched off (ambient_sea false) or in a look without
// the open sea, a new display time computes nothing; the first picture that draws the sea
// computes them for the newest time, once.
TEST_F(VizRender, AmbientSeaIsComputedOnlyForAPictureThatDrawsIt) {
  const GridPlacement g = test_grid();
  WaterRenderer r(g, -kDepth, 4);
  r.set_heights(std::vector<float>(kN * kN, 0.0f));
  const RenderAmbientSea sea{std::make_shared<AmbientSeaSlopes>(WindParams{}, Water{}, 64, 2.0 * kWidth),
                             WindParams{}.speed_mps};
  r.set_ambient_sea(sea);
  EXPECT_TRUE(std::isnan(r.sea_slopes_time())) << "nothing drawn yet";
  OrbitCamera cam = default_camera(g.x0, g.y0, kWidth, kWidth);
  RenderSettings s = plain_settings();
  s.deep_water = true;
  s.ambient_sea = false;
  r.set_sea_time(1.5);
  render(r, cam, s, 32, 32);
  EXPECT_TRUE(std::isnan(r.sea_slopes_time())) << "the wind is off";
  s.ambient_sea = true, s.deep_water = false;
  render(r, cam, s, 32, 32);
  EXPECT_TRUE(std::isnan(r.sea_slopes_time())) << "a look without the open sea";
  s.deep_water = true;
  r.set_sea_time(2.5);
  render(r, cam, s, 32, 32);
  EXPECT_EQ(r.sea_slopes_time(), 2.5);
  s.ambient_sea = false;
  r.set_sea_time(3.5);
  render(r, cam, s, 32, 32);
  EXPECT_EQ(r.sea_slopes_time(), 2.5) << "switched off again";
}
