// End-to-end render tests of huygens-viz, headless through EGL's surfaceless platform (Mesa
// llvmpipe): the same scene gives the same image, golden images of the shipped scenes, the real
// window under Xvfb, the caustics' light on solver fields against photons, and the dye and foam the
// flow carries. Each pass has its own test file (tests/viz/*_pass_test.cpp).
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
#include "render_test_helpers.hpp"
#include "renderer.hpp"
#include "scene_view.hpp"
#include "scenes_dir.hpp"

using namespace huygens;
using namespace huygens::test;

// The same options give the same image (fixed time step, the runner's manual clock: no wall
// clock, no threads racing); the built-in default scene is the shipped one.
TEST_F(VizRender, HeadlessRenderIsDeterministic) {
  HeadlessOptions o;
  o.frames = 4;
  o.width = o.height = 96;
  const HeadlessResult a = render_headless(viewer_solver(""), o), b = render_headless(viewer_solver(""), o);
  EXPECT_EQ(a.image.pixels, b.image.pixels);
  // frames at 0, 1, 2, 3 x dt / 3: the last shows the first step (dt = 0.05 s), none after it
  EXPECT_EQ(a.steps, 1);
  EXPECT_NEAR(a.field_time, 0.05, 1e-12);
  const std::string file = huygens::test::scenes_dir() + "/default.json";
  ASSERT_TRUE(std::filesystem::exists(file)) << file;
  EXPECT_EQ(render_headless(viewer_solver(file), o).image.pixels, a.image.pixels)
      << "built-in default.json vs " << file;
}

// Golden images of the shipped scenes at 256 x 256. Generated once (see tests/golden/README.md):
//   huygens-viz scenes/NAME.json --headless --time 1 --frames 3 --size 256x256 --screenshot tests/golden/NAME.png
// Tolerance: max-abs difference <= 24/255 on any channel, and at most 0.5 % of the pixels
// differing by more than 4/255 (room for a different LLVM/Mesa rounding, not for a changed
// picture). On failure actual/expected/diff PNGs are written next to the test's temp dir.
TEST_F(VizRender, GoldenImagesOfTheShippedScenes) {
  const char* golden_env = std::getenv("HUYGENS_GOLDEN_DIR");  // set by CTest (tests/CMakeLists.txt)
  const std::filesystem::path golden_dir = golden_env && *golden_env ? golden_env : "tests/golden";
  int compared = 0;
  // every shipped scene (checked below: a scene without a golden fails); the SPH scenes at
  // t = 0.1 s (their adaptive step makes 1 s cost a minute of CPU), the others at t = 1 s
  const std::pair<const char*, double> shots[] = {
      {"default", 1.0},       {"ring", 1.0},      {"ocean", 1.0},   {"kelvin", 1.0}, {"pond", 1.0},     {"pool", 0.1},
      {"sph_dam_break", 0.1}, {"dam_break", 1.0}, {"channel", 1.0}, {"flood", 1.0},  {"sph_wedge", 0.1}};
  for (const auto& e : std::filesystem::directory_iterator(huygens::test::scenes_dir())) {
    if (e.path().extension() == ".json") {
      EXPECT_TRUE(std::any_of(std::begin(shots), std::end(shots),
                              [&](const auto& shot) { return e.path().stem() == shot.first; }))
          << e.path() << " is shipped without a golden image";
    }
  }
  for (const auto& [name, t] : shots) {
    const std::filesystem::path scene =
        std::filesystem::path(huygens::test::scenes_dir()) / (std::string(name) + ".json");
    const std::filesystem::path golden = golden_dir / (std::string(name) + ".png");
    if (!std::filesystem::exists(scene)) continue;  // scenes arrive with their solvers
    ASSERT_TRUE(std::filesystem::exists(golden))
        << "missing golden " << golden << "; generate it with\n  huygens-viz " << scene << " --headless --time " << t
        << " --frames 3 --size 256x256 --screenshot " << golden;
    HeadlessOptions o;
    o.time = t;
    o.frames = 3;
    ViewerSolver vs = viewer_solver(scene.string());
    o.settings = view_setup(vs, 1.0).settings;  // as huygens-viz does
    o.flow = !vs.solver->velocity().empty();
    const gl::Image8 actual = render_headless(std::move(vs), o).image;
    const gl::Image8 expected = gl::read_png(golden.string(), 4);
    ASSERT_EQ(actual.width, expected.width);
    ASSERT_EQ(actual.height, expected.height);
    gl::Image8 diff = actual;
    int max_diff = 0;
    long failing = 0;
    for (std::size_t p = 0; p < actual.pixels.size() / 4; ++p) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(actual.pixels[4 * p + c] - expected.pixels[4 * p + c]));
      max_diff = std::max(max_diff, d);
      failing += d > 4;
      for (int c = 0; c < 3; ++c) diff.pixels[4 * p + c] = static_cast<std::uint8_t>(std::min(255, 8 * d));
      diff.pixels[4 * p + 3] = 255;
    }
    const double frac = static_cast<double>(failing) / (actual.pixels.size() / 4);
    std::printf("golden %s: max-abs difference %d/255, %.4f %% of pixels over 4/255\n", name, max_diff, 100 * frac);
    const bool ok = max_diff <= 24 && frac <= 0.005;
    if (!ok) {
      const std::string base = ::testing::TempDir() + "/golden_" + name;
      gl::write_png(base + "_actual.png", actual);
      gl::write_png(base + "_expected.png", expected);
      gl::write_png(base + "_diff.png", diff);
      ADD_FAILURE() << "golden " << name << " differs; wrote " << base << "_{actual,expected,diff}.png";
    }
    ++compared;
  }
  EXPECT_GE(compared, 1) << "no shipped scene to compare";
}

