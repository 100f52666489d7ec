// The "huygens" scene solver: drop scheduling with exact sub-step timing, UI drops through
// Solver::apply, outputs and the per-stage counters.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "huygens/solvers/registry.hpp"
#include "huygens/spectral/spectral_solver.hpp"
#include "scenes_dir.hpp"

using namespace huygens;

namespace {
std::unique_ptr<Solver> build(const std::string& extra, const std::string& time = R"({"dt_s": 0.02})") {
  const std::string text =
      R"({"solver": "huygens", "grid": {"n": 64, "length_m": 2.0, "margin": 0, "cutoff": false}, "time": )" + time +
      extra + "}";
  return make_solver(parse_scene_text(text), RunOptions{false});
}
}  // namespace

// A drop at t = 0.05 s with dt = 0.02 s enters in step 3 (t = 0.06 s) with 0.01 s of phase: after
// 5 steps it equals a drop at rest propagated exactly for 0.05 s.
TEST(HuygensSolver, DropsEnterWithExactSubStepTiming) {
  auto solver = build(R"(, "drops": [{"t_s": 0.05, "x_m": 1.0, "y_m": 0.8, "radius_m": 0.08, "depth_m": 0.01}])");
  for (int i = 0; i < 5; ++i) solver->step();
  HuygensParams p;
  p.n = 64;
  p.length_m = 2.0;
  p.margin = 0;
  p.absorber = Absorber::off;
  p.dt_s = 0.05;
  p.effort = PlanEffort::estimate;
  HuygensPropagator ref(p);
  ref.add_gaussian(1.0, 0.8, 0.08, -0.01);
  ref.step();
  const auto a = solver->height(), b = ref.eta();
  ASSERT_EQ(a.size(), b.size());
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    err = std::max(err, double(std::abs(a[i] - b[i])));
    scale = std::max(scale, double(std::abs(b[i])));
  }
  EXPECT_GT(scale, 1e-3);
  EXPECT_LT(err, 1e-5 * scale);
  const auto& st = solver->stats();
  EXPECT_EQ(st[st.find("drops")].calls, 1u);
  EXPECT_EQ(st[st.find("drops")].bytes, 2u * 64 * 64 * sizeof(float)) << "timed drops: tables made up front";
}

TEST(HuygensSolver, UiDropIsAppliedBetweenSteps) {
  auto solver = build("");
  solver->step();
  double before = 0;
  for (float v : solver->height()) before = std::max(before, double(std::abs(v)));
  EXPECT_EQ(before, 0.0);
  // a scene without timed drops owns no source tables until the first UI drop
  const int drops = solver->stats().find("drops");
  ASSERT_GE(drops, 0);
  EXPECT_EQ(solver->stats()[drops].bytes, 0u);
  EXPECT_TRUE(solver->apply(Command{cmd::Drop{1.0f, 1.0f, 0.05f, 0.01f}}));
  EXPECT_EQ(solver->stats()[drops].bytes, 2u * 64 * 64 * sizeof(float)) << "-omega/k and omega per mode";
  double after = 0;
  for (float v : solver->height()) after = std::min(after, double(v));
  EXPECT_NEAR(after, -0.01, 1e-3);  // the depression is in the height at once
  EXPECT_EQ(solver->height_rate().size(), solver->height().size());
  EXPECT_FALSE(solver->apply(Command{cmd::Pause{}}));
  EXPECT_FALSE(solver->apply(Command{cmd::Drop{5.0f, 1.0f, 0.05f, 0.01f}}));  // outside the grid
}

