// The scene pipeline on the Huygens solver: determinism across thread counts,
// proof that absent stages cost nothing, and failure containment (a non-finite value is
// reported with the stage that produced it; dumps up to the last good step stay valid); the
// manual-clock runner shows the frames of the steps at or before the display time, bit for bit.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "huygens/common/atomic_file.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/common/finite.hpp"
#include "huygens/common/npy.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/runner.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"
#include "huygens/spectral/spectral_solver.hpp"
#include "scenes_dir.hpp"

using namespace huygens;
using nlohmann::json;

namespace {

/// A Huygens scene: n x n grid, 10 m side, margin n/8, a Gaussian hump, optional drops.
std::string scene_text(int n, bool cutoff, bool initial, bool drops, double dt = 0.02) {
  json s = {{"solver", "huygens"},
            // the round trip every step (the stage counts below are per step)
            {"grid", {{"n", n}, {"length_m", 10.0}, {"margin", n / 8}, {"cutoff", cutoff}, {"round_trip_every", 1}}},
            {"time", {{"dt_s", dt}}}};
  if (initial)
    s["initial"] =
        json::array({{{"type", "gaussian"}, {"x_m", 4.0}, {"y_m", 5.5}, {"sigma_m", 0.15}, {"amplitude_m", 0.01}}});
  if (drops)
    s["drops"] = json::array({{{"t_s", 0.1}, {"x_m", 6.0}, {"y_m", 4.0}, {"radius_m", 0.1}, {"depth_m", 0.005}}});
  return s.dump();
}

std::uint64_t fnv1a(std::span<const float> v, std::uint64_t h = 1469598103934665603ull) {
  const auto* b = reinterpret_cast<const unsigned char*>(v.data());
  for (std::size_t i = 0; i < v.size_bytes(); ++i) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

struct ThreadScope {
  explicit ThreadScope(int t) {
    fft_set_threads(t);
    omp_set_num_threads(t);
  }
  ~ThreadScope() {
    fft_set_threads(2);
    omp_set_num_threads(2);
  }
};

struct RunResult {
  std::uint64_t hash = 0;
  std::vector<float> eta, etadot;
};

RunResult run_steps(const std::string& text, int threads, bool measure, int steps) {
  ThreadScope scope(threads);
  RunOptions o;
  o.measure_plans = measure;
  auto s = make_solver(parse_scene_text(text), o);
  for (int i = 0; i < steps; ++i) s->step();
  RunResult r;
  r.eta.assign(s->height().begin(), s->height().end());
  r.etadot.assign(s->height_rate().begin(), s->height_rate().end());
  r.hash = fnv1a(r.etadot, fnv1a(r.eta));
  return r;
}

const StageStat* stage(const StageStats& st, const std::string& name) {
  const int i = st.find(name);
  return i < 0 ? nullptr : &st[i];
}

std::uint64_t total_transforms(const StageStats& st) {
  std::uint64_t t = 0;
  for (const auto& s : st.all()) t += s.transforms;
  return t;
}

}  // namespace

// ---- 3. determinism ------------------------------------------------------------------------

TEST(Pipeline, SameSceneSameHashWithOneAndTwoThreads) {
  // FFTW_ESTIMATE picks its algorithm from the sizes alone, and every OpenMP loop of the step
  // is element-wise with schedule(static): the result must not depend on the thread count.
  // 500 steps on a 128 grid (FFTW's threaded transforms differ between 1 and 2 threads; the
  // propagator's OpenMP loops start at n = 256), then 60 steps on a 256 grid, where both do.
  for (const auto& [n, steps] : {std::pair{128, 500}, std::pair{256, 60}}) {
    SCOPED_TRACE(::testing::Message() << "n = " << n << ", " << steps << " steps");
    const std::string text = scene_text(n, true, true, true);
    const RunResult one = run_steps(text, 1, false, steps);
    const RunResult two = run_steps(text, 2, false, steps);
    ASSERT_TRUE(all_finite(one.eta));
    double peak = 0;
    for (float x : one.eta) peak = std::max(peak, std::abs(static_cast<double>(x)));
    ASSERT_GT(peak, 1e-5) << "the scene must still have waves for the hash to mean anything";
    EXPECT_EQ(one.hash, two.hash) << "bitwise determinism across thread counts with FFTW_ESTIMATE plans";
  }
}

TEST(Pipeline, MeasuredPlansAgreeAcrossThreadsWithinRounding) {
  // FFTW_MEASURE times candidate algorithms and may pick different ones for 1 and 2 threads
  // (or between runs): sums are then rounded in another order. Each transform's relative
  // error is ~eps log2(N) (eps = 6e-8, N = 256: ~5e-7); 500 steps of 3 transforms add such
  // independent errors as a random walk, sqrt(1500) * 5e-7 = 2e-5 of the field's scale
  // (fewer steps and a smaller N below make the estimate smaller still).
  // Tolerance: 1e-4 of the peak height (5x that estimate); a wrong result is O(1).
  // 200 steps on a 128 grid here (planning with FFTW_MEASURE costs seconds).
  const std::string text = scene_text(128, true, true, true);
  const RunResult one = run_steps(text, 1, true, 200);
  const RunResult two = run_steps(text, 2, true, 200);
  double peak = 0, diff = 0;
  for (std::size_t i = 0; i < one.eta.size(); ++i) {
    peak = std::max(peak, std::abs(static_cast<double>(one.eta[i])));
    diff = std::max(diff, std::abs(static_cast<double>(one.eta[i]) - two.eta[i]));
  }
  ASSERT_GT(peak, 1e-5);
  EXPECT_LE(diff, 1e-4 * peak);
  RecordProperty("max_rel_diff", std::to_string(diff / peak));
  RecordProperty("bitwise", one.hash == two.hash ? "yes" : "no");
}

// ---- 4. skip proof -------------------------------------------------------------------------

TEST(Pipeline, AbsentStagesRunNothingAndTransformsMatchTheFeatures) {
  struct Case {
    bool cutoff, drops;
    int transforms_per_step;
  };
  const int steps = 20;
  for (const Case c : {Case{true, false, 3}, Case{true, true, 3}, Case{false, false, 1}, Case{false, true, 1}}) {
    SCOPED_TRACE(::testing::Message() << "cutoff " << c.cutoff << ", drops " << c.drops);
    RunOptions o;
    o.measure_plans = false;
    auto s = make_solver(parse_scene_text(scene_text(64, c.cutoff, true, c.drops)), o);
    for (int i = 0; i < steps; ++i) s->step();
    const StageStats& st = s->stats();
    // features this build's scenes can name but these do not: no stage, or zero calls and bytes
    for (const char* absent : {"ships", "ship", "wind", "stokes"}) {
      const StageStat* a = stage(st, absent);
      if (a) {
        EXPECT_EQ(a->calls, 0u) << absent;
        EXPECT_EQ(a->bytes, 0u) << absent;
        EXPECT_EQ(a->transforms, 0u) << absent;
      }
    }
    // the absorber: without the cutoff there is no cutoff stage and no spatial round trip
    const StageStat* cut = stage(st, "cutoff");
    const StageStat* spec = stage(st, "spectrum");
    if (c.cutoff) {
      ASSERT_NE(cut, nullptr);
      EXPECT_EQ(cut->calls, static_cast<std::uint64_t>(steps));
    } else {
      if (cut) {
        EXPECT_EQ(cut->calls, 0u);
        EXPECT_EQ(cut->bytes, 0u);
      }
      if (spec) {
        EXPECT_EQ(spec->calls, 0u);
        EXPECT_EQ(spec->transforms, 0u);
      }
    }
    // drops run only in the step a scene drop falls into (analytic spectrum: no transform)
    if (const StageStat* d = stage(st, "drops")) {
      EXPECT_EQ(d->calls, c.drops ? 1u : 0u);
      EXPECT_EQ(d->transforms, 0u);
    } else {
      EXPECT_FALSE(c.drops) << "a scene with drops needs the drops stage";
    }
    EXPECT_EQ(total_transforms(st), static_cast<std::uint64_t>(steps * c.transforms_per_step))
        << "N x N transforms per step";
  }
}

TEST(Pipeline, ShipsWindAndStokesCostOnlyWhenNamed) {
  // the same 64-cell pool with each feature alone, and with all three; every feature not
  // named has no stage (or zero calls, bytes and transforms), every named one runs each step
  struct Case {
    bool ships, wind, stokes;
    int transforms_per_step;  // N x N transforms: 3 for the step with the cutoff, the height
                              // transform replaced by Stokes' 3 (eta1, eta1_dot, chi) when on
  };
  const int steps = 12;
  for (const Case c : {Case{false, false, false, 3}, Case{true, false, false, 3}, Case{false, true, false, 3},
                       Case{false, false, true, 5}, Case{true, true, true, 5}}) {
    SCOPED_TRACE(::testing::Message() << "ships " << c.ships << ", wind " << c.wind << ", stokes " << c.stokes);
    json sc = json::parse(scene_text(64, true, true, false));
    if (c.ships)
      sc["ships"] = json::array({{{"length_m", 1.0},
                                  {"beam_m", 0.3},
                                  {"draft_m", 0.05},
                                  {"path", json::array({{{"t_s", 0.0}, {"x_m", 3.0}, {"y_m", 5.0}},
                                                        {{"t_s", 10.0}, {"x_m", 7.0}, {"y_m", 5.0}}})}}});
    if (c.wind) sc["wind"] = {{"speed_mps", 5.0}, {"direction_deg", 30.0}, {"seed", 1}};
    sc["stokes"] = c.stokes;
    RunOptions o;
    o.measure_plans = false;
    std::unique_ptr<Solver> s;
    ASSERT_NO_THROW(s = make_solver(parse_scene_text(sc.dump()), o));
    for (int i = 0; i < steps; ++i) s->step();
    const StageStats& st = s->stats();
    auto check = [&](const char* name, bool present) {
      const StageStat* a = stage(st, name);
      if (present) {
        ASSERT_NE(a, nullptr) << name;
        EXPECT_EQ(a->calls, static_cast<std::uint64_t>(steps)) << name;
      } else if (a) {
        EXPECT_EQ(a->calls, 0u) << name;
        EXPECT_EQ(a->bytes, 0u) << name;
        EXPECT_EQ(a->transforms, 0u) << name;
      }
    };
    check("ships", c.ships);
    check("wind", c.wind);
    check("height_stokes", c.stokes);
    if (!c.stokes && !c.wind) check("height_wind", false);
    EXPECT_EQ(total_transforms(st), static_cast<std::uint64_t>(steps * c.transforms_per_step))
        << "N x N transforms per step";
    if (auto* h = dynamic_cast<HuygensSolver*>(s.get())) {
      EXPECT_EQ(h->transforms_per_step(), c.transforms_per_step);
    }
  }
}

namespace {

/// Max |a - b| and max |b|.
std::pair<double, double> max_diff(std::span<const float> a, std::span<const float> b) {
  double d = 0, peak = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    d = std::max(d, double(std::abs(a[i] - b[i])));
    peak = std::max(peak, double(std::abs(b[i])));
  }
  return {d, peak};
}

HuygensScene still_scene(bool initial, double drop_t, bool skip, bool drop = true) {
  RunOptions o;
  o.measure_plans = false;
  json sc = json::parse(scene_text(64, true, initial, false));
  if (drop)
    sc["drops"] = json::array({{{"t_s", drop_t}, {"x_m", 6.0}, {"y_m", 4.0}, {"radius_m", 0.1}, {"depth_m", 0.005}}});
  HuygensScene h = parse_huygens_scene(parse_scene_text(sc.dump()), o);
  h.still_skip = skip;
  // the 1 cm hump's waves need ~18000 steps to fall below the default 1e-7 m threshold (the
  // longest waves leave the 64-cell pool slowly: the energy's tail decays by e every ~3500
  // steps); with a 1e-5 m threshold they are below it after ~2900 steps
  if (initial) h.still_amplitude_m = 1e-5;
  return h;
}

}  // namespace

