#pragma once
// What the render tests share (tests/viz/*_test.cpp): one headless EGL context for a suite, quiet
// settings for optical checks, a test grid and cameras, pixel readers, the scene renderer as
// huygens-viz runs it, and the glint's closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "camera.hpp"
#include "caustics_stage.hpp"
#include "dye.hpp"
#include "foam.hpp"
#include "gl.hpp"
#include "headless.hpp"
#include "huygens/pipeline/runner.hpp"
#include "huygens/solvers/registry.hpp"
#include "huygens/spectral/ambient_slopes.hpp"  // the Huygens solver's far sea, built here as its render_info does
#include "plot.hpp"
#include "renderer.hpp"
#include "scene_view.hpp"
#include "scenes_dir.hpp"
#include "srgb.hpp"

namespace huygens::test {

inline gl::HeadlessContext& context() {
  static gl::HeadlessContext ctx;  // one context for the whole suite
  return ctx;
}

// A quiet setting for optical checks: no caustics, no absorption, no reflections.
inline RenderSettings plain_settings() {
  RenderSettings s;
  s.caustics = false;
  s.absorption = false;
  s.fresnel = FresnelModel::off;
  s.sun_glint = false;
  s.draw_ship = false;
  s.ambient = 1.0f;
  s.sun_light = 0.0f;
  s.sky_gradient = false;  // the uniform sky_colour, no tone map: pixels are the closed forms
  s.tone_map = false;
  return s;
}

// Deep water (no floor) with Schlick's Fresnel, otherwise plain_settings; glint on or off.
inline RenderSettings deep_sea_settings(bool glint) {
  RenderSettings s = plain_settings();
  s.deep_water = true;
  s.fresnel = FresnelModel::schlick;
  s.sun_glint = glint;
  return s;
}

// Visible region of kN x kN points, 4 m wide, corner at (1, 1) m; ground 2 m down.
constexpr std::size_t kN = 128;
constexpr double kWidth = 4.0, kDepth = 2.0;
inline GridPlacement test_grid() {
  GridPlacement g;
  g.rows = g.cols = kN;
  g.dx = kWidth / kN;
  g.x0 = g.y0 = 1.0;
  return g;
}

// An orthographic camera looking straight down at (x, y) (m), showing height_m of the scene.
inline OrbitCamera top_down(double x, double y, double height_m) {
  OrbitCamera cam;
  cam.ortho = true;
  cam.ortho_height = height_m;
  cam.target = glm::dvec3(x, y, 0.0);
  cam.distance = 10.0;
  cam.pitch = 1.5707963267948966;
  return cam;
}

// The renderer shades in linear radiance and encodes sRGB once (srgb.hpp): a pixel's value for a
// linear radiance (clamped, no tone map), and an sRGB colour's linear radiance.
inline double display(double linear) { return linear_to_srgb(std::clamp(linear, 0.0, 1.0)); }
inline double lin(double srgb) { return srgb_to_linear(srgb); }

inline double channel(const gl::Image8& img, int x, int y, int c) {
  return img.pixels[4 * (static_cast<std::size_t>(y) * img.width + x) + c] / 255.0;
}
inline double lum(const gl::Image8& img, int x, int y) {
  return (channel(img, x, y, 0) + channel(img, x, y, 1) + channel(img, x, y, 2)) / 3.0;
}

// Sub-pixel position (pixel-centre units) where the row y crosses `level`, searching from
// x_start in direction dir (+1/-1); NaN if none.
inline double crossing(const gl::Image8& img, int y, int x_start, int dir, double level) {
  for (int x = x_start; x + dir >= 0 && x + dir < img.width; x += dir) {
    const double a = lum(img, x, y), b = lum(img, x + dir, y);
    if ((a - level) * (b - level) <= 0.0 && a != b) return x + dir * (a - level) / (a - b);
  }
  return std::nan("");
}

inline gl::Image8 render(WaterRenderer& r, const OrbitCamera& cam, const RenderSettings& s, int w, int h) {
  RenderTarget target(w, h);
  r.render(cam, s, target);
  return target.read();
}

inline void write_debug(const std::string& name, const gl::Image8& img) {
  gl::write_png(::testing::TempDir() + "/" + name, img);
}

class VizRender : public ::testing::Test {
 protected:
  void SetUp() override { context().make_current(); }
};

// The scene's solver for the viewer, as huygens-viz makes it for --headless (FFTW_ESTIMATE plans).
inline ViewerSolver viewer_solver(const std::string& scene) {
  RunOptions ro;
  ro.measure_plans = false;
  return open_viewer_solver(scene, ro);
}

// A shipped scene rendered headless at time t and w x h with its look, then again with `change`
// applied to the options: the two images.
inline std::pair<gl::Image8, gl::Image8> render_twice(const std::string& scene, double t, int w, int h,
                                                      const std::function<void(HeadlessOptions&)>& change) {
  const std::string file = (std::filesystem::path(huygens::test::scenes_dir()) / scene).string();
  HeadlessOptions o;
  o.time = t;
  o.width = w, o.height = h;
  ViewerSolver vs = viewer_solver(file);
  o.settings = view_setup(vs, static_cast<double>(w) / h).settings;
  gl::Image8 first = render_headless(std::move(vs), o).image;
  change(o);
  return {std::move(first), render_headless(viewer_solver(file), o).image};
}

// The glint's radiance in the closed form of ground_common.glsl's glint(): the sun (irradiance
// E over the sky's radiance, colour C) on facets with Gaussian slopes about the mean normal n, of
// mean square slope m2 (Beckmann's D; with `masking`, Smith's G1 in Walter et al.'s 2007
// rational form), seen along d (towards the water), with Schlick's F of index `index` at the
// angle between the facet and the eye.
inline double glint_closed_form(const glm::dvec3& d, const glm::dvec3& sun, double E, double m2, double index,
                                const glm::dvec3& n = {0.0, 0.0, 1.0}, bool masking = true) {
  const glm::dvec3 v = -d, h = glm::normalize(sun + v);
  const double nv = glm::dot(n, v), ns = glm::dot(n, sun), nh = glm::dot(n, h);
  if (nv <= 0 || ns <= 0) return 0.0;
  const auto g1 = [&](double c) {
    const double a = c / std::sqrt(m2 * (1 - c * c));
    return !masking || a >= 1.6 ? 1.0 : (3.535 * a + 2.181 * a * a) / (1 + 2.276 * a + 2.577 * a * a);
  };
  const double f0 = std::pow((index - 1) / (index + 1), 2), F = f0 + (1 - f0) * std::pow(1 - glm::dot(h, v), 5);
  const double tan2 = (1 - nh * nh) / (nh * nh);
  const double D = std::exp(-tan2 / m2) / (std::numbers::pi * m2 * std::pow(nh, 4));
  return E * F * D * g1(nv) * g1(ns) / (4 * nv);
}

}  // namespace huygens::test