// The real window (GLFW, GLX under Xvfb): 60 frames of a scene, a left click on open water
// halfway (through the mouse handler: a stone command reaches the simulation), then the S
// key's screenshot path and Esc, exit code 0, and a screenshot that is not blank.
TEST(VizWindow, XvfbRunsSixtyFramesAndTakesAScreenshot) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    FAIL() << "xvfb-run is not installed (apt-get install xvfb)";
  std::string scene = huygens::test::scenes_dir() + "/ocean.json";
  if (!std::filesystem::exists(scene)) scene = huygens::test::scenes_dir() + "/default.json";
  const std::string shot = ::testing::TempDir() + "/viz_window_smoke.png";
  std::filesystem::remove(shot);
  const std::string cmd = "xvfb-run -a -s '-screen 0 800x600x24' " + std::string(HUYGENS_VIZ) + " " + scene +
                          " --size 320x240 --auto-frames 60 --screenshot " + shot + " > " + ::testing::TempDir() +
                          "/viz_window_smoke.log 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_EQ(rc, 0) << cmd << "\nlog: " << ::testing::TempDir() << "/viz_window_smoke.log";
  ASSERT_TRUE(std::filesystem::exists(shot));
  // the automation clicked the middle of the window halfway: the stone reached the simulation
  std::ifstream log(::testing::TempDir() + "/viz_window_smoke.log");
  const std::string text((std::istreambuf_iterator<char>(log)), {});
  EXPECT_NE(text.find("stone dropped at"), std::string::npos) << text;
  EXPECT_NE(text.find("commands applied 1,"), std::string::npos) << text;
  const gl::Image8 img = gl::read_png(shot, 4);
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.height, 240);
  double sum = 0, sum2 = 0;
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  for (std::size_t p = 0; p < n; ++p) {
    const double l = (img.pixels[4 * p] + img.pixels[4 * p + 1] + img.pixels[4 * p + 2]) / 3.0;
    sum += l, sum2 += l * l;
  }
  const double var = sum2 / n - (sum / n) * (sum / n);
  std::printf("window screenshot: mean %.1f, variance %.1f (levels^2)\n", sum / n, var);
  EXPECT_GT(var, 25.0) << "the screenshot looks blank";
}