// Issue 4: a still sea (no ships, no wind, energy below the threshold) does no transform
// after it settles; a timed drop wakes it, and the result equals the run without the skip.
TEST(Pipeline, StillSeaSkipsPropagationUntilATimedDropWakesIt) {
  for (const bool initial : {false, true}) {
    SCOPED_TRACE(initial ? "a hump whose waves leave through the margin" : "an empty sea");
    // the empty sea settles at the first check (step 16); the hump's waves need longer to leave
    const double drop_t = initial ? 80.0 : 1.0;  // dt = 0.02 s: step 50 or 4000
    HuygensSolver skip(still_scene(initial, drop_t, true)), ref(still_scene(initial, drop_t, false));
    ASSERT_GT(skip.still_energy(), 0.0);
    EXPECT_EQ(ref.still_energy(), 0.0);
    const auto drop_step = static_cast<std::int64_t>(std::llround(drop_t / 0.02));
    std::int64_t settled = -1;
    for (std::int64_t k = 1; k < drop_step; ++k) {
      skip.step();
      ref.step();
      if (skip.still() && settled < 0) settled = k;
    }
    ASSERT_GT(settled, 0) << "never settled";
    if (!initial) {
      EXPECT_EQ(settled, 16);
    }
    RecordProperty(initial ? "hump_settled_step" : "empty_settled_step", std::to_string(settled));
    const StageStats& st = skip.stats();
    const std::int64_t still_steps = drop_step - 1 - settled;
    // no transform and no propagate/height call after it settled; every skipped step counted
    EXPECT_EQ(total_transforms(st), static_cast<std::uint64_t>(3 * settled));
    EXPECT_EQ(stage(st, "propagate")->calls, static_cast<std::uint64_t>(settled));
    EXPECT_EQ(stage(st, "height")->calls, static_cast<std::uint64_t>(settled));
    EXPECT_EQ(stage(st, "still")->calls, static_cast<std::uint64_t>(still_steps));
    EXPECT_EQ(stage(st, "still")->transforms, 0u);
    EXPECT_DOUBLE_EQ(skip.time(), ref.time());
    EXPECT_EQ(skip.steps(), ref.steps());
    for (float v : skip.height()) ASSERT_EQ(v, 0.0f) << "the still sea is flat";
    // the drop step and 30 more
    for (int k = 0; k <= 30; ++k) {
      skip.step();
      ref.step();
    }
    EXPECT_FALSE(skip.still());
    EXPECT_EQ(stage(st, "drops")->calls, 1u);
    EXPECT_EQ(stage(st, "propagate")->calls, static_cast<std::uint64_t>(settled + 31));
    // the reference keeps the residual the skip dropped. The step is linear, so the
    // reference is the skip run plus that residual alone, i.e. a third run without the skip
    // and without the drop: skip = ref - residual to float rounding
    const auto [d, peak] = max_diff(skip.height(), ref.height());
    ASSERT_GT(peak, 1e-4);
    const double skip_scene_amp = still_scene(initial, drop_t, true).still_amplitude_m;
    if (initial) {
      HuygensSolver residual(still_scene(initial, drop_t, false, false));
      for (std::int64_t k = 0; k < skip.steps(); ++k) residual.step();
      std::vector<float> expect(ref.height().begin(), ref.height().end());
      for (std::size_t i = 0; i < expect.size(); ++i) expect[i] -= residual.height()[i];
      const auto [e, epeak] = max_diff(skip.height(), expect);
      EXPECT_LE(e, 1e-5 * epeak);
      double res = 0;
      for (float v : residual.height()) res = std::max(res, double(std::abs(v)));
      RecordProperty("hump_residual_m", std::to_string(res));
      RecordProperty("hump_settled_bound_m", std::to_string(1.01 * skip_scene_amp * 64));
      RecordProperty("hump_max_diff_vs_superposition_m", std::to_string(e));
    } else {
      EXPECT_EQ(d, 0.0) << "from an exactly flat sea both runs are the same";
    }
    RecordProperty(initial ? "hump_max_diff_m" : "empty_max_diff_m", std::to_string(d));
  }
}

