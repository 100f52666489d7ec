// The "huygens" scene solver: drop scheduling with exact sub-step timing, UI drops through
// Solver::apply, outputs and the per-stage counters.
#include "huygens/huygens_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

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
}

TEST(HuygensSolver, UiDropIsAppliedBetweenSteps) {
  auto solver = build("");
  solver->step();
  double before = 0;
  for (float v : solver->height()) before = std::max(before, double(std::abs(v)));
  EXPECT_EQ(before, 0.0);
  EXPECT_TRUE(solver->apply(Command{cmd::Drop{1.0f, 1.0f, 0.05f, 0.01f}}));
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