// ---------------------------------------------------------------------------------
// Caustics energy on real solver fields (docs/viz.md "Caustics"): the mean floor light the
// caustics stage gives (as the renderer samples it: texture value x scale(), after its blur),
// still water = 1, against the photon-histogram reference (viz::photon_caustics: exact Snell
// refraction of jittered photons, 3 x 3 per grid cell, weighed by the flux through the tilted
// surface) on the same ground rectangle, over the interior that leaves out the strip lit by
// rays entering outside the field (D tan(theta_t) on the sun's side) plus 8 texels. The
// default path (CausticsMode::conserving) must be within 2 % (issue 15's criterion); the
// paper's modes are printed for docs/viz.md (they are not light-conserving: the MIP trick's
// piecewise-linear levels and the 8-bit target's saturation).
namespace {

struct EnergyRow {
  double mean = 0, reference = 0, clamped = 0, rms = 0;  // rms: texel RMS of (light - conserving) over the mean
  double ms = 0;                                         // one run of the stage, wall time
};

std::vector<float> read_r(GLuint tex, int w, int h) {
  GLuint fb = 0;
  glGenFramebuffers(1, &fb);
  glBindFramebuffer(GL_FRAMEBUFFER, fb);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
  std::vector<float> out(static_cast<std::size_t>(w) * h);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, out.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &fb);
  return out;
}

// The field of `scene_text` (or a shipped scene's file) after its steps up to t_s.
struct SolverField {
  GridPlacement grid;
  std::vector<float> eta;
};
SolverField solver_field(const Scene& scene, double t_s) {
  RunOptions ro;
  ro.measure_plans = false;
  std::unique_ptr<Solver> solver = make_solver(scene, ro);
  const RenderInfo info = solver->render_info();
  while (solver->time() < t_s - 1e-9) solver->step();
  SolverField f;
  f.grid = scene_view(info).grid;
  const auto h = solver->height();
  f.eta.assign(h.begin(), h.end());
  for (float& v : f.eta) v -= static_cast<float>(info.rest_level_m);
  return f;
}

EnergyRow caustic_energy(const SolverField& f, CausticsMode mode, glm::vec3 sun, double depth,
                         std::vector<float>* reference_cache, std::vector<float>* conserving_cache) {
  const std::unique_ptr<CausticsStage> stage = make_caustics_stage(f.grid, -depth);
  RenderSettings s;
  s.caustics_mode = mode;
  s.sun_dir = sun;
  stage->run(f.eta, {}, s);  // the first run builds the mesh and targets; the second is timed
  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  stage->run(f.eta, {}, s);
  glFinish();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const viz::CausticsParams& p = *stage->params();
  const int W = p.texture_width, H = p.texture_height;
  const std::vector<float> raw = read_r(stage->texture(), W, H);
  const viz::HeightfieldView view{f.eta, static_cast<int>(f.grid.rows), static_cast<int>(f.grid.cols),
                                  static_cast<float>(f.grid.dx), static_cast<float>(depth)};
  if (reference_cache->empty()) *reference_cache = viz::photon_caustics(p, view, 3, 11);
  const std::vector<float>& ref = *reference_cache;
  const viz::LinearProjection L = viz::linear_projection(p, depth);
  const viz::GroundRect g = viz::ground_rect(p, view);
  if (mode == CausticsMode::conserving) {
    conserving_cache->resize(raw.size());
    for (std::size_t k = 0; k < raw.size(); ++k) (*conserving_cache)[k] = stage->scale() * raw[k];
  }
  const int bx = 8 + static_cast<int>(std::ceil(std::abs(L.x0) / (g.width / W)));
  const int by = 8 + static_cast<int>(std::ceil(std::abs(L.y0) / (g.height / H)));
  EnergyRow r;
  double n = 0;
  for (int y = by; y < H - by; ++y)
    for (int x = bx; x < W - bx; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * W + x;
      r.mean += stage->scale() * raw[k];
      r.reference += ref[k];
      r.clamped += (!p.float_target && raw[k] >= 254.5f / 255.0f) ? 1.0 : 0.0;
      r.rms += std::pow(stage->scale() * raw[k] - (*conserving_cache)[k], 2.0);
      n += 1;
    }
  r.mean /= n, r.reference /= n, r.clamped /= n;
  r.rms = std::sqrt(r.rms / n) / r.reference;
  r.ms = ms;
  return r;
}

}  // namespace