// A UI drop (cmd::Drop through apply) wakes a still sea at once; the height shows it without
// a step, and the following steps equal those of the run without the skip.
TEST(Pipeline, StillSeaWakesOnACommandDrop) {
  HuygensSolver skip(still_scene(false, 1e6, true)), ref(still_scene(false, 1e6, false));
  for (int k = 0; k < 20; ++k) {
    skip.step();
    ref.step();
  }
  ASSERT_TRUE(skip.still());
  const Command drop{cmd::Drop{5.0f, 5.0f, 0.1f, 0.005f}};
  ASSERT_TRUE(skip.apply(drop));
  ASSERT_TRUE(ref.apply(drop));
  EXPECT_FALSE(skip.still());
  EXPECT_EQ(max_diff(skip.height(), ref.height()).first, 0.0);
  double lowest = 0;
  for (float v : skip.height()) lowest = std::min(lowest, double(v));
  EXPECT_LT(lowest, -1e-3) << "the depression is in the height before the next step";
  for (int k = 0; k < 10; ++k) {
    skip.step();
    ref.step();
  }
  const auto [d, peak] = max_diff(skip.height(), ref.height());
  ASSERT_GT(peak, 1e-4);
  EXPECT_EQ(d, 0.0);
  EXPECT_EQ(stage(skip.stats(), "propagate")->calls, 16u + 10u);
}

