// Section "stress", LBM part (issue 9): the shallow-water LBM (paper 002 sec. 2) on its hardest
// shipped scene, scenes/dam_break.json (a partial dam break through a 75 m breach, 10 m / 7 m),
// for 1e5 steps (--quick: 2000) with the budgets printed every tenth of the run (volume, largest
// speed and Froude number, shallowest wet cell) and a verdict; then the edge of its limits: the
// CFL number, the depth ratio of a dam and the relaxation time tau swept until the scene is refused
// before the run (SceneError naming the JSON path and the reason) or the run stops naming the
// cell (LbmDryError) or the stage (NonFiniteError). Nothing may go non-finite silently.
#include <algorithm>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench.hpp"
#include "huygens/lbm/shallow.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"

namespace huygens::bench {

namespace {

nlohmann::json lbm_scene_json(const std::string& name) {
  return nlohmann::json::parse(shipped_scene(name));
}

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
  } catch (const LbmDryError& e) {
    return std::string("stopped: ") + e.what();
  } catch (const NonFiniteError& e) {
    return std::string("stopped: ") + e.what();
  }
}

bool contained(const std::string& outcome) {
  return outcome.rfind("finite and bounded", 0) == 0 || outcome.rfind("refused before the run", 0) == 0 ||
         outcome.rfind("stopped: ", 0) == 0;
}

}  // namespace

void stress_lbm(Context& ctx) {
  const nlohmann::json base = lbm_scene_json("dam_break.json");
  const double cell = base["lbm"]["grid"]["cell_m"].get<double>();
  const double g = base["lbm"]["water"]["gravity_mps2"].get<double>();

  // 1. the long run of the hardest shipped LBM scene
  {
    const long steps = ctx.quick ? 2000 : 100000;
    auto s = make_solver(parse_scene_text(base.dump(), "scenes/dam_break.json"));
    const double dt = s->meta()["dt"].get<double>();
    Table t({"step", "t s", "volume m^3", "V/V0 - 1", "max |u| m/s", "max Froude", "min depth m", "ms/step"});
    LbmBudget b = lbm_budget(*s, cell, g);
    const double v0 = b.volume_m3;
    t.add({"0", "0", num(v0, 8), "0", num(b.max_speed, 4), num(b.max_froude, 4), num(b.min_depth, 4), "-"});
    double worst_drift = 0, worst_froude = b.max_froude;
    std::string failure;
    Progress bar("stress dam_break.json (lbm)", steps);
    auto t0 = std::chrono::steady_clock::now();
    try {
      for (long i = 1; i <= steps; ++i) {
        s->step();
        if (i % (steps / 10) == 0) {
          const double ms = seconds_since(t0) * 1e3 / static_cast<double>(steps / 10);
          b = lbm_budget(*s, cell, g);
          if (!b.finite) {
            failure = "NON-FINITE, NOT REPORTED at step " + std::to_string(i);
            break;
          }
          worst_drift = std::max(worst_drift, std::abs(b.volume_m3 / v0 - 1));
          worst_froude = std::max(worst_froude, b.max_froude);
          t.add({std::to_string(i), num(s->time(), 6), num(b.volume_m3, 8), num(b.volume_m3 / v0 - 1, 3),
                 num(b.max_speed, 4), num(b.max_froude, 4), num(b.min_depth, 4), fmt("%.3f", ms)});
          bar.update(i);
          t0 = std::chrono::steady_clock::now();
        }
      }
    } catch (const std::exception& e) {
      failure = e.what();
    }
    // closed walls: the volume is conserved exactly by the scheme (sum of populations); float
    // rounding of ~4e4 cells random-walks far below 1e-4 over 1e5 steps
    const bool bounded = failure.empty() && worst_drift <= 1e-4;
    ctx.report("stress",
               fmt("%ld steps of dam_break.json (LBM, dt %.4g s, %.0f s simulated): budgets; verdict: %s", steps,
                   dt, steps * dt,
                   bounded ? fmt("bounded (volume drift at most %.2g, Froude at most %.3f)", worst_drift,
                                 worst_froude)
                                 .c_str()
                           : ("NOT bounded: " + (failure.empty() ? fmt("volume drift %.2g", worst_drift) : failure))
                                 .c_str()),
               t);
    ctx.expect(bounded, "stress: dam_break.json (LBM) long run stays finite and conserves its volume to 1e-4");
  }

  // 2. the edge of its limits: every input either runs finite or is refused / stopped by name
  {
    struct Edge {
      std::string name;
      std::function<void(nlohmann::json&)> edit;
    };
    auto cfl = [](double c) {
      return Edge{fmt("CFL %.2f (dt from the fastest initial signal)", c),
                  [c](nlohmann::json& j) { j["lbm"]["time"] = {{"cfl", c}}; }};
    };
    auto ratio = [](double r) {
      return Edge{fmt("dam h_L/h_R = %.3g (10 m upstream)", r), [r](nlohmann::json& j) {
                    j["lbm"]["initial"]["dam"]["right_depth_m"] = 10.0 / r;
                  }};
    };
    auto tau = [](double t) {
      return Edge{fmt("tau = %.4g (viscosity from tau)", t), [t](nlohmann::json& j) {
                    j["lbm"]["water"].erase("viscosity_m2s");
                    j["lbm"]["water"]["tau"] = t;
                  }};
    };
    const std::vector<Edge> cases = {cfl(0.25),   cfl(0.5),   cfl(0.75),  cfl(1.0),    cfl(1.5),
                                     ratio(1.43), ratio(2.0), ratio(5.0), ratio(10.0), tau(0.5001),
                                     tau(0.51),   tau(0.6),   tau(2.0),   tau(10.0)};
    const long steps = ctx.quick ? 300 : 3000;
    Table t({"input", "steps", "max Froude", "V/V0 - 1", "outcome"});
    Progress bar("stress lbm limits", static_cast<long long>(cases.size()));
    long done = 0;
    for (const Edge& c : cases) {
      nlohmann::json j = base;
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
}

}  // namespace huygens::bench
