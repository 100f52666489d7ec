// One-way data into a viewer (render_info.hpp, runner.hpp): what each solver's RenderInfo says
// about its scene, the Huygens solver's run-time toggles (Stokes off gives the first-order height,
// a wind toggle without a wind sea is refused), the runner reporting a refused command back, and
// the runner's manual clock publishing exactly the steps at or before the display time.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "huygens/pipeline/render_request.hpp"
#include "huygens/pipeline/runner.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"
#include "huygens/spectral/spectral_solver.hpp"
#include "scenes_dir.hpp"

using namespace huygens;

namespace {

// A steep plane wave (k A = 0.13) on a small deep-water grid: eq. 3's second-order term is about
// 6 % of the first-order height, far above float rounding.
std::string wave_scene(bool stokes, bool wind) {
  return std::string(R"({"solver": "huygens", "grid": {"n": 64, "length_m": 6.4, "margin": 8},
    "time": {"dt_s": 0.05, "display_per_step": 3}, "stokes": )") +
         (stokes ? "true" : "false") +
         (wind ? R"(, "wind": {"speed_mps": 5.0, "direction_deg": 10.0, "seed": 7, "fetch_m": 5000.0})" : "") +
         R"(, "initial": [{"type": "plane_wave", "wavelength_m": 1.0, "amplitude_m": 0.02, "direction_deg": 0}]})";
}

std::unique_ptr<Solver> make(const std::string& text) {
  RunOptions ro;
  ro.measure_plans = false;
  return make_solver(parse_scene_text(text), ro);
}

std::vector<float> height_of(Solver& s) {
  const auto h = s.height();
  return {h.begin(), h.end()};
}

double max_abs_diff(std::span<const float> a, std::span<const float> b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(double(a[i]) - double(b[i])));
  return d;
}

double max_abs(std::span<const float> a) {
  double m = 0.0;
  for (float v : a) m = std::max(m, std::abs(double(v)));
  return m;
}

void step(Solver& s, int n) {
  for (int i = 0; i < n; ++i) s.step();
}

}  // namespace

// Toggling Stokes off makes the height the first-order height of a solver built without Stokes
// (paper 004 eq. 3 without its chi^2 term), and it stays so over further steps; toggling it on
// again gives back the second-order height bit for bit.
TEST(HuygensToggle, StokesOffGivesTheFirstOrderHeight) {
  auto second = make(wave_scene(true, false)), first = make(wave_scene(false, false));
  auto reference = make(wave_scene(true, false));
  step(*second, 10), step(*first, 10), step(*reference, 10);
  const std::vector<float> h1 = height_of(*first);
  const double scale = max_abs(h1);
  ASSERT_GT(scale, 0.01);
  EXPECT_GT(max_abs_diff(height_of(*second), h1), 0.03 * scale) << "eq. 3's second-order term is visible";
  ASSERT_TRUE(second->apply(cmd::Toggle{CommandName{"stokes"}, false}));
  EXPECT_LT(max_abs_diff(height_of(*second), h1), 1e-5 * scale);
  EXPECT_LT(max_abs_diff(second->height_rate(), first->height_rate()), 1e-5 * max_abs(first->height_rate()));
  step(*second, 5), step(*first, 5), step(*reference, 5);
  EXPECT_LT(max_abs_diff(height_of(*second), height_of(*first)), 1e-5 * scale) << "after 5 more steps";
  EXPECT_FALSE(second->render_info().toggles.at(0).on);
  ASSERT_TRUE(second->apply(cmd::Toggle{CommandName{"stokes"}, true}));
  EXPECT_EQ(height_of(*second), height_of(*reference)) << "back on: the scene's own second-order height";
}

// A scene without Stokes switches it on at run time (its height stage is made then) and matches a
// scene that had it from the start; off again, it is the propagator's own height once more.
TEST(HuygensToggle, StokesOnInASceneWithoutIt) {
  auto plain = make(wave_scene(false, false)), stokes = make(wave_scene(true, false));
  step(*plain, 4), step(*stokes, 4);
  const std::vector<float> before = height_of(*plain);
  ASSERT_TRUE(plain->apply(cmd::Toggle{CommandName{"stokes"}, true}));
  const double scale = max_abs(before);
  EXPECT_LT(max_abs_diff(height_of(*plain), height_of(*stokes)), 1e-5 * scale);
  step(*plain, 3), step(*stokes, 3);
  EXPECT_LT(max_abs_diff(height_of(*plain), height_of(*stokes)), 1e-5 * scale);
  auto again = make(wave_scene(false, false));
  step(*again, 7);
  ASSERT_TRUE(plain->apply(cmd::Toggle{CommandName{"stokes"}, false}));
  EXPECT_EQ(height_of(*plain), height_of(*again));
}