TEST(HuygensSolver, OutputsAreTheVisibleRegion) {
  auto solver = make_solver(parse_scene_text(R"({"solver": "huygens", "grid": {"n": 64, "length_m": 2.0, "margin": 8},
      "time": {"dt_s": 0.02, "display_per_step": 3}})"),
                            RunOptions{false});
  const auto out = solver->outputs();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].name, "eta");
  EXPECT_EQ(out[0].shape, (std::vector<std::size_t>{48, 48}));
  const auto meta = solver->meta();
  EXPECT_EQ(meta["display_per_step"], 3);
  EXPECT_EQ(meta["round_trip_every"], 3);  // auto_round_trip_every of this grid and step
  EXPECT_DOUBLE_EQ(meta["transforms_per_step"].get<double>(), 1.0 + 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(meta["dx"].get<double>(), 2.0 / 64);
}

// Issue 3 integration: each feature a scene does not name costs nothing (no stage registered),
// and the stages that exist make exactly the transforms the features need.
TEST(HuygensSolver, FeaturesRegisterOnlyTheirStagesAndTransforms) {
  auto stage = [](const Solver& s, const std::string& name) -> const StageStat* {
    for (const auto& st : s.stats().all())
      if (st.name == name) return &st;
    return nullptr;
  };
  const std::string ship = R"(, "ships": [{"length_m": 0.2, "beam_m": 0.06, "draft_m": 0.01,
      "path": [{"t_s": 0, "x_m": 0.5, "y_m": 1.0}, {"t_s": 2, "x_m": 1.5, "y_m": 1.0}]}])";
  const std::string wind = R"(, "wind": {"speed_mps": 3, "direction_deg": 0, "seed": 7})";
  auto plain = build("");
  auto full = build(R"(, "stokes": true)" + ship + wind);
  auto first = build(wind);
  for (int i = 0; i < 4; ++i) plain->step(), full->step(), first->step();
  for (const char* name : {"ships", "wind", "height_stokes", "height_wind", "spectrum"})
    EXPECT_EQ(stage(*plain, name), nullptr) << name;
  ASSERT_NE(stage(*plain, "height"), nullptr);
  EXPECT_EQ(stage(*plain, "height")->transforms, 4u);     // periodic, no ships: 1 transform per step
  EXPECT_EQ(stage(*plain, "propagate")->transforms, 0u);  // spectral rotation only
  ASSERT_NE(stage(*full, "ships"), nullptr);
  ASSERT_NE(stage(*full, "wind"), nullptr);
  ASSERT_NE(stage(*full, "height_stokes"), nullptr);
  EXPECT_EQ(stage(*full, "ships")->calls, 4u);
  EXPECT_EQ(stage(*full, "height_stokes")->transforms, 12u);  // 3 per step (second order)
  EXPECT_EQ(stage(*full, "propagate")->transforms, 4u);       // ships force the round trip
  EXPECT_EQ(stage(*full, "spectrum")->transforms, 4u);
  EXPECT_EQ(stage(*full, "height"), nullptr);  // the propagator's own height is not made
  EXPECT_EQ(stage(*first, "height"), nullptr);
  EXPECT_EQ(full->meta()["transforms_per_step"], 5);
  ASSERT_NE(stage(*first, "height_wind"), nullptr);
  EXPECT_EQ(stage(*first, "height_wind")->transforms, 4u);  // first order with the sea: 1 per step
  EXPECT_EQ(first->meta()["transforms_per_step"], 1);
  // the ship made waves, the wind sea is there
  double e = 0, w = 0;
  for (float v : full->height()) e = std::max(e, double(std::abs(v)));
  for (float v : first->height()) w = std::max(w, double(std::abs(v)));
  EXPECT_GT(e, 0.0);
  EXPECT_GT(w, 0.0);
}

