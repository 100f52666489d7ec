// The "huygens" scene solver: drop scheduling with exact sub-step timing, UI drops through
// Solver::apply, outputs and the per-stage counters.
#include "huygens/huygens_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using namespace huygens;

namespace {
std::unique_ptr<Solver> build(const std::string& extra) {
  const std::string text = R"({"solver": "huygens", "grid": {"n": 64, "length_m": 2.0, "margin": 0, "cutoff": false},
                               "time": {"dt": 0.02})" +
                           extra + "}";
  return make_solver(parse_scene_text(text), RunOptions{false});
}
}  // namespace

// A drop at t = 0.05 s with dt = 0.02 s enters in step 3 (t = 0.06 s) with 0.01 s of phase: after
// 5 steps it equals a drop at rest propagated exactly for 0.05 s.
TEST(HuygensSolver, DropsEnterWithExactSubStepTiming) {
  auto solver = build(R"(, "drops": [{"t": 0.05, "x_m": 1.0, "y_m": 0.8, "radius_m": 0.08, "depth_m": 0.01}])");
  for (int i = 0; i < 5; ++i) solver->step();
  HuygensParams p;
  p.n = 64;
  p.length_m = 2.0;
  p.margin = 0;
  p.absorber = Absorber::off;
  p.dt = 0.05;
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
      "time": {"dt": 0.02, "display_per_step": 3}})"),
                            RunOptions{false});
  const auto out = solver->outputs();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].name, "eta");
  EXPECT_EQ(out[0].shape, (std::vector<std::size_t>{48, 48}));
  const auto meta = solver->meta();
  EXPECT_EQ(meta["display_per_step"], 3);
  EXPECT_EQ(meta["transforms_per_step"], 3);
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
      "path": [{"t": 0, "x_m": 0.5, "y_m": 1.0}, {"t": 2, "x_m": 1.5, "y_m": 1.0}]}])";
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
  auto s = build(R"(, "time": {"dt": 0.02, "display_per_step": 3},
      "initial": [{"type": "gaussian", "x_m": 1.0, "y_m": 1.0, "sigma_m": 0.1, "amplitude_m": 0.01}])");
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