// "wind" is refused without a wind sea (nothing is allocated for it) and not offered; with one,
// switching it off leaves the sea out of the height (the plane wave alone), on brings it back.
TEST(HuygensToggle, WindIsRefusedWithoutAWindSeaAndSwitchesOneOff) {
  auto calm = make(wave_scene(false, false));
  EXPECT_FALSE(calm->apply(cmd::Toggle{CommandName{"wind"}, true}));
  EXPECT_FALSE(calm->apply(cmd::Toggle{CommandName{"wind"}, false}));
  EXPECT_FALSE(calm->apply(cmd::Toggle{CommandName{"foam"}, true}));
  const RenderInfo calm_info = calm->render_info();
  ASSERT_EQ(calm_info.toggles.size(), 1u);
  EXPECT_EQ(calm_info.toggles[0].name, "stokes");

  auto windy = make(wave_scene(false, true));
  const RenderInfo info = windy->render_info();
  ASSERT_EQ(info.toggles.size(), 2u);
  EXPECT_EQ(info.toggles[1].name, "wind");
  EXPECT_TRUE(info.toggles[1].on);
  step(*windy, 6), step(*calm, 6);
  const double scale = max_abs(height_of(*calm));
  EXPECT_GT(max_abs_diff(height_of(*windy), height_of(*calm)), 1e-3 * scale) << "the sea is there";
  const std::vector<float> with_sea = height_of(*windy);
  ASSERT_TRUE(windy->apply(cmd::Toggle{CommandName{"wind"}, false}));
  EXPECT_LT(max_abs_diff(height_of(*windy), height_of(*calm)), 1e-5 * scale) << "wind off: the plane wave alone";
  ASSERT_TRUE(windy->apply(cmd::Toggle{CommandName{"wind"}, true}));
  EXPECT_EQ(height_of(*windy), with_sea);
}

// The runner hands a refused command back to the UI (next_refused) and counts it; an accepted one
// is not handed back.
TEST(RunnerRefused, ARefusedToggleIsReportedBack) {
  RunnerParams rp;
  rp.realtime = false;
  rp.start_paused = true;
  Runner runner(make(wave_scene(false, false)), rp);
  runner.start();
  ASSERT_TRUE(runner.send(cmd::Toggle{CommandName{"wind"}, true}));
  ASSERT_TRUE(runner.send(cmd::Toggle{CommandName{"stokes"}, true}));
  ASSERT_TRUE(runner.send(cmd::StepOnce{}));
  for (int i = 0; i < 20000 && runner.commands_applied() + runner.commands_rejected() < 3; ++i)
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  runner.stop();
  EXPECT_EQ(runner.commands_rejected(), 1u);
  EXPECT_EQ(runner.commands_applied(), 2u);
  Command c;
  ASSERT_TRUE(runner.next_refused(c));
  const auto* t = std::get_if<cmd::Toggle>(&c);
  ASSERT_NE(t, nullptr);
  EXPECT_TRUE(t->feature == "wind");
  EXPECT_TRUE(t->on);
  EXPECT_FALSE(runner.next_refused(c)) << "only the refused one comes back";
}

// The manual clock publishes no step after the display time: after show(T) the newest frame is
// the last full step at or before T, the one before it the step before that, and the display time is T.
TEST(RunnerManualClock, PublishesExactlyTheStepsAtOrBeforeTheDisplayTime) {
  RunnerParams rp;
  rp.manual_clock = true;
  Runner runner(make(wave_scene(false, false)), rp);  // dt = 0.05 s
  runner.start();
  for (const auto& [t, steps] : {std::pair{0.0, 0}, std::pair{0.049, 0}, std::pair{0.05, 1}, std::pair{0.1, 2},
                                 std::pair{0.31, 6}, std::pair{1.0, 20}}) {
    runner.show(t);
    ASSERT_TRUE(runner.wait_shown(60.0)) << t;
    const FramePair fp = runner.frames();
    ASSERT_TRUE(fp);
    EXPECT_EQ(fp.newest->info.step, steps) << "display time " << t;
    EXPECT_EQ(runner.display_time(), t);
    ASSERT_TRUE(fp.prev || steps == 0);
    if (steps > 0) {
      EXPECT_EQ(fp.prev->info.step, steps - 1) << "the step before it: the interpolation's other end";
    }
    EXPECT_LE(runner.frames_published(), static_cast<std::uint64_t>(steps) + 1) << "none ahead";
  }
  runner.stop();
  EXPECT_FALSE(runner.failed());
}