TEST_F(VizRender, DefaultCausticsConserveLightOnSolverFields) {
  // the paper's Figure 1 set-up: a windy 15 m pool with a boat, floor 3 m down (the viewer's
  // deep-water floor); the shipped ocean and kelvin scenes
  const std::string windy_pool = R"({
    "solver": "huygens",
    "grid": { "n": 256, "length_m": 15.0, "margin": 32 },
    "water": { "gravity_mps2": 9.81, "surface_tension_npm": 0.072, "density_kgpm3": 1000.0, "depth_m": null },
    "time": { "dt_s": 0.05, "display_per_step": 3 },
    "stokes": false,
    "wind": { "speed_mps": 5.0, "direction_deg": 30.0, "seed": 1, "fetch_m": 2000.0, "gamma": 3.3 },
    "ships": [ { "length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
                 "path": [ { "t_s": 0.0, "x_m": 3.0, "y_m": 7.5 }, { "t_s": 10.0, "x_m": 13.0, "y_m": 7.5 } ] } ]
  })";
  const double D = SceneView::kDeepGround;
  const float s30 = std::sin(30.0f * 3.14159265f / 180.0f), c30 = std::cos(30.0f * 3.14159265f / 180.0f);
  struct Case {
    const char* name;
    SolverField field;
    glm::vec3 sun;
  };
  const auto t0 = std::chrono::steady_clock::now();
  const SolverField pool = solver_field(parse_scene_text(windy_pool, "windy_pool"), 3.0);
  const std::string dir = huygens::test::scenes_dir();
  std::vector<Case> cases = {
      {"windy pool, sun overhead", pool, {0.0f, 0.0f, 1.0f}},
      {"windy pool, sun 30 deg", pool, {0.0f, -s30, c30}},
      {"ocean t=2 s, sun 30 deg", solver_field(load_scene(dir + "/ocean.json"), 2.0), {0.0f, -s30, c30}},
      {"kelvin t=5 s, sun 30 deg", solver_field(load_scene(dir + "/kelvin.json"), 5.0), {0.0f, -s30, c30}}};
  std::printf("[ energy ] fields in %.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  const std::pair<CausticsMode, const char*> modes[] = {{CausticsMode::conserving, "conserving (default)"},
                                                        {CausticsMode::mip_paper, "mip_paper"},
                                                        {CausticsMode::mip_float, "mip_float"},
                                                        {CausticsMode::explicit_u8, "explicit_u8"},
                                                        {CausticsMode::simple, "simple (paper 000)"}};
  for (const Case& c : cases) {
    std::vector<float> ref, conserving;
    for (const auto& [mode, mname] : modes) {
      const EnergyRow r = caustic_energy(c.field, mode, c.sun, D, &ref, &conserving);
      std::printf(
          "[ energy ] %-26s %-21s floor light %.4f, photons %.4f, ratio %.4f, texel rms vs conserving %.3f, clamped "
          "%.2f %%, %.1f ms\n",
          c.name, mname, r.mean, r.reference, r.mean / r.reference, r.rms, 100.0 * r.clamped, r.ms);
      if (mode == CausticsMode::conserving) {
        EXPECT_NEAR(r.mean / r.reference, 1.0, 0.02) << c.name;
        EXPECT_EQ(r.clamped, 0.0) << c.name;
      }
    }
  }
}