// Ships and wind keep the sea alive: no still stage, no still state.
TEST(Pipeline, ShipsAndWindNeverGoStill) {
  json sc = json::parse(scene_text(64, true, false, false));
  sc["wind"] = {{"speed_mps", 5.0}, {"direction_deg", 30.0}, {"seed", 1}};
  RunOptions o;
  o.measure_plans = false;
  HuygensSolver s(parse_huygens_scene(parse_scene_text(sc.dump()), o));
  for (int k = 0; k < 20; ++k) s.step();
  EXPECT_FALSE(s.still());
  EXPECT_EQ(stage(s.stats(), "still"), nullptr);
  EXPECT_EQ(s.still_energy(), 0.0);
}

// ---- 5. NaN containment --------------------------------------------------------------------

namespace {

/// A Huygens solver whose named stage produces a NaN at step `at`, through the test hook
/// HuygensSolver::inject_nonfinite_for_test (not reachable from a scene); "none": no fault.
std::unique_ptr<HuygensSolver> make_faulty(const HuygensScene& scene, const std::string& stage, std::int64_t at) {
  auto s = std::make_unique<HuygensSolver>(scene);
  if (stage != "none") s->inject_nonfinite_for_test(stage, at);
  return s;
}

HuygensScene small_scene() {
  RunOptions o;
  o.measure_plans = false;
  return parse_huygens_scene(parse_scene_text(scene_text(64, true, true, false)), o);
}

/// The dump loop of `huygens run --dump DIR` (cli/huygens.cpp): meta.json rewritten
/// atomically after every dump, "stopped" added on a NonFiniteError.
void run_with_dumps(Solver& s, int steps, const std::string& dir) {
  std::filesystem::create_directories(dir);
  json meta = s.meta();
  meta["dumps"] = json::array();
  meta["complete"] = false;
  auto dump = [&] {
    json entry = {{"index", meta["dumps"].size()}, {"step", s.steps()}, {"time_s", s.time()}, {"files", json::array()}};
    for (const auto& f : s.outputs()) {
      char name[64];
      std::snprintf(name, sizeof name, "%s_%06lld.npy", f.name.c_str(), static_cast<long long>(s.steps()));
      write_npy(dir + "/" + name, f.data, f.shape);
      entry["files"].push_back(name);
    }
    meta["dumps"].push_back(entry);
    write_file_atomic(dir + "/meta.json", meta.dump(2));
  };
  try {
    dump();
    for (int i = 0; i < steps; ++i) {
      s.step();
      dump();
    }
    meta["complete"] = true;
  } catch (const NonFiniteError& e) {
    meta["stopped"] = {{"stage", e.stage()}, {"step", e.step()}, {"reason", e.what()}};
  }
  write_file_atomic(dir + "/meta.json", meta.dump(2));
}

}  // namespace