// What the viewer is told about the shipped Huygens scenes: the visible region, depth, hulls,
// display rate and the render block, as the scene file says (no JSON read by the viewer).
TEST(RenderInfo, HuygensScenesAsTheirFilesSay) {
  const std::string dir = huygens::test::scenes_dir();
  ASSERT_TRUE(std::filesystem::exists(dir + "/ocean.json")) << dir;
  RunOptions ro;
  ro.measure_plans = false;
  auto ocean = make_solver(load_scene(dir + "/ocean.json"), ro);
  const RenderInfo o = ocean->render_info();
  EXPECT_EQ(o.grid.rows, 448u);
  EXPECT_EQ(o.grid.cols, 448u);
  EXPECT_DOUBLE_EQ(o.grid.dx_m, 100.0 / 512);
  EXPECT_DOUBLE_EQ(o.grid.x0_m, 32 * 100.0 / 512);
  EXPECT_DOUBLE_EQ(o.grid.y0_m, 32 * 100.0 / 512);
  EXPECT_FALSE(o.depth_m.has_value()) << "deep water";
  ASSERT_EQ(o.hulls.size(), 1u);
  EXPECT_EQ(o.hulls[0].length_m, 8.0);
  EXPECT_EQ(o.hulls[0].beam_m, 2.0);
  EXPECT_EQ(o.hulls[0].draft_m, 0.4);
  EXPECT_EQ(o.display_per_step, 3);
  EXPECT_DOUBLE_EQ(o.frame_dt_s, 0.05 / 3);
  ASSERT_TRUE(o.request.caustics.has_value());
  EXPECT_FALSE(*o.request.caustics);
  EXPECT_FALSE(o.request.blur.has_value());
  ASSERT_EQ(o.toggles.size(), 2u);
  EXPECT_TRUE(o.toggles[0].on) << "the scene has Stokes";
  EXPECT_EQ(o.rest_level_m, 0.0);

  const std::string pool = R"({"solver": "huygens", "grid": {"n": 64, "length_m": 2.0, "margin": 4},
    "water": {"depth_m": 0.5}, "time": {"dt_s": 0.02}, "render": {"blur": "float"}})";
  const RenderInfo p = make(pool)->render_info();
  ASSERT_TRUE(p.depth_m.has_value());
  EXPECT_EQ(*p.depth_m, 0.5);
  EXPECT_EQ(p.display_per_step, 1);
  EXPECT_DOUBLE_EQ(p.frame_dt_s, 0.02);
  ASSERT_TRUE(p.request.blur.has_value());
  EXPECT_EQ(*p.request.blur, BlurMode::float_target);
  EXPECT_THROW(make(R"({"solver": "huygens", "grid": {"n": 64, "length_m": 2.0, "margin": 4},
    "time": {"dt_s": 0.02}, "render": {"blur": "gaussian"}})"),
               SceneError);
}

// The LBM and SPH adapters: cell centres, the rest level (mean initial height above the floor),
// the obstacles as shapes with units, the display rate; no run-time toggles.
TEST(RenderInfo, LbmAndSphScenesAsTheirFilesSay) {
  const std::string dir = huygens::test::scenes_dir();
  RunOptions ro;
  ro.measure_plans = false;
  auto channel = make_solver(load_scene(dir + "/channel.json"), ro);
  const RenderInfo c = channel->render_info();
  EXPECT_EQ(c.grid.rows, 160u);
  EXPECT_EQ(c.grid.cols, 320u);
  EXPECT_DOUBLE_EQ(c.grid.dx_m, 0.01);
  EXPECT_DOUBLE_EQ(c.grid.x0_m, 0.005) << "cell centres";
  EXPECT_NEAR(c.rest_level_m, 0.1, 0.002) << "0.1 m deep, the cylinder's cells dry";
  ASSERT_TRUE(c.depth_m.has_value());
  EXPECT_EQ(c.bed_m.size(), 160u * 320u);
  ASSERT_EQ(c.obstacles.size(), 1u);
  EXPECT_EQ(c.obstacles[0].kind, RenderObstacle::Kind::cylinder);
  EXPECT_DOUBLE_EQ(c.obstacles[0].centre_m[0], 0.8);
  EXPECT_DOUBLE_EQ(c.obstacles[0].centre_m[1], 0.805);
  EXPECT_DOUBLE_EQ(c.obstacles[0].radius_m, 0.08);
  EXPECT_TRUE(std::isinf(c.obstacles[0].z1_m)) << "through the whole water column";
  EXPECT_DOUBLE_EQ(c.dt_s, 0.00403855);
  EXPECT_DOUBLE_EQ(c.frame_dt_s, 0.00403855);
  EXPECT_TRUE(c.toggles.empty());
  EXPECT_FALSE(channel->apply(cmd::Toggle{CommandName{"stokes"}, true})) << "no control, and refused";

  auto pool = make_solver(load_scene(dir + "/pool.json"), ro);
  const RenderInfo p = pool->render_info();
  EXPECT_NEAR(p.grid.dx_m, 0.005, 1e-9) << "float parameters";
  EXPECT_NEAR(p.grid.x0_m, 0.0025, 1e-9);
  // mean of the extracted field: 0.075 m of fill over the pool less the cylinder's dry columns
  // (pi 0.025^2 / 0.2^2 of the area), within half a particle spacing (the iso-surface's reach)
  EXPECT_NEAR(p.rest_level_m, 0.075 * (1.0 - std::numbers::pi * 0.025 * 0.025 / 0.04), 0.005);
  ASSERT_EQ(p.obstacles.size(), 1u);
  EXPECT_EQ(p.obstacles[0].kind, RenderObstacle::Kind::cylinder);
  EXPECT_NEAR(p.obstacles[0].radius_m, 0.025, 1e-8);
  EXPECT_NEAR(p.obstacles[0].z1_m, 0.15, 1e-7);
  EXPECT_EQ(p.dt_s, 0.0) << "adaptive step";
  EXPECT_DOUBLE_EQ(p.frame_dt_s, 1.0 / 60.0);
  EXPECT_TRUE(p.toggles.empty());
}