// Foam (foam.hpp), on a strip 160 points long (dx = 0.25 m, flat bed at 0): a moving bore
// (Rankine-Hugoniot: 1 m of still water ahead, 1.5 m behind, bore speed S = sqrt(g h1 (h1 + h0) /
// (2 h0)) = 4.29 m/s, h u = S (h - h0), a tanh front 0.5 m wide) seeds foam at its front, where
// eta_t / c = S |dh/dx| / c peaks near 0.6, and nowhere in the still water ahead or in the
// subcritical flow behind it (Froude 0.37); still water seeds none. Then the foam is carried
// by a uniform flow of one point per step exactly like the dye's step carries it (a shift) and
// halves every half-life; a steady fast sheet (Froude 10) holds it at f* = r / (lambda + r).
TEST(VizFoam, BoreSeedsStillWaterDoesNotAdvectedLikeTheDyeHalvesInTheHalfLife) {
  GridPlacement g;
  g.rows = 4, g.cols = 160, g.dx = 0.25;
  const std::size_t R = g.rows, C = g.cols, n = R * C;
  const double h0 = 1.0, h1 = 1.5, grav = 9.81, S = std::sqrt(grav * h1 * (h1 + h0) / (2.0 * h0));
  std::vector<float> height(n), u(2 * n, 0.0f);
  FoamField foam(g, {});
  // still water: no seed, no foam
  std::fill(height.begin(), height.end(), static_cast<float>(h0));
  foam.step(height, u, 0.1);
  EXPECT_EQ(*std::max_element(foam.seed().begin(), foam.seed().end()), 0.0f) << "still water";
  EXPECT_EQ(*std::max_element(foam.values().begin(), foam.values().end()), 0.0f) << "still water";
  // the bore, its front at x = 20 m (point 80) moving along +x
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t j = 0; j < C; ++j) {
      const double x = g.x(j), h = h0 + (h1 - h0) * 0.5 * (1.0 - std::tanh((x - 20.0) / 0.5));
      height[i * C + j] = static_cast<float>(h);
      u[2 * (i * C + j)] = static_cast<float>(S * (h - h0) / h);
    }
  foam.step(height, u, 0.05);
  const std::span<const float> row1 = foam.seed().subspan(C, C);
  const auto top = std::max_element(row1.begin(), row1.end());
  EXPECT_GT(*top, 0.5f) << "at the front";
  EXPECT_NEAR(g.x(static_cast<std::size_t>(top - row1.begin())), 20.0, 0.5) << "the seed's peak at the front";
  for (std::size_t j = 0; j < C; ++j) {
    if (std::abs(g.x(j) - 20.0) > 2.5) {
      EXPECT_EQ(row1[j], 0.0f) << "away from the front, point " << j;
    }
  }
  EXPECT_GT(foam.values()[C + 80], 0.2f) << "foam at the front after 0.05 s of seeding";
  // carried: one point per step along +x in still water at rest depth (no seed): the dye's step
  // shifts the pattern, the foam fades by 2^(-dt / half-life) per step
  const std::vector<float> start(foam.values().begin(), foam.values().end());
  std::fill(height.begin(), height.end(), static_cast<float>(h0));
  const double dt = 0.25, half = foam.params().half_life_s;
  for (std::size_t k = 0; k < 2 * n; k += 2) u[k] = static_cast<float>(g.dx / dt), u[k + 1] = 0.0f;
  std::vector<float> dyed = start, next(n);
  const int steps = static_cast<int>(std::lround(half / dt));  // exactly one half-life
  ASSERT_DOUBLE_EQ(steps * dt, half);
  for (int k = 0; k < steps; ++k) {
    foam.step(height, u, dt);
    advect_semi_lagrangian(g, u, dt, dyed, next);
    dyed.swap(next);
  }
  EXPECT_EQ(*std::max_element(foam.seed().begin(), foam.seed().end()), 0.0f) << "Froude 0.32, no seed";
  for (std::size_t k = 0; k < n; ++k) EXPECT_NEAR(foam.values()[k], 0.5f * dyed[k], 1e-6f) << "point " << k;
  for (std::size_t j = static_cast<std::size_t>(steps); j < C; ++j)
    EXPECT_NEAR(foam.values()[C + j], 0.5f * start[C + j - steps], 1e-6f) << "shifted by " << steps << ", point " << j;
  // a steady sheet at Froude 10 (over froude_full): f* = r / (lambda + r) everywhere
  ASSERT_LT(foam.params().froude_full, 10.0);
  for (std::size_t k = 0; k < 2 * n; k += 2) u[k] = static_cast<float>(10.0 * std::sqrt(grav * h0));
  for (int k = 0; k < 100; ++k) foam.step(height, u, 0.1);
  const double lambda = std::log(2.0) / half, r = 1.0 / foam.params().seed_time_s;
  for (std::size_t k = 0; k < n; ++k) EXPECT_NEAR(foam.values()[k], r / (lambda + r), 1e-5) << "point " << k;
}

