// The test-only solver (toy_solver.hpp): the linear long-wave equation by leapfrog.
#include "toy_solver.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "huygens/common/finite.hpp"

namespace huygens::toy {

namespace {

constexpr double kG = 9.81;

class ToySolver : public Solver {
 public:
  explicit ToySolver(const ToyParams& p)
      : p_(p), now_(std::size_t(p.n) * std::size_t(p.n)), before_(now_.size()), next_(now_.size()) {
    stage_ = stats_.add("leapfrog", 3 * now_.size() * sizeof(float));
    const double k = 2 * std::numbers::pi * p.mode / p.length_m, dx = p.length_m / p.n;
    const double c = std::sqrt(kG * p.depth_m);
    // the scheme's own frequency (toy_solver.hpp), so eta^1 = A cos(kx) cos(w_d dt) starts it at rest
    const double wd = 2 / p.dt_s * std::asin(c * p.dt_s / dx * std::sin(k * dx / 2));
    for (int r = 0; r < p.n; ++r)
      for (int col = 0; col < p.n; ++col) {
        const double a = p.amplitude_m * std::cos(k * col * dx);
        now_[idx(r, col)] = static_cast<float>(a * std::cos(wd * p.dt_s));
        before_[idx(r, col)] = static_cast<float>(a);
      }
    steps_ = 1;
  }

  void step() override {
    StageTimer timer(stats_[stage_]);
    const int n = p_.n;
    const double dx = p_.length_m / n, r2 = kG * p_.depth_m * p_.dt_s * p_.dt_s / (dx * dx);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const double lap = now_[idx((r + 1) % n, c)] + now_[idx((r + n - 1) % n, c)] + now_[idx(r, (c + 1) % n)] +
                           now_[idx(r, (c + n - 1) % n)] - 4.0 * now_[idx(r, c)];
        next_[idx(r, c)] = static_cast<float>(2.0 * now_[idx(r, c)] - before_[idx(r, c)] + r2 * lap);
      }
    std::swap(before_, now_);
    std::swap(now_, next_);
    ++steps_;
    if (!all_finite(now_)) throw NonFiniteError("leapfrog", steps_);
  }
  double time() const override { return double(steps_) * p_.dt_s; }
  std::int64_t steps() const override { return steps_; }
  double time_bound(int steps) const override { return double(steps_ + steps) * p_.dt_s; }
  std::vector<OutputField> outputs() override { return {OutputField{"eta", {height_rows(), height_cols()}, now_}}; }
  nlohmann::json meta() const override {
    return {{"solver", "toy"}, {"n", p_.n}, {"dx_m", p_.length_m / p_.n}, {"dt_s", p_.dt_s}};
  }
  const StageStats& stats() const override { return stats_; }
  std::span<const float> height() override { return now_; }
  std::size_t height_rows() const override { return std::size_t(p_.n); }
  std::size_t height_cols() const override { return std::size_t(p_.n); }
  RenderInfo render_info() override {
    RenderInfo r = Solver::render_info();
    r.grid.dx_m = p_.length_m / p_.n;
    r.depth_m = p_.depth_m;
    r.dt_s = r.frame_dt_s = p_.dt_s;
    return r;
  }

 private:
  std::size_t idx(int r, int c) const { return std::size_t(r) * std::size_t(p_.n) + std::size_t(c); }

  ToyParams p_;
  std::vector<float> now_, before_, next_;
  std::int64_t steps_ = 0;
  StageStats stats_;
  int stage_ = 0;
};

MemoryEstimate toy_memory(const ToyParams& p) {
  MemoryEstimate m;
  m.size_key = "$.toy.n";
  m.add("three levels", 3 * std::uint64_t(p.n) * std::uint64_t(p.n) * sizeof(float), "$.toy.n");
  return m;
}

constexpr const char* kScene = R"({"solver": "toy", "toy": {"n": 64, "length_m": 1, "depth_m": 0.1, "dt_s": 0.005}})";

}  // namespace

ToyParams parse_toy_scene(const Scene& scene) {
  scene.root().allow_only({"solver", "toy"});
  const JsonIn t = scene.root().object("toy");
  t.allow_only({"n", "length_m", "depth_m", "dt_s", "amplitude_m", "mode"});
  ToyParams p;
  p.n = static_cast<int>(t.integer("n", 64, 4, 4096));
  p.length_m = t.number("length_m", 1.0, 1e-3, 1e6);
  p.depth_m = t.number("depth_m", 0.1, 1e-4, 1e4);
  p.dt_s = t.number("dt_s", 0.005, 1e-7, 1e3);
  p.amplitude_m = t.number("amplitude_m", 0.01, 0.0, 1e3);
  p.mode = static_cast<int>(t.integer("mode", 1, 0, p.n / 2));
  // leapfrog on the 5-point Laplacian is stable for c dt / dx < 1 / sqrt(2)
  const double courant = std::sqrt(kG * p.depth_m) * p.dt_s / (p.length_m / p.n);
  if (courant >= 1 / std::sqrt(2.0))
    t.fail("dt_s", "unstable: c dt / dx = " + std::to_string(courant) + " must be below 1/sqrt(2)");
  return p;
}

SolverEntry toy_solver_entry() {
  SolverEntry e;
  e.name = "toy";
  e.summary = "test-only: the linear long-wave equation by leapfrog (tests/toy_solver/)";
  e.make = [](const Scene& s, const RunOptions&) -> std::unique_ptr<Solver> {
    const ToyParams p = parse_toy_scene(s);
    require_memory(toy_memory(p));
    return std::make_unique<ToySolver>(p);
  };
  e.sizing = [](const Scene& s) {
    const ToyParams p = parse_toy_scene(s);
    return SceneSizing{"toy", std::to_string(p.n) + " x " + std::to_string(p.n), 1, false};
  };
  e.rank_memory = [](const Scene& s) -> std::function<MemoryEstimate(int)> {
    const MemoryEstimate m = toy_memory(parse_toy_scene(s));
    return [m](int) { return m; };
  };
  e.bench_scene = kScene;
  e.bench_steps = 400;
  return e;
}

std::vector<ValidationCase> toy_validation_cases() {
  ValidationCase c{"toy_standing_wave", "toy", "standing wave period against 2 pi / (sqrt(g H) k)", [] {
                     const ToyParams p = parse_toy_scene(parse_scene_text(kScene, "toy case"));
                     ToySolver s(p);
                     // the first zero of eta(0) at a quarter period, linearly interpolated between steps
                     double before = s.height()[0], t_before = s.time();
                     while (s.height()[0] > 0) {
                       before = s.height()[0];
                       t_before = s.time();
                       s.step();
                     }
                     const double after = s.height()[0];
                     const double quarter = t_before + p.dt_s * before / (before - after);
                     const double k = 2 * std::numbers::pi * p.mode / p.length_m;
                     const double expected = 2 * std::numbers::pi / (std::sqrt(kG * p.depth_m) * k);
                     return std::vector<ValidationRow>{check("toy_standing_wave", "period (s)", 4 * quarter, expected,
                                                             std::fabs(4 * quarter / expected - 1), 1e-3)};
                   }};
  return {c};
}

}  // namespace huygens::toy