TEST(Pipeline, NonFiniteValueIsNamedByItsStage) {
  // The hook writes one NaN into the named stage's output at step `at`, before that stage's
  // own check. With the default check_every = 16, steps 16 and 32 run every stage's check;
  // on the other steps the fused check of the height finds it and the buffers name the stage
  // (Z: propagate, Z^: spectrum, P: height). The cutoff writes into the same spatial buffer as
  // propagate, so it is named on check steps only (or with check_every = 1): a multiplication by
  // h(p)h(q) in [0, 1] cannot make a non-finite value from finite ones. The ships check each
  // patch before adding it, on every step.
  struct Case {
    const char* stage;
    std::int64_t at;
    int check_every;
    bool drops, ships;
  };
  std::vector<Case> cases;
  for (const char* st : {"propagate", "spectrum", "height"})
    for (std::int64_t at : {1, 5, 16, 17}) cases.push_back({st, at, 16, false, false});
  for (std::int64_t at : {16, 32}) cases.push_back({"cutoff", at, 16, false, false});
  cases.push_back({"cutoff", 5, 1, false, false});
  cases.push_back({"drops", 5, 16, true, false});  // the scene drop at t = 0.1 s enters in step 5
  for (std::int64_t at : {5, 16, 17}) cases.push_back({"ships", at, 16, false, true});
  cases.push_back({"ships", 5, 1, false, true});
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << c.stage << " at step " << c.at << ", check_every " << c.check_every);
    json sc = json::parse(scene_text(64, true, true, c.drops));
    if (c.ships)
      sc["ships"] = json::array({{{"length_m", 1.0},
                                  {"beam_m", 0.3},
                                  {"draft_m", 0.05},
                                  {"path", json::array({{{"t_s", 0.0}, {"x_m", 3.0}, {"y_m", 5.0}},
                                                        {{"t_s", 10.0}, {"x_m", 7.0}, {"y_m", 5.0}}})}}});
    RunOptions o;
    o.measure_plans = false;
    HuygensScene scene = parse_huygens_scene(parse_scene_text(sc.dump()), o);
    scene.params.check_every = c.check_every;
    auto s = make_faulty(scene, c.stage, c.at);
    for (std::int64_t k = 1; k < c.at; ++k) ASSERT_NO_THROW(s->step());
    try {
      s->step();
      ADD_FAILURE() << "no NonFiniteError";
    } catch (const NonFiniteError& e) {
      EXPECT_EQ(e.stage(), c.stage);
      EXPECT_EQ(e.step(), c.at);
      EXPECT_NE(std::string(e.what()).find(c.stage), std::string::npos);
    }
  }
  HuygensSolver s(small_scene());
  EXPECT_THROW(s.inject_nonfinite_for_test("no_such_stage", 1), std::invalid_argument);
}