// Displayed frames: j = 0 is the full step; j = 1..D-1 are the cubic Hermite interpolants between
// the previous and the current full step (at s = 0 and 1 they would be the end frames exactly).
TEST(HuygensSolver, DisplayFramesInterpolateBetweenFullSteps) {
  auto s = build(R"(, "initial": [{"type": "gaussian", "x_m": 1.0, "y_m": 1.0, "sigma_m": 0.1, "amplitude_m": 0.01}])",
                 R"({"dt_s": 0.02, "display_per_step": 3})");
  EXPECT_EQ(s->display_per_step(), 3);
  EXPECT_TRUE(s->display_outputs(1).empty());  // no step yet: nothing to interpolate
  const std::vector<float> e0(s->height().begin(), s->height().end());
  const std::vector<float> d0(s->height_rate().begin(), s->height_rate().end());
  s->step();
  const auto f = s->display_outputs(1);
  ASSERT_EQ(f.size(), 1u);
  const auto e1 = s->height(), d1 = s->height_rate();
  const double dt = 0.02;
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < e1.size(); ++i) {
    const double expect = 20.0 / 27 * e0[i] + 7.0 / 27 * e1[i] + dt * (4.0 / 27 * d0[i] - 2.0 / 27 * d1[i]);
    err = std::max(err, std::abs(f[0].data[i] - expect));
    scale = std::max(scale, double(std::abs(e1[i])));
  }
  EXPECT_LT(err, 1e-6 * scale);
  EXPECT_EQ(s->display_outputs(0)[0].data.data(), s->height().data());
}

// ---------------------------------------------------------------- ship steering (cmd::ShipTarget)

namespace {

const char* kShipScene = R"({"solver": "huygens", "grid": {"n": 128, "length_m": 16.0, "margin": 8},
    "time": {"dt_s": 0.05},
    "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
               "path": [{"t_s": 0, "x_m": 4.0, "y_m": 8.0}, {"t_s": 8, "x_m": 12.0, "y_m": 8.0}]}]})";

/// Sum of eta^2 over the visible cells within `radius` of (x, y) (unit: m^2 per cell).
double energy_near(Solver& s, double x, double y, double radius) {
  const auto eta = s.height();
  const std::size_t v = s.height_cols();
  const double dx = 16.0 / 128, x0 = 8 * dx;
  double e = 0;
  for (std::size_t r = 0; r < v; ++r)
    for (std::size_t c = 0; c < v; ++c)
      if (std::hypot(x0 + c * dx - x, x0 + r * dx - y) < radius) e += double(eta[r * v + c]) * eta[r * v + c];
  return e;
}

ShipState pose_of(const Solver& s) {
  std::array<ShipState, kMaxFrameShips> p{};
  EXPECT_EQ(s.ship_poses(p), 1u);
  return p[0];
}

}  // namespace

// A ShipTarget between steps takes the ship off its scripted path: the solver's pose follows
// ShipWaves' steering law (the same ship steered directly at the same time), the scripted
// position is no longer where the ship is, and the wake follows the new track: energy appears
// around the steered ship and not where the path would have taken it.
TEST(HuygensSolver, ShipTargetSteersTheShipAndItsWake) {
  auto steered = make_solver(parse_scene_text(kShipScene), RunOptions{false});
  auto scripted = make_solver(parse_scene_text(kShipScene), RunOptions{false});
  const HuygensScene sc = parse_huygens_scene(parse_scene_text(kShipScene), RunOptions{false});
  ShipWaves ref(sc.params.water, 128, 16.0, sc.ship_patch, sc.ships, PlanEffort::estimate);
  std::vector<cfloat> z(128 * 128);
  const double dt = 0.05;
  for (int i = 0; i < 20; ++i) {
    steered->step(), scripted->step();
    ref.add(z.data(), i * dt, dt);
  }
  EXPECT_NEAR(pose_of(*steered).x_m, 5.0, 1e-9);  // on its path: 1 m/s along +x
  EXPECT_NEAR(pose_of(*steered).speed_mps, 1.0, 1e-9);
  ASSERT_TRUE(steered->apply(Command{cmd::ShipTarget{0, 5.0f, 13.0f, 0.0f, 0.0f}}));
  ASSERT_TRUE(ref.steer(0, 20 * dt, 5.0, 13.0, 0.0, 0.0));
  for (int i = 20; i < 80; ++i) {
    steered->step(), scripted->step();
    ref.add(z.data(), i * dt, dt);
  }
  const ShipState p = pose_of(*steered), q = pose_of(*scripted);
  const ShipPoseNow r = ref.pose(0, 80 * dt);
  EXPECT_NEAR(p.x_m, r.x_m, 1e-9);
  EXPECT_NEAR(p.y_m, r.y_m, 1e-9);
  EXPECT_NEAR(p.heading_rad, r.heading_rad, 1e-12);
  EXPECT_NEAR(p.speed_mps, r.speed_mps, 1e-12);
  EXPECT_GT(p.y_m, 10.0) << "heads for y = 13";
  EXPECT_NEAR(p.x_m, 5.0, 0.7);
  EXPECT_NEAR(q.x_m, 8.0, 1e-9);  // the unsteered twin is where the path says
  EXPECT_NEAR(q.y_m, 8.0, 1e-9);
  // the wake follows the ship
  const double near_new = energy_near(*steered, p.x_m, p.y_m, 1.5);
  const double at_old = energy_near(*steered, 8.0, 8.0, 1.5);
  const double twin_at_old = energy_near(*scripted, 8.0, 8.0, 1.5);
  std::printf("energy near the steered ship %.3g, at the scripted position %.3g (twin there %.3g)\n", near_new, at_old,
              twin_at_old);
  EXPECT_GT(near_new, 10.0 * at_old);
  EXPECT_LT(at_old, 0.1 * twin_at_old);
  EXPECT_GT(near_new, 0.1 * twin_at_old);
}

