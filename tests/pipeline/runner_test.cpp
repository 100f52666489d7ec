// Runner: a solver on its own thread, commands at step boundaries, frames published after
// every step, pacing, pause / step / resume / reset, clean stop, and exceptions from step()
// reported to the consumer. Uses a tiny fake solver whose fields encode its step and the
// drops it received, so every frame can be checked for content.
#include "huygens/pipeline/runner.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

using namespace huygens;

namespace {

constexpr std::size_t kRows = 6, kCols = 10;

/// A fake solver: eta[i] = step + i + (sum of drop depths), eta_dot[i] = 1 / dt.
/// Records command order and whether a command ever arrived inside step().
class FakeSolver : public Solver {
 public:
  struct Options {
    double dt = 0.01;
    /// Throw NonFiniteError("propagate", k) when step k would be taken (0 = never).
    std::int64_t fail_at = 0;
    /// Busy time per step (unit: s).
    double step_cost_s = 0;
    bool with_rate = true;
    /// Report one ship (x = step, y = the last ShipTarget's x, heading = its y) and accept ShipTarget.
    bool ship = false;
    /// Solver::time_bound: 0 none (+infinity), 1 exact (fixed dt), 2 adaptive steps of
    /// dt (0.3 .. 1] (step-dependent) bounded by t + k dt.
    int bound = 0;
  };
  explicit FakeSolver(Options o) : o_(o), eta_(kRows * kCols), rate_(kRows * kCols) {
    stage_ = stats_.add("propagate", eta_.size() * sizeof(float));
    fill();
  }

  void step() override {
    in_step_ = true;
    StageTimer t(stats_[stage_]);
    if (o_.fail_at > 0 && steps_ + 1 == o_.fail_at) {
      in_step_ = false;
      throw NonFiniteError("propagate", steps_ + 1);
    }
    if (o_.step_cost_s > 0) {
      const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(o_.step_cost_s);
      while (std::chrono::steady_clock::now() < until) {
      }
    }
    t_ += o_.bound == 2 ? o_.dt * (0.3 + 0.7 * static_cast<double>((steps_ * 7) % 5) / 4.0) : 0.0;
    ++steps_;
    stats_[stage_].transforms += 2;
    fill();
    in_step_ = false;
  }
  double time() const override { return o_.bound == 2 ? t_ : static_cast<double>(steps_) * o_.dt; }
  std::int64_t steps() const override { return steps_; }
  double time_bound(int k) const override {
    if (o_.bound == 1) return static_cast<double>(steps_ + k) * o_.dt;
    if (o_.bound == 2) return t_ + k * o_.dt;
    return Solver::time_bound(k);
  }
  std::vector<OutputField> outputs() override { return {{"eta", {kRows, kCols}, eta_}}; }
  nlohmann::json meta() const override { return nlohmann::json::object(); }
  const StageStats& stats() const override { return stats_; }
  std::span<const float> height() override { return eta_; }
  std::size_t height_rows() const override { return kRows; }
  std::size_t height_cols() const override { return kCols; }
  std::span<const float> height_rate() override {
    return o_.with_rate ? std::span<const float>(rate_) : std::span<const float>();
  }
  bool apply(const Command& c) override {
    if (in_step_) inside_step_ = true;
    if (const auto* d = std::get_if<cmd::Drop>(&c)) {
      drops_.push_back(d->depth_m);
      depth_sum_ += d->depth_m;
      fill();  // the drop shows in height() at once
      return true;
    }
    if (const auto* t = std::get_if<cmd::ShipTarget>(&c); t && o_.ship) {
      target_x_ = t->x_m;
      target_y_ = t->y_m;
      return true;
    }
    if (std::holds_alternative<cmd::Reset>(c)) {
      steps_ = 0;
      depth_sum_ = 0;
      fill();
      return true;
    }
    return false;  // ship targets (unless Options::ship), parameters, toggles: not supported by this solver
  }
  std::size_t ship_poses(std::span<ShipState> out) const override {
    if (!o_.ship || out.empty()) return 0;
    out[0] = ShipState{static_cast<double>(steps_), target_x_, target_y_, 1.0};
    return 1;
  }

  std::vector<float> drops_;
  bool inside_step_ = false;