TEST(Pipeline, DumpsStayValidUpToTheLastGoodStep) {
  const std::int64_t at = 7;
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("huygens_nan_" + std::to_string(::getpid()))).string();
  std::filesystem::remove_all(dir);
  auto faulty = make_faulty(small_scene(), "spectrum", at);
  run_with_dumps(*faulty, 20, dir);

  // the same scene without the fault gives the reference heights of the good steps
  HuygensSolver clean(small_scene());
  std::ifstream f(dir + "/meta.json");
  const json meta = json::parse(f);
  EXPECT_EQ(meta["complete"], false);
  EXPECT_EQ(meta["stopped"]["stage"], "spectrum");
  EXPECT_EQ(meta["stopped"]["step"], at);
  ASSERT_EQ(meta["dumps"].size(), static_cast<std::size_t>(at)) << "steps 0 .. at-1";
  for (std::size_t i = 0; i < meta["dumps"].size(); ++i) {
    const json& d = meta["dumps"][i];
    EXPECT_EQ(d["step"], static_cast<std::int64_t>(i));
    const NpyArray a = read_npy(dir + "/" + d["files"][0].get<std::string>());
    EXPECT_TRUE(all_finite(a.data));
    ASSERT_EQ(a.data.size(), clean.height().size());
    EXPECT_EQ(0, std::memcmp(a.data.data(), clean.height().data(), a.data.size() * sizeof(float)))
        << "dump of step " << i << " differs from the fault-free run";
    clean.step();
  }
  char bad[64];
  std::snprintf(bad, sizeof bad, "/eta_%06lld.npy", static_cast<long long>(at));
  EXPECT_FALSE(std::filesystem::exists(dir + bad)) << "nothing of the failed step is written";
  std::filesystem::remove_all(dir);
}

TEST(Pipeline, RunnerReportsTheStageAndKeepsTheLastGoodFrame) {
  RunnerParams p;
  p.realtime = false;
  Runner r(make_faulty(small_scene(), "propagate", 9), p);
  r.start();
  while (!r.finished()) std::this_thread::yield();
  ASSERT_TRUE(r.failed());
  EXPECT_EQ(r.error().stage, "propagate");
  EXPECT_EQ(r.error().step, 9);
  const FramePair f = r.frames();
  ASSERT_TRUE(f);
  EXPECT_EQ(f.newest->info.step, 8);
  EXPECT_TRUE(all_finite(f.newest->eta.span()));
  r.stop();
}