// The "render" block's viewer keys (docs/viz.md "Looks"): look, view, camera, sun, foam and
// caustics_mode are read with their ranges; an unknown key, in the block or in its objects, is
// refused with its JSON path (the SI-suffix convention of docs/design.md 6).
TEST(RenderRequest, ViewerKeysAndUnknownKeysRefused) {
  auto parse = [](const std::string& text) {
    const nlohmann::json j = nlohmann::json::parse(text);
    return parse_render_request(JsonIn(j, "$"));
  };
  const RenderRequest r = parse(R"({"render": {"look": "shallow", "view": "plan", "caustics_mode": "mip_paper",
      "camera": {"target_m": [1, 2, 0], "distance_m": 12, "yaw_deg": -90, "pitch_deg": 55, "follow_ship": false},
      "sun": {"elevation_deg": 40, "azimuth_deg": 180}, "foam": false}})");
  ASSERT_TRUE(r.look.has_value());
  EXPECT_EQ(*r.look, LookRequest::shallow);
  EXPECT_TRUE(r.plan_view.value_or(false));
  EXPECT_EQ(r.caustics_mode.value_or(CausticsModeRequest::conserving), CausticsModeRequest::mip_paper);
  ASSERT_TRUE(r.camera.target_m.has_value());
  EXPECT_EQ((*r.camera.target_m)[1], 2.0);
  EXPECT_EQ(r.camera.distance_m.value_or(0.0), 12.0);
  EXPECT_EQ(r.camera.yaw_deg.value_or(0.0), -90.0);
  EXPECT_EQ(r.camera.pitch_deg.value_or(0.0), 55.0);
  EXPECT_FALSE(r.camera.follow_ship.value_or(true));
  EXPECT_EQ(r.sun_elevation_deg.value_or(0.0), 40.0);
  EXPECT_EQ(r.sun_azimuth_deg.value_or(0.0), 180.0);
  EXPECT_FALSE(r.foam.value_or(true));
  const RenderRequest none = parse(R"({"solver": "huygens"})");
  EXPECT_FALSE(none.look.has_value() || none.plan_view.has_value() || none.camera.distance_m.has_value() ||
               none.foam.has_value());
  auto refused = [&](const std::string& text, const std::string& path) {
    try {
      parse(text);
      ADD_FAILURE() << "accepted " << text;
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  };
  refused(R"({"render": {"looks": "pool"}})", "$.render");
  refused(R"({"render": {"look": "lake"}})", "$.render.look");
  refused(R"({"render": {"view": "side"}})", "$.render.view");
  refused(R"({"render": {"camera": {"distance": 3}}})", "$.render.camera");
  refused(R"({"render": {"camera": {"pitch_deg": 120}}})", "$.render.camera.pitch_deg");
  refused(R"({"render": {"sun": {"elevation_deg": 40, "zenith_deg": 3}}})", "$.render.sun");
  refused(R"({"render": {"caustics_mode": "photons"}})", "$.render.caustics_mode");
  refused(R"({"render": {"foam": "white"}})", "$.render.foam");
}
