// Section "stress", SPH part: the SPH solver (paper 000 after MCG03) on its hardest
// shipped scene, scenes/sph_dam_break.json (the Martin & Moyce column hitting the far wall),
// for 10 s of simulated time (--quick: 0.5 s) with budgets printed every tenth of the run
// (mechanical energy against its start, largest speed against sqrt(2 g H), largest density
// error, particles outside the container, dt) and a verdict; a search for the largest stable
// fixed time step (the adaptive conditions switched off, dt swept up to the failure, whose mode
// is named); and extreme inputs (a block dropped from the top of the container, gravity 10 g).
// Nothing may go non-finite silently: a run stays finite and contained, or stops with
// NonFiniteError naming the stage.
#include <algorithm>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/sph/sph_solver.hpp"
#include "huygens/sph/system.hpp"

namespace huygens::bench {

namespace {

SphParams sph_params_of(const std::string& name) {
  return parse_sph_scene(parse_scene_text(shipped_scene(name), name)).params;
}

struct SphBudget {
  double energy_j = 0;      // kinetic + potential (gravity's lowest corner = 0), unit J
  double max_speed = 0;     // unit m/s
  double density_err = 0;   // max (rho / rho0 - 1): compression (free-surface particles read low)
  std::size_t outside = 0;  // particles outside the container
  bool finite = true;
};

SphBudget sph_budget(const SphSystem& s) {
  SphBudget b;
  const auto& p = s.params();
  const double m = s.mass();
  const auto x = s.x(), y = s.y(), z = s.z(), vx = s.vx(), vy = s.vy(), vz = s.vz(), rho = s.density();
  for (std::size_t i = 0; i < s.count(); ++i) {
    const double v2 = double(vx[i]) * vx[i] + double(vy[i]) * vy[i] + double(vz[i]) * vz[i];
    if (!std::isfinite(x[i] + y[i] + z[i]) || !std::isfinite(v2) || !std::isfinite(rho[i])) b.finite = false;
    // potential energy above the container's lowest corner along the gravity vector
    const double r[3] = {x[i], y[i], z[i]};
    double pe = 0;
    for (int a = 0; a < 3; ++a)
      pe += std::abs(double(p.gravity_mps2[a])) * (p.gravity_mps2[a] < 0 ? r[a] : p.container_m[a] - r[a]);
    b.energy_j += m * (0.5 * v2 + pe);
    b.max_speed = std::max(b.max_speed, std::sqrt(v2));
    b.density_err = std::max(b.density_err, double(rho[i]) / p.rest_density_kgpm3 - 1);
    if (x[i] < 0 || y[i] < 0 || z[i] < 0 || x[i] > p.container_m[0] || y[i] > p.container_m[1] ||
        z[i] > p.container_m[2])
      ++b.outside;
  }
  return b;
}

// Height of the fluid blocks' tallest top (unit: m): the H of sqrt(2 g H).
double fluid_height(const SphParams& p) {
  double h = 0;
  for (const auto& b : p.fluid) h = std::max(h, double(b.max_m[2]));
  return h;
}

struct SphRun {
  std::string outcome;
  SphBudget worst;  // largest speed, density error and outside count over the checks
  double energy_ratio = 0, t_end = 0;
  std::int64_t steps = 0;
};

// Runs to `t_end` seconds, checking the budget `checks` times; the outcome names how it ended.
SphRun run_sph(const SphParams& p, double t_end, int checks) {
  SphRun r;
  try {
    SphSystem s(p);
    s.refresh();
    const double e0 = sph_budget(s).energy_j;
    for (int c = 1; c <= checks; ++c) {
      while (s.time() < t_end * c / checks) {
        s.step();
        const SphBudget b = sph_budget(s);  // every step: impacts last a few steps
        if (!b.finite) {
          r.outcome = "NON-FINITE, NOT REPORTED";
          return r;
        }
        r.worst.max_speed = std::max(r.worst.max_speed, b.max_speed);
        r.worst.density_err = std::max(r.worst.density_err, b.density_err);
        r.worst.outside = std::max(r.worst.outside, b.outside);
        r.energy_ratio = std::max(r.energy_ratio, b.energy_j / e0);
      }
    }
    r.t_end = s.time();
    r.steps = s.steps();
    r.outcome = r.worst.outside         ? "LEAKED"
                : r.energy_ratio > 1.05 ? fmt("unstable: energy grew %.3g x", r.energy_ratio)
                                        : "finite and contained";
  } catch (const NonFiniteError& e) {
    r.outcome = std::string("stopped: ") + e.what();
  } catch (const std::invalid_argument& e) {
    r.outcome = std::string("refused before the run: ") + e.what();
  }
  return r;
}

// What every part of the SPH stress shares: the shipped scene and its speed scale.
struct SphStress {
  SphParams base;
  double H = 0, v_ref = 0;  // fluid height (m) and sqrt(2 g H) (m/s)
};

// ---- 1. the long run of the hardest shipped SPH scene
struct SphLongRun {
  double worst_e = 1, worst_v = 0, worst_rho = 0;  // E / E0, speed / sqrt(2gH), rho / rho0 - 1
  std::size_t worst_out = 0;
  std::string failure;
};

// Runs to t_end in ten parts, a table row each: speed and compression as maxima over the part
// (every step: impacts last a few steps), E and the particles outside at its end.
SphLongRun run_sph_long(SphSystem& s, double t_end, double v_ref, double e0, Table& t) {
  SphLongRun lr;
  Progress bar("stress sph_dam_break.json", 1000);
  for (int c = 1; c <= 10; ++c) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::int64_t n0 = s.steps();
    double iv = 0, irho = 0;  // maxima over this tenth of the run
    while (s.time() < t_end * c / 10) {
      s.step();
      const SphBudget k = sph_budget(s);
      iv = std::max(iv, k.max_speed / v_ref);
      irho = std::max(irho, k.density_err);
      lr.worst_e = std::max(lr.worst_e, k.energy_j / e0);
      if (s.steps() % 64 == 0) bar.update(static_cast<long long>(1000 * s.time() / t_end));
    }
    const double ms = seconds_since(t0) * 1e3 / static_cast<double>(std::max<std::int64_t>(s.steps() - n0, 1));
    const SphBudget b = sph_budget(s);
    if (!b.finite) {
      lr.failure = "NON-FINITE, NOT REPORTED";
      break;
    }
    lr.worst_e = std::max(lr.worst_e, b.energy_j / e0);
    lr.worst_v = std::max(lr.worst_v, iv);
    lr.worst_rho = std::max(lr.worst_rho, irho);
    lr.worst_out = std::max(lr.worst_out, b.outside);
    t.add({num(s.time(), 4), std::to_string(s.steps()), num(s.dt_stats().min, 3), num(b.energy_j / e0, 5), num(iv, 4),
           num(100 * irho, 3), std::to_string(b.outside), fmt("%.3f", ms)});
  }
  return lr;
}

void sph_long_run(Context& ctx, const SphStress& st) {
  const double t_end = ctx.quick ? 0.5 : 10.0;
  SphSystem s(st.base);
  s.refresh();
  Table t({"t s", "steps", "dt min s", "E / E0", "max speed / sqrt(2gH)", "max rho/rho0 - 1 %", "outside", "ms/step"});
  const SphBudget b = sph_budget(s);
  t.add({"0", "0", "-", "1", num(b.max_speed / st.v_ref, 4), num(100 * b.density_err, 3), std::to_string(b.outside),
         "-"});
  SphLongRun lr;
  try {
    lr = run_sph_long(s, t_end, st.v_ref, b.energy_j, t);
  } catch (const NonFiniteError& e) {
    lr.failure = e.what();
  }
  // bounded: the mechanical energy of a dam break only falls (viscous and artificial
  // dissipation); the weakly compressible fluid stores a little elastic energy, so a rise of
  // more than 1 % over the start would be the integrator feeding energy in
  const bool bounded = lr.failure.empty() && lr.worst_out == 0 && lr.worst_e <= 1.01;
  const std::string verdict =
      bounded
          ? fmt("bounded (E/E0 at most %.4f, no particle outside, max speed %.3f sqrt(2gH), compression up to %.2f %%)",
                lr.worst_e, lr.worst_v, 100 * lr.worst_rho)
          : "NOT bounded: " +
                (lr.failure.empty() ? fmt("E/E0 %.4f, %zu outside", lr.worst_e, lr.worst_out) : lr.failure);
  ctx.report("stress",
             fmt("%.3g s of sph_dam_break.json (%zu particles, H = %.4g m): budgets; verdict: %s "
                 "(targets: max speed < 1.5 sqrt(2gH), density error ~1 %%)",
                 t_end, s.count(), st.H, verdict.c_str()),
             t);
  ctx.expect(bounded, "stress: sph_dam_break.json long run stays finite, contained, energy not growing");
}

// ---- 2. largest stable fixed time step: the adaptive conditions off, dt = dt_max swept upwards
void sph_fixed_dt(Context& ctx, const SphStress& st) {
  SphSystem probe(st.base);
  probe.step();
  const double dt_adaptive = probe.dt_stats().last;
  Table t(
      {"dt s", "dt / adaptive dt", "steps", "E max / E0", "max speed / sqrt(2gH)", "max rho/rho0 - 1 %", "outcome"});
  const double t_end = ctx.quick ? 0.1 : 0.4;
  double largest_ok = 0;
  std::string first_failure;
  for (double f : {1.0, 2.0, 4.0, 8.0, 16.0}) {
    SphParams p = st.base;
    p.cfl = p.force_factor = p.viscous_factor = 1e6f;  // dt = dt_max
    p.dt_max_s = static_cast<float>(f * dt_adaptive);
    const SphRun r = run_sph(p, t_end, 10);
    const bool ok = r.outcome == "finite and contained";
    if (ok && first_failure.empty()) largest_ok = p.dt_max_s;
    if (!ok && first_failure.empty()) first_failure = r.outcome;
    t.add({num(p.dt_max_s, 3), num(f, 3), std::to_string(r.steps), num(r.energy_ratio, 4),
           num(r.worst.max_speed / st.v_ref, 4), num(100 * r.worst.density_err, 3), r.outcome});
    ctx.expect(
        ok || r.outcome.rfind("stopped: ", 0) == 0 || r.outcome == "LEAKED" || r.outcome.rfind("unstable", 0) == 0,
        fmt("stress: SPH at fixed dt %.3g s did not go non-finite silently", p.dt_max_s));
  }
  ctx.report("stress",
             fmt("SPH largest stable fixed dt over %.2g s of the dam break: %.3g s (%.3g x the adaptive step); "
                 "first failure: %s",
                 t_end, largest_ok, largest_ok / dt_adaptive,
                 first_failure.empty() ? "none up to 16 x" : first_failure.c_str()),
             t);
  ctx.expect(largest_ok >= dt_adaptive, "stress: the adaptive dt of the dam break is stable");
}

// ---- 3. extreme inputs
struct SphExtreme {
  std::string name;
  std::function<void(SphParams&)> edit;
  double t_quick = 0.1;  // simulated time of the --quick run (unit: s)
};

const std::vector<SphExtreme> kSphExtremes = {
    {"block dropped from the top of the container onto a shallow layer",
     [](SphParams& p) {
       const auto c = p.container_m;
       const float s = p.spacing_m;
       p.fluid.clear();
       p.fluid.push_back({{0.f, 0.f, 0.f}, {c[0], c[1], 4 * s}});
       p.fluid.push_back({{0.4f * c[0], 0.f, c[2] - 0.3f * c[2]}, {0.6f * c[0], c[1], c[2]}});
     },
     0.25},  // it lands after about 0.18 s
    {"gravity 10 g", [](SphParams& p) { p.gravity_mps2[2] *= 10.f; }},
    {"sideways gravity (container tipped over)",
     [](SphParams& p) {
       p.gravity_mps2 = {9.81f, 0.f, 0.f};
     }},
};

void sph_extremes(Context& ctx, const SphStress& st) {
  Table t({"input", "t s", "steps", "E max / E0", "max speed m/s", "max rho/rho0 - 1 %", "outcome"});
  for (const SphExtreme& c : kSphExtremes) {
    SphParams p = st.base;
    c.edit(p);
    const SphRun r = run_sph(p, ctx.quick ? c.t_quick : 0.5, 10);
    t.add({c.name, num(r.t_end, 4), std::to_string(r.steps), num(r.energy_ratio, 4), num(r.worst.max_speed, 4),
           num(100 * r.worst.density_err, 3), r.outcome});
    ctx.expect(r.outcome == "finite and contained" || r.outcome.rfind("stopped: ", 0) == 0 ||
                   r.outcome.rfind("refused", 0) == 0,
               "stress: SPH " + c.name + " stays finite and contained (or stops naming the stage)");
  }
  ctx.report("stress", "SPH extreme inputs on sph_dam_break.json", t);
}

}  // namespace

// The SPH parts of the stress section, in the order they are printed.
void stress_sph(Context& ctx) {
  SphStress st;
  st.base = sph_params_of("sph_dam_break.json");
  st.H = fluid_height(st.base);
  st.v_ref = std::sqrt(2 * std::abs(st.base.gravity_mps2[2]) * st.H);
  using Part = void (*)(Context&, const SphStress&);
  const Part parts[] = {sph_long_run, sph_fixed_dt, sph_extremes};
  for (const Part part : parts) part(ctx, st);
}

}  // namespace huygens::bench