 private:
  void fill() {
    for (std::size_t i = 0; i < eta_.size(); ++i) {
      eta_[i] = static_cast<float>(steps_) + static_cast<float>(i) + depth_sum_;
      rate_[i] = static_cast<float>(1.0 / o_.dt);
    }
  }
  Options o_;
  StageStats stats_;
  int stage_ = 0;
  std::int64_t steps_ = 0;
  double t_ = 0;  // Options::bound == 2
  float depth_sum_ = 0;
  double target_x_ = -1, target_y_ = 0;
  bool in_step_ = false;
  std::vector<float> eta_, rate_;
};

std::unique_ptr<Solver> fake(FakeSolver::Options o = {}) { return std::make_unique<FakeSolver>(o); }

/// The fake's frame content is a function of its step and its drops.
bool consistent(const Frame& f, float depth_sum) {
  for (std::size_t i = 0; i < f.eta.size(); ++i)
    if (f.eta[i] != static_cast<float>(f.info.step) + static_cast<float>(i) + depth_sum) return false;
  return f.stages.size() == 1 && f.stages[0].transforms == 2 * static_cast<std::uint64_t>(f.info.step);
}

/// Polls until pred() or the runner finished; the test fails on a 30 s safety limit (a hang).
template <class Pred>
void wait_for(const Pred& pred) {
  const auto limit = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!pred()) {
    ASSERT_LT(std::chrono::steady_clock::now(), limit) << "hung";
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

}  // namespace

TEST(Runner, FastModePublishesEveryStepInOrder) {
  RunnerParams p;
  p.realtime = false;
  p.max_steps = 2000;
  Runner r(fake(), p);
  ASSERT_EQ(r.stage_names().size(), 1u);
  EXPECT_EQ(r.stage_names()[0], "propagate");
  r.start();
  std::int64_t last = -1;
  std::uint64_t bad = 0, unpaired = 0;
  for (;;) {
    const bool finished = r.finished();
    const FramePair f = r.frames();
    if (f) {
      if (!consistent(*f.newest, 0) || (f.prev && !consistent(*f.prev, 0))) ++bad;
      if (f.prev && f.prev->info.step + 1 != f.newest->info.step) ++unpaired;
      EXPECT_GE(f.newest->info.step, last);
      last = f.newest->info.step;
      EXPECT_TRUE(f.newest->has_rate);
    }
    if (finished) break;
  }
  r.stop();
  EXPECT_FALSE(r.failed());
  EXPECT_EQ(bad, 0u);
  EXPECT_EQ(unpaired, 0u);
  EXPECT_EQ(last, 2000);
  EXPECT_EQ(r.frames_published(), 2001u) << "the initial state plus one frame per step";
  EXPECT_EQ(r.solver().steps(), 2000);
  EXPECT_TRUE(std::isinf(r.display_time())) << "as fast as possible: the display shows the newest frame";
}

TEST(Runner, CommandsAreAppliedInOrderBetweenStepsAndShowInTheNextFrame) {
  RunnerParams p;
  p.realtime = false;
  p.start_paused = true;
  Runner r(fake(), p);
  r.start();
  wait_for([&] { return r.frames_published() >= 1; });
  for (int k = 1; k <= 5; ++k) ASSERT_TRUE(r.send(cmd::Drop{1.0f, 2.0f, 0.05f, 0.25f * static_cast<float>(k)}));
  ASSERT_TRUE(r.send(cmd::ShipTarget{0, 1, 1, 0, 0}));  // the fake refuses this
  ASSERT_TRUE(r.send(cmd::StepOnce{}));
  wait_for([&] { return r.frames_published() >= 2; });
  const FramePair f = r.frames();
  ASSERT_TRUE(f);
  EXPECT_EQ(f.newest->info.step, 1);
  EXPECT_EQ(f.newest->info.commands_applied, 6u) << "five drops and the step command";
  // the drops (0.25 + 0.5 + ... + 1.25 = 3.75 m) show in the frame after the boundary they were applied at
  EXPECT_TRUE(consistent(*f.newest, 3.75f));
  EXPECT_TRUE(consistent(*f.prev, 0.0f));
  EXPECT_EQ(r.commands_rejected(), 1u);
  r.stop();
  auto& s = dynamic_cast<FakeSolver&>(r.solver());
  EXPECT_EQ(s.drops_, (std::vector<float>{0.25f, 0.5f, 0.75f, 1.0f, 1.25f}));
  EXPECT_FALSE(s.inside_step_) << "a command reached the solver inside step()";
}

// Every frame carries the solver's ship poses at its step (Solver::ship_poses), and a ShipTarget
// applied at a step boundary shows in the next frame; a solver without ships publishes none.
TEST(Runner, FramesCarryTheSolversShipPoses) {
  RunnerParams p;
  p.realtime = false;
  p.start_paused = true;
  FakeSolver::Options o;
  o.ship = true;
  Runner r(fake(o), p);
  r.start();
  wait_for([&] { return r.frames_published() >= 1; });
  ASSERT_TRUE(r.send(cmd::StepOnce{}));
  wait_for([&] { return r.frames_published() >= 2; });
  ASSERT_TRUE(r.send(cmd::ShipTarget{0, 3.5f, -0.25f, 0.0f, 0.0f}));
  ASSERT_TRUE(r.send(cmd::StepOnce{}));
  wait_for([&] { return r.frames_published() >= 3; });
  const FramePair f = r.frames();
  ASSERT_TRUE(f && f.prev);
  ASSERT_EQ(f.prev->info.ship_count, 1u);
  ASSERT_EQ(f.newest->info.ship_count, 1u);
  EXPECT_EQ(f.prev->info.ships[0].x_m, 1.0);  // step 1, before the target
  EXPECT_EQ(f.prev->info.ships[0].y_m, -1.0);
  EXPECT_EQ(f.newest->info.ships[0].x_m, 2.0);  // step 2, after it
  EXPECT_EQ(f.newest->info.ships[0].y_m, 3.5);
  EXPECT_EQ(f.newest->info.ships[0].heading_rad, -0.25);
  ShipState mid;
  ASSERT_TRUE(f.ship(0, f.prev->info.time_s + 0.5 * (f.newest->info.time_s - f.prev->info.time_s), mid));
  EXPECT_DOUBLE_EQ(mid.x_m, 1.5);  // interpolated between the two frames
  ShipState none;
  EXPECT_FALSE(f.ship(1, 0.0, none));
  EXPECT_EQ(r.commands_rejected(), 0u);
  r.stop();
  Runner plain(fake(), p);
  plain.start();
  wait_for([&] { return plain.frames_published() >= 1; });
  EXPECT_EQ(plain.frames().newest->info.ship_count, 0u);
  plain.stop();
}

TEST(Runner, PauseStepOnceResume) {
  RunnerParams p;
  p.realtime = false;
  p.start_paused = true;
  p.max_steps = 50;
  Runner r(fake(), p);
  r.start();
  wait_for([&] { return r.frames_published() >= 1; });
  EXPECT_TRUE(r.paused());
  // paused: no step however long we wait (a logical check, not a timing threshold)
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_EQ(r.frames_published(), 1u);
  ASSERT_TRUE(r.send(cmd::StepOnce{}));
  ASSERT_TRUE(r.send(cmd::StepOnce{}));
  wait_for([&] { return r.frames_published() >= 3; });
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_EQ(r.frames_published(), 3u) << "exactly one step per StepOnce";
  EXPECT_EQ(r.frames().newest->info.step, 2);
  ASSERT_TRUE(r.send(cmd::Resume{}));
  wait_for([&] { return r.finished(); });
  EXPECT_FALSE(r.paused());
  EXPECT_EQ(r.frames().newest->info.step, 50);
  r.stop();
}

TEST(Runner, NonFiniteErrorReachesTheConsumerWithItsStage) {
  RunnerParams p;
  p.realtime = false;
  FakeSolver::Options o;
  o.fail_at = 7;
  Runner r(fake(o), p);
  r.start();
  wait_for([&] { return r.finished(); });
  ASSERT_TRUE(r.failed());
  EXPECT_TRUE(r.error().non_finite);
  EXPECT_EQ(r.error().stage, "propagate");
  EXPECT_EQ(r.error().step, 7);
  EXPECT_NE(r.error().message.find("propagate"), std::string::npos);
  EXPECT_THROW(r.rethrow_if_failed(), NonFiniteError);
  // the frames up to the last good step stay with the consumer
  const FramePair f = r.frames();
  ASSERT_TRUE(f);
  EXPECT_EQ(f.newest->info.step, 6);
  EXPECT_TRUE(consistent(*f.newest, 0));
  r.stop();
}

TEST(Runner, ResetRebuildsTheSolverFromTheFactory) {
  RunnerParams p;
  p.realtime = false;
  p.start_paused = true;
  Runner r(fake(), p, [] { return fake(); });
  r.start();
  for (int k = 0; k < 3; ++k) r.send(cmd::StepOnce{});
  wait_for([&] { return r.frames_published() >= 4; });
  EXPECT_EQ(r.frames().newest->info.step, 3);
  r.send(cmd::Reset{});
  wait_for([&] { return r.frames_published() >= 5; });
  EXPECT_EQ(r.frames().newest->info.step, 0);
  r.stop();
  EXPECT_EQ(r.solver().steps(), 0);
}

TEST(Runner, ResetFallsBackToTheSolver) {
  RunnerParams p;
  p.realtime = false;
  p.start_paused = true;
  Runner r(fake(), p);
  r.start();
  r.send(cmd::StepOnce{});
  r.send(cmd::Reset{});
  wait_for([&] { return r.frames_published() >= 3; });
  EXPECT_EQ(r.frames().newest->info.step, 0);
  r.stop();
}

TEST(Runner, RealTimeNeverShowsAFrameBeforeTheClockReachesItsPredecessor) {
  // dt = 10 ms at time_scale 1: frame n+1 may be published only once the display clock
  // has reached t_n, so 20 steps cannot take less than 0.19 s of wall time
  RunnerParams p;
  p.realtime = true;
  p.max_steps = 20;
  Runner r(fake(), p);
  const auto t0 = std::chrono::steady_clock::now();
  r.start();
  std::uint64_t early = 0;
  for (;;) {
    const bool finished = r.finished();
    const FramePair f = r.frames();
    const double d = r.display_time();
    if (f.prev && d < f.prev->info.time_s - 1e-9) ++early;
    if (finished) break;
    std::this_thread::sleep_for(std::chrono::microseconds(300));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.stop();
  EXPECT_EQ(early, 0u);
  EXPECT_EQ(r.frames().newest->info.step, 20);
  EXPECT_GE(wall, 0.19 * (1 - 1e-6));
}

TEST(Runner, PauseFreezesTheDisplayClock) {
  RunnerParams p;
  p.realtime = true;
  Runner r(fake(), p);
  r.start();
  wait_for([&] { return r.frames_published() >= 3; });
  r.send(cmd::Pause{});
  wait_for([&] { return r.paused(); });
  const double d1 = r.display_time();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(r.display_time(), d1);
  r.send(cmd::SetParam{"time_scale", 0.0});  // refused: must be positive
  r.send(cmd::SetParam{"time_scale", 2.0});
  r.send(cmd::Toggle{"realtime", false});
  r.send(cmd::Resume{});
  wait_for([&] { return r.commands_applied() + r.commands_rejected() >= 5; });
  EXPECT_EQ(r.commands_rejected(), 1u);
  EXPECT_TRUE(std::isinf(r.display_time()));
  r.stop();
  EXPECT_TRUE(r.finished());
  EXPECT_FALSE(r.failed());
}

TEST(Runner, FullCommandQueueRefusesInsteadOfBlocking) {
  RunnerParams p;
  p.command_capacity = 4;
  Runner r(fake(), p);  // not started: nothing drains the queue
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(r.send(cmd::Pause{}));
  EXPECT_FALSE(r.send(cmd::Pause{}));
}

TEST(Runner, StopsCleanlyInEveryState) {
  for (int mode = 0; mode < 3; ++mode) {
    RunnerParams p;
    p.realtime = mode != 0;
    p.start_paused = mode == 2;
    FakeSolver::Options o;
    o.dt = 10.0;  // real time: the next frame is due in 10 s, so stop() must not wait for it
    Runner r(fake(o), p);
    r.start();
    wait_for([&] { return r.frames_published() >= 1; });
    r.stop();
    EXPECT_TRUE(r.finished());
    EXPECT_FALSE(r.failed());
  }
}

TEST(Runner, ThreeThreadsStress) {
  // UI thread sends drops while the simulation steps and the render thread reads frames
  RunnerParams p;
  p.realtime = false;
  p.max_steps = 20000;
  p.command_capacity = 8;
  Runner r(fake(), p);
  r.start();
  std::atomic<int> sent{0};
  std::thread ui([&] {
    for (int k = 0; k < 500 && !r.finished(); ++k) {
      if (r.send(cmd::Drop{0, 0, 0.05f, 1.0f})) sent.fetch_add(1);
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    }
  });
  std::uint64_t bad = 0;
  for (;;) {
    const bool finished = r.finished();
    const FramePair f = r.frames();
    // drops of 1 m each: frame content = step + i + (drops applied before the frame)
    if (f && !consistent(*f.newest, static_cast<float>(f.newest->info.commands_applied))) ++bad;
    if (finished) break;
  }
  ui.join();
  r.stop();
  EXPECT_EQ(bad, 0u);
  EXPECT_FALSE(r.failed());
  auto& s = dynamic_cast<FakeSolver&>(r.solver());
  EXPECT_FALSE(s.inside_step_);
  EXPECT_LE(s.drops_.size(), static_cast<std::size_t>(sent.load()));
}

namespace {

/// The fake's time after `steps` steps, as it computes it (the reference for the frames expected).
double fake_time(const FakeSolver::Options& o, std::int64_t steps) {
  FakeSolver ref(o);
  for (std::int64_t k = 0; k < steps; ++k) ref.step();
  return ref.time();
}

}  // namespace

// The manual clock shows the same frames whether or not the solver bounds its next steps' times:
// after show(T) the newest frame is the last step at or before T and the one before it the step
// before that (the pair the display interpolates between), each with its step's field; the runner
// leaves unpublished only frames that display time passed (fewer frames than steps), none when the
// solver cannot bound its step (every step, as the window's real-time path has them).
TEST(RunnerManualClock, ShowsTheSameFramesWithAndWithoutTimeBounds) {
  const std::vector<double> shows = {0.0, 0.004, 0.01, 0.0345, 0.05, 0.05, 0.2, 0.2001, 0.5, 1.0};
  for (int bound : {0, 1, 2}) {
    FakeSolver::Options o;
    o.bound = bound;
    RunnerParams rp;
    rp.manual_clock = true;
    Runner runner(fake(o), rp);
    runner.start();
    FakeSolver ref(o);  // stepped while its next step is at or before T: the frames expected
    for (double t : shows) {
      for (;;) {
        const double t0 = ref.time();
        const double t1 = fake_time(o, ref.steps() + 1);
        if (!(t1 <= t + 1e-9 * (t1 - t0))) break;
        ref.step();
      }
      runner.show(t);
      ASSERT_TRUE(runner.wait_shown(60.0)) << t;
      const FramePair fp = runner.frames();
      ASSERT_TRUE(fp);
      EXPECT_EQ(fp.newest->info.step, ref.steps()) << "bound " << bound << ", display time " << t;
      EXPECT_EQ(fp.newest->info.time_s, ref.time()) << "bound " << bound << ", display time " << t;
      EXPECT_TRUE(consistent(*fp.newest, 0.0f));
      if (ref.steps() == 0) continue;
      ASSERT_NE(fp.prev, nullptr);
      EXPECT_EQ(fp.prev->info.step, ref.steps() - 1) << "bound " << bound << ", display time " << t;
      EXPECT_TRUE(consistent(*fp.prev, 0.0f));
    }
    runner.stop();
    EXPECT_FALSE(runner.failed());
    const auto all = static_cast<std::uint64_t>(ref.steps()) + 1;
    if (bound == 0)
      EXPECT_EQ(runner.frames_published(), all) << "no bound: every step published";
    else
      EXPECT_LT(runner.frames_published(), all / 2) << "bound " << bound << ": frames the display passed left out";
  }
}

// max_steps ends the run before the display time: the last two steps taken are still published.
TEST(RunnerManualClock, TheLastStepsBeforeMaxStepsArePublished) {
  FakeSolver::Options o;
  o.bound = 1;
  RunnerParams rp;
  rp.manual_clock = true;
  rp.max_steps = 40;
  Runner runner(fake(o), rp);
  runner.start();
  runner.show(1.0);  // 100 steps of 0.01 s
  EXPECT_FALSE(runner.wait_shown(60.0)) << "the thread ends at step 40";
  const FramePair fp = runner.frames();
  ASSERT_TRUE(fp);
  EXPECT_EQ(fp.newest->info.step, 40);
  ASSERT_NE(fp.prev, nullptr);
  EXPECT_EQ(fp.prev->info.step, 39);
  runner.stop();
}

// A paused manual-clock runner still steps one frame per StepOnce and publishes it.
TEST(RunnerManualClock, StepOncePublishesEveryStepWhilePaused) {
  FakeSolver::Options o;
  o.bound = 1;
  RunnerParams rp;
  rp.manual_clock = true;
  rp.start_paused = true;
  Runner runner(fake(o), rp);
  runner.start();
  runner.show(1.0);
  for (int k = 1; k <= 3; ++k) {
    ASSERT_TRUE(runner.send(cmd::StepOnce{}));
    wait_for([&] { return runner.frames_published() >= static_cast<std::uint64_t>(k) + 1; });
    EXPECT_EQ(runner.frames().newest->info.step, k);
  }
  runner.stop();
}