TEST(HuygensSolver, ShipTargetRefusesInvalidCommands) {
  auto s = make_solver(parse_scene_text(kShipScene), RunOptions{false});
  const float nan = std::nanf(""), inf = INFINITY;
  EXPECT_FALSE(s->apply(Command{cmd::ShipTarget{1, 5.0f, 5.0f, 0.0f, 0.0f}}));   // one ship only
  EXPECT_FALSE(s->apply(Command{cmd::ShipTarget{-1, 5.0f, 5.0f, 0.0f, 0.0f}}));  // no such ship
  EXPECT_FALSE(s->apply(Command{cmd::ShipTarget{0, nan, 5.0f, 0.0f, 0.0f}}));
  EXPECT_FALSE(s->apply(Command{cmd::ShipTarget{0, 5.0f, 5.0f, inf, 0.0f}}));
  EXPECT_FALSE(s->apply(Command{cmd::ShipTarget{0, 5.0f, 20.0f, 0.0f, 0.0f}}));  // outside the 16 m grid
  s->step();
  EXPECT_NEAR(pose_of(*s).x_m, 4.05, 1e-9) << "refused commands leave the path alone";
  auto calm = build("");
  EXPECT_FALSE(calm->apply(Command{cmd::ShipTarget{0, 1.0f, 1.0f, 0.0f, 0.0f}}));  // no ships at all
  std::array<ShipState, kMaxFrameShips> p{};
  EXPECT_EQ(calm->ship_poses(p), 0u);
}

// The shipped scenes with the cutoff, ships, wind and Stokes: the round trip every K steps brings
// them to at most 3.5 N x N transforms per step (issue 37 item 2), counted by the stages.
TEST(HuygensSolver, ShippedScenesTakeAtMostThreeAndAHalfTransformsPerStep) {
  for (const char* name : {"default", "ocean", "kelvin"}) {
    SCOPED_TRACE(name);
    auto s = make_solver(load_scene(test::scenes_dir() + "/" + name + ".json"), RunOptions{false});
    const double per_step = s->meta()["transforms_per_step"].get<double>();
    EXPECT_LE(per_step, 3.5);
    const int k = s->meta()["round_trip_every"].get<int>();
    EXPECT_GT(k, 1);
    for (int i = 0; i < 2 * k; ++i) s->step();
    std::uint64_t total = 0;
    for (const auto& st : s->stats().all()) total += st.transforms;
    EXPECT_DOUBLE_EQ(static_cast<double>(total) / (2 * k), per_step);
  }
}