// Foam behind an obstacle (foam.hpp's shear seed): a shear layer u = U tanh(y / delta) (U =
// 0.3 m/s, delta = 2 cm, 0.1 m deep: |omega| sqrt(h / g) = 1.5 at y = 0, Froude 0.3) seeds along
// its middle and not in the uniform flow on either side.
TEST(VizFoam, ShearLayerSeeds) {
  GridPlacement g;
  g.rows = 40, g.cols = 10, g.dx = 0.01;
  const std::size_t R = g.rows, C = g.cols;
  std::vector<float> height(R * C, 0.1f), u(2 * R * C, 0.0f);
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t j = 0; j < C; ++j) u[2 * (i * C + j)] = static_cast<float>(0.3 * std::tanh((g.y(i) - 0.2) / 0.02));
  FoamField foam(g, {});
  foam.step(height, u, 0.01);
  EXPECT_EQ(foam.seed()[20 * C + 5], 1.0f) << "in the shear layer";
  EXPECT_EQ(foam.seed()[3 * C + 5], 0.0f) << "in the uniform flow";
  EXPECT_EQ(foam.seed()[37 * C + 5], 0.0f) << "in the uniform flow";
}

// Dye (dye.hpp): a uniform flow of exactly one grid point per step along x moves the bands
// (and any pattern) one point downstream, the inflow edge keeps its value; no flow changes
// nothing; the LBM channel's frames carry the solver's velocity (Frame::velocity) into the dye.
TEST(VizDye, UniformFlowShiftsThePatternAndTheChannelCarriesVelocity) {
  GridPlacement g;
  g.rows = 20, g.cols = 30, g.dx = 0.1;
  DyeField dye(g, 4);
  const std::vector<float> start(dye.values().begin(), dye.values().end());
  EXPECT_EQ(start[0], 0.0f);
  EXPECT_EQ(start[5 * 30], 1.0f) << "the second band";
  std::vector<float> u(2 * 20 * 30, 0.0f);
  dye.advect(u, 0.5);
  EXPECT_EQ(std::vector<float>(dye.values().begin(), dye.values().end()), start) << "no flow";
  // a diagonal pattern, then one point per step along x: c'(i, j) = c(i, j - 1), c'(i, 0) = c(i, 0)
  for (std::size_t k = 0; k < 2 * 20 * 30; k += 2) u[k] = 0.2f;  // 0.2 m/s x 0.5 s = 1 point
  for (int step = 0; step < 3; ++step) dye.advect(u, 0.5);
  for (std::size_t i = 0; i < 20; ++i) EXPECT_EQ(dye.values()[i * 30 + 29], start[i * 30]) << "row " << i;
  // the channel: velocity in every frame, the inflow's 0.297 m/s at the left edge
  ViewerSolver vs = viewer_solver("channel");
  ASSERT_FALSE(vs.solver->velocity().empty());
  RunnerParams rp;
  rp.manual_clock = true;
  const std::size_t n = vs.info.grid.rows * vs.info.grid.cols;
  Runner runner(std::move(vs.solver), rp);
  runner.start();
  runner.show(0.05);
  ASSERT_TRUE(runner.wait_shown());
  std::vector<float> vel(2 * n);
  ASSERT_TRUE(runner.frames().velocity(vel));
  EXPECT_NEAR(vel[2 * (80 * 320 + 2)], 0.297, 0.03) << "u at the inflow";
  runner.stop();
}
