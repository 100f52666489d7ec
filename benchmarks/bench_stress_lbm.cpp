// Section "stress", LBM part: the shallow-water LBM (paper 002 sec. 2) on its hardest
// shipped scene, scenes/dam_break.json (a partial dam break through a 75 m breach, 10 m / 7 m),
// for 1e5 steps (--quick: 2000) with the budgets printed every tenth of the run (volume, largest
// speed and Froude number, shallowest wet cell) and a verdict; then the edge of its limits: the
// CFL number, the depth ratio of a dam and the relaxation time tau swept until the scene is refused
// before the run (SceneError naming the JSON path and the reason) or the run stops naming the
// cell (LbmDryError) or the stage (NonFiniteError), both a RunStopped. Nothing may go non-finite silently.
#include <algorithm>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/lbm/shallow.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"

namespace huygens::bench {

namespace {

nlohmann::json lbm_scene_json(const std::string& name) { return nlohmann::json::parse(shipped_scene(name)); }

// Volume, largest speed and Froude number, shallowest wet cell of the current state.
struct LbmBudget {
  double volume_m3 = 0, max_speed = 0, max_froude = 0, min_depth = 0;
  bool finite = true;
};

LbmBudget lbm_budget(Solver& s, double cell_m, double g) {
  LbmBudget b;
  b.min_depth = INFINITY;
  std::span<const float> h, u;
  for (const OutputField& f : s.outputs()) {
    if (f.name == "h") h = f.data;
    if (f.name == "u") u = f.data;
  }
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double d = h[i], ux = u[2 * i], uy = u[2 * i + 1];
    if (!std::isfinite(d) || !std::isfinite(ux) || !std::isfinite(uy)) b.finite = false;
    if (d <= 0) continue;  // obstacle cells hold 0
    const double sp = std::hypot(ux, uy);
    b.volume_m3 += d * cell_m * cell_m;
    b.max_speed = std::max(b.max_speed, sp);
    b.max_froude = std::max(b.max_froude, sp / std::sqrt(g * d));
    b.min_depth = std::min(b.min_depth, d);
  }
  return b;
}

// Runs `steps` steps of the scene; the outcome names how it ended.
std::string run_lbm(const nlohmann::json& j, long steps, LbmBudget* last = nullptr) {
  try {
    auto s = make_solver(parse_scene_text(j.dump(), "lbm stress scene"));
    for (long i = 0; i < steps; ++i) s->step();
    const LbmBudget b = lbm_budget(*s, j["lbm"]["grid"]["cell_m"].get<double>(), 9.81);
    if (last) *last = b;
    return b.finite ? "finite and bounded" : "NON-FINITE, NOT REPORTED";
  } catch (const SceneError& e) {
    return std::string("refused before the run: ") + e.what();
  } catch (const RunStopped& e) {
    return std::string("stopped: ") + e.what();
  }
}

bool contained(const std::string& outcome) {
  return outcome.rfind("finite and bounded", 0) == 0 || outcome.rfind("refused before the run", 0) == 0 ||
         outcome.rfind("stopped: ", 0) == 0;
}

// What every part of the LBM stress shares: the shipped scene, its cell size (m) and gravity (m/s^2).
struct LbmStress {
  nlohmann::json base;
  double cell = 0, g = 0;
};

// ---- 1. the long run of the hardest shipped LBM scene
struct LbmLongRun {
  double worst_drift = 0, worst_froude = 0;  // max |V/V0 - 1|, max Froude number
  std::string failure;
};

// Steps `steps` times with a budget and a table row every tenth of the run.
LbmLongRun run_lbm_long(Solver& s, const LbmStress& st, long steps, double v0, Table& t) {
  LbmLongRun lr;
  Progress bar("stress dam_break.json (lbm)", steps);
  auto t0 = std::chrono::steady_clock::now();
  for (long i = 1; i <= steps; ++i) {
    s.step();
    if (i % (steps / 10) != 0) continue;
    const double ms = seconds_since(t0) * 1e3 / static_cast<double>(steps / 10);
    const LbmBudget b = lbm_budget(s, st.cell, st.g);
    if (!b.finite) {
      lr.failure = "NON-FINITE, NOT REPORTED at step " + std::to_string(i);
      break;
    }
    lr.worst_drift = std::max(lr.worst_drift, std::abs(b.volume_m3 / v0 - 1));
    lr.worst_froude = std::max(lr.worst_froude, b.max_froude);
    t.add({std::to_string(i), num(s.time(), 6), num(b.volume_m3, 8), num(b.volume_m3 / v0 - 1, 3), num(b.max_speed, 4),
           num(b.max_froude, 4), num(b.min_depth, 4), fmt("%.3f", ms)});
    bar.update(i);
    t0 = std::chrono::steady_clock::now();
  }
  return lr;
}

void lbm_long_run(Context& ctx, const LbmStress& st) {
  const long steps = ctx.quick ? 2000 : 100000;
  auto s = make_solver(parse_scene_text(st.base.dump(), "scenes/dam_break.json"));
  const double dt = s->meta()["dt"].get<double>();
  Table t({"step", "t s", "volume m^3", "V/V0 - 1", "max |u| m/s", "max Froude", "min depth m", "ms/step"});
  const LbmBudget b = lbm_budget(*s, st.cell, st.g);
  const double v0 = b.volume_m3;
  t.add({"0", "0", num(v0, 8), "0", num(b.max_speed, 4), num(b.max_froude, 4), num(b.min_depth, 4), "-"});
  LbmLongRun lr;
  lr.worst_froude = b.max_froude;
  try {
    const LbmLongRun r = run_lbm_long(*s, st, steps, v0, t);
    lr.worst_drift = r.worst_drift;
    lr.worst_froude = std::max(lr.worst_froude, r.worst_froude);
    lr.failure = r.failure;
  } catch (const std::exception& e) {
    lr.failure = e.what();
  }
  // closed walls: the volume is conserved exactly by the scheme (sum of populations); float
  // rounding of ~4e4 cells random-walks far below 1e-4 over 1e5 steps
  const bool bounded = lr.failure.empty() && lr.worst_drift <= 1e-4;
  const std::string verdict =
      bounded ? fmt("bounded (volume drift at most %.2g, Froude at most %.3f)", lr.worst_drift, lr.worst_froude)
              : "NOT bounded: " + (lr.failure.empty() ? fmt("volume drift %.2g", lr.worst_drift) : lr.failure);
  ctx.report("stress",
             fmt("%ld steps of dam_break.json (LBM, dt %.4g s, %.0f s simulated): budgets; verdict: %s", steps, dt,
                 steps * dt, verdict.c_str()),
             t);
  ctx.expect(bounded, "stress: dam_break.json (LBM) long run stays finite and conserves its volume to 1e-4");
}

// ---- 2. the edge of its limits: every input either runs finite or is refused / stopped by name
struct Edge {
  std::string name;
  std::function<void(nlohmann::json&)> edit;
};

Edge cfl_edge(double c) {
  return {fmt("CFL %.2f (dt from the fastest initial signal)", c), [c](nlohmann::json& j) {
            j["lbm"]["time"] = {{"cfl", c}};
          }};
}
Edge ratio_edge(double r) {
  return {fmt("dam h_L/h_R = %.3g (10 m upstream)", r),
          [r](nlohmann::json& j) { j["lbm"]["initial"]["dam"]["right_depth_m"] = 10.0 / r; }};
}
Edge tau_edge(double t) {
  return {fmt("tau = %.4g (viscosity from tau)", t), [t](nlohmann::json& j) {
            j["lbm"]["water"].erase("viscosity_m2s");
            j["lbm"]["water"]["tau"] = t;
          }};
}

void lbm_edges(Context& ctx, const LbmStress& st) {
  const std::vector<Edge> cases = {cfl_edge(0.25),   cfl_edge(0.5),    cfl_edge(0.75),  cfl_edge(1.0),
                                   cfl_edge(1.5),    ratio_edge(1.43), ratio_edge(2.0), ratio_edge(5.0),
                                   ratio_edge(10.0), tau_edge(0.5001), tau_edge(0.51),  tau_edge(0.6),
                                   tau_edge(2.0),    tau_edge(10.0)};
  const long steps = ctx.quick ? 300 : 3000;
  Table t({"input", "steps", "max Froude", "V/V0 - 1", "outcome"});
  Progress bar("stress lbm limits", static_cast<long long>(cases.size()));
  long done = 0;
  for (const Edge& c : cases) {
    nlohmann::json j = st.base;
    c.edit(j);
    LbmBudget b0, b1;
    std::string outcome = run_lbm(j, 0, &b0);
    if (outcome.rfind("finite", 0) == 0) outcome = run_lbm(j, steps, &b1);
    const bool ran = outcome.rfind("finite", 0) == 0;
    t.add({c.name, std::to_string(steps), ran ? num(b1.max_froude, 4) : "-",
           ran ? num(b1.volume_m3 / b0.volume_m3 - 1, 3) : "-", outcome});
    ctx.expect(contained(outcome), "stress: LBM " + c.name + " did not go non-finite silently");
    bar.update(++done);
  }
  ctx.report("stress",
             "LBM at the edge of its limits (dam_break.json edited): runs finite, or is refused before the run "
             "naming the JSON path, or stops naming the cell or stage",
             t);
}

}  // namespace

// The LBM parts of the stress section, in the order they are printed.
void stress_lbm(Context& ctx) {
  LbmStress st;
  st.base = lbm_scene_json("dam_break.json");
  st.cell = st.base["lbm"]["grid"]["cell_m"].get<double>();
  st.g = st.base["lbm"]["water"]["gravity_mps2"].get<double>();
  using Part = void (*)(Context&, const LbmStress&);
  const Part parts[] = {lbm_long_run, lbm_edges};
  for (const Part part : parts) part(ctx, st);
}

}  // namespace huygens::bench