namespace {

/// What a frame shows of a solver's state.
struct Snapshot {
  std::int64_t step = 0;
  double time_s = 0;
  std::vector<float> eta, particles;
  std::vector<ShipState> ships;
};

Snapshot snapshot(Solver& s) {
  Snapshot r{s.steps(), s.time(), {}, {}, {}};
  const auto h = s.height();
  r.eta.assign(h.begin(), h.end());
  const auto p = s.particles();
  r.particles.assign(p.begin(), p.end());
  std::array<ShipState, kMaxFrameShips> ships{};
  r.ships.assign(ships.begin(), ships.begin() + static_cast<std::ptrdiff_t>(s.ship_poses(ships)));
  return r;
}

void expect_frame(const Frame& f, const Snapshot& s, const std::string& what) {
  EXPECT_EQ(f.info.step, s.step) << what;
  EXPECT_EQ(f.info.time_s, s.time_s) << what;
  EXPECT_EQ(std::memcmp(f.eta.data(), s.eta.data(), s.eta.size() * sizeof(float)), 0) << what << ": eta";
  if (!s.particles.empty()) {
    EXPECT_EQ(std::memcmp(f.particles.data(), s.particles.data(), s.particles.size() * sizeof(float)), 0)
        << what << ": particles";
  }
  ASSERT_EQ(f.info.ship_count, s.ships.size()) << what;
  for (std::size_t i = 0; i < s.ships.size(); ++i) {
    EXPECT_EQ(f.info.ships[i].x_m, s.ships[i].x_m) << what;
    EXPECT_EQ(f.info.ships[i].y_m, s.ships[i].y_m) << what;
  }
}

}  // namespace

// The headless render's frames (huygens-viz --headless: the runner's manual clock, display times
// T, T + frame_dt, ...) are the steps a synchronous loop takes: after show(T) the newest frame is
// the last step at or before T (1e-9 of a step: the runner's tolerance) and the one before it the
// step before that (the interpolation's other end), with bit-identical heights, particles and
// ships, for the three solvers (SPH: adaptive step bounded by dt_max; LBM and Huygens: fixed).
TEST(Pipeline, ManualClockFramesAreTheStepsOfASynchronousLoop) {
  const std::string dir = huygens::test::scenes_dir();
  RunOptions ro;
  ro.measure_plans = false;
  for (const auto& [name, t0] : {std::pair{"sph_dam_break", 0.02}, std::pair{"channel", 1.5}, std::pair{"kelvin", 1.0},
                                 std::pair{"ocean", 1.0}}) {
    const Scene scene = load_scene(dir + "/" + name + ".json");
    std::unique_ptr<Solver> ref = make_solver(scene, ro), run = make_solver(scene, ro);
    const double frame_dt = ref->render_info().frame_dt_s;
    (void)run->render_info();  // as the viewer does before the runner starts
    RunnerParams rp;
    rp.manual_clock = true;
    Runner runner(std::move(run), rp);
    runner.start();
    Snapshot prev, cur = snapshot(*ref);
    ref->step();  // one step ahead of `cur`, as the runner holds a step that is not due yet
    for (int k = 0; k < 3; ++k) {
      const double t = t0 + k * frame_dt;
      while (ref->time() <= t + 1e-9 * (ref->time() - cur.time_s)) {
        prev = std::move(cur);
        cur = snapshot(*ref);
        ref->step();
      }
      runner.show(t);
      ASSERT_TRUE(runner.wait_shown(600.0)) << name << " " << t;
      const FramePair fp = runner.frames();
      ASSERT_TRUE(fp && fp.prev) << name;
      const std::string what = std::string(name) + " at display time " + std::to_string(t);
      expect_frame(*fp.newest, cur, what + ", newest frame");
      expect_frame(*fp.prev, prev, what + ", the frame before it");
    }
    runner.stop();
    EXPECT_FALSE(runner.failed()) << name;
    EXPECT_LT(runner.frames_published(), static_cast<std::uint64_t>(cur.step) + 1)
        << name << ": frames the display time passed are not published";
  }
}
