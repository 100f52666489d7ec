// Validation cases of the shallow-water LBM (paper 002): wave speed, mass, lake at rest over the
// Goutal-Maurel bump, Stoker dam breaks and their convergence, the h_L/h_R = 10 dam, and the
// Strouhal number of a cylinder wake. `huygens validate` prints them; the tests run cheaper ones.
#include "huygens/validation/lbm_cases.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "huygens/common/report.hpp"
#include "huygens/lbm/shallow.hpp"
#include "huygens/lbm/stoker.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/validation/validation.hpp"

namespace huygens {

namespace {

constexpr double kG = 9.81;

// Viscosity that gives relaxation time tau for cell dx and step dt.
double nu_for_tau(double tau, double dx, double dt) { return (tau - 0.5) * dx * dx / (3.0 * dt); }

LbmFields fields(int rows, int cols) {
  LbmFields f;
  const std::size_t n = static_cast<std::size_t>(rows) * cols;
  f.bed_m.assign(n, 0.0f);
  f.depth_m.assign(n, 0.0f);
  f.ux_mps.assign(n, 0.0f);
  f.uy_mps.assign(n, 0.0f);
  return f;
}

}  // namespace

LbmDamBreakResult lbm_dam_break_1d(double ratio, int cells, double tau, double cfl, bool froude_check) {
  LbmDamBreakResult out;
  const double length = 100.0, x0 = 50.0, hl = 1.0, hr = hl / ratio;
  const auto st = stoker_solve({hl, hr, kG});
  LbmParams p;
  p.cols = cells;
  p.rows = 1;
  p.cell_m = length / cells;
  p.dt_s = cfl * p.cell_m / st.max_signal_speed_mps;
  p.viscosity_m2s = nu_for_tau(tau, p.cell_m, p.dt_s);
  p.bottom = p.top = LbmSide::periodic;
  p.expected_signal_speed_mps = st.max_signal_speed_mps;
  out.froude = st.middle_velocity_mps / std::sqrt(kG * st.middle_depth_m);
  if (froude_check) p.expected_froude = out.froude;
  LbmFields f = fields(1, cells);
  for (int c = 0; c < cells; ++c) f.depth_m[c] = static_cast<float>((c + 0.5) * p.cell_m < x0 ? hl : hr);
  const double t_end = std::min(45.0 / -st.fan_head_speed_mps, 45.0 / st.shock_speed_mps);
  out.steps = static_cast<std::int64_t>(std::llround(t_end / p.dt_s));
  try {
    LbmShallow sim(p, f);
    const auto t0 = std::chrono::steady_clock::now();
    try {
      sim.run(out.steps);
    } catch (const std::exception& e) {
      out.stopped = e.what();
    }
    out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.time_s = sim.time_s();
    out.done_steps = sim.steps();
    double err = 0, norm = 0;
    for (int c = 0; c < cells; ++c) {
      const double ex = st.depth(((c + 0.5) * p.cell_m - x0) / out.time_s);
      err += std::abs(sim.depth_at(0, c) - ex);
      norm += ex;
    }
    out.l1_relative = out.stopped.empty() ? err / norm : NAN;
  } catch (const LbmRefused& e) {
    out.refused = e.what();
    out.l1_relative = NAN;
  }
  return out;
}

LbmLakeResult lbm_lake_at_rest(std::int64_t steps, LbmBedForce force) {
  const int cols = 250, rows = 4;
  const double eta = 0.7;
  LbmParams p;
  p.cols = cols;
  p.rows = rows;
  p.cell_m = 25.0 / cols;
  p.dt_s = 0.4 * p.cell_m / std::sqrt(kG * eta);
  p.viscosity_m2s = nu_for_tau(0.6, p.cell_m, p.dt_s);
  p.bed_force = force;
  LbmFields f = fields(rows, cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const double x = (c + 0.5) * p.cell_m;
      const double z = (x > 8 && x < 12) ? 0.2 - 0.05 * (x - 10) * (x - 10) : 0.0;
      f.bed_m[r * cols + c] = static_cast<float>(z);
      f.depth_m[r * cols + c] = static_cast<float>(eta - z);
    }
  LbmShallow sim(p, f);
  sim.run(steps);
  LbmLakeResult res;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const auto u = sim.velocity_at(r, c);
      res.max_speed_mps = std::max(res.max_speed_mps, std::hypot(double(u[0]), double(u[1])));
      res.max_surface_error_m =
          std::max(res.max_surface_error_m, std::abs(double(sim.depth_at(r, c)) + f.bed_m[r * cols + c] - eta));
    }
  return res;
}

double lbm_mass_drift(int rows, int cols, std::int64_t steps) {
  LbmParams p;
  p.cols = cols;
  p.rows = rows;
  p.cell_m = 1.0;
  p.dt_s = 0.4 / std::sqrt(kG * 1.2);
  p.viscosity_m2s = nu_for_tau(0.6, p.cell_m, p.dt_s);
  LbmFields f = fields(rows, cols);
  const double w = std::max(2.0, cols / 6.0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const double x = c + 0.5, y = r + 0.5;
      const double bx = x - 0.6 * cols, by = y - 0.5 * rows, hx = x - 0.3 * cols, hy = y - 0.4 * rows;
      const double z = 0.3 * std::exp(-(bx * bx + by * by) / (2 * w * w));
      f.bed_m[r * cols + c] = static_cast<float>(z);
      f.depth_m[r * cols + c] = static_cast<float>(1.0 + 0.1 * std::exp(-(hx * hx + hy * hy) / (2 * w * w)) - z);
    }
  LbmShallow sim(p, f);
  const double v0 = sim.volume_m3();
  sim.run(steps);
  return (sim.volume_m3() - v0) / v0;
}

double lbm_wave_speed_ratio(int cells) {
  const double h0 = 1.0, amp = 1e-4, c0 = std::sqrt(kG * h0), sigma = 20.0;
  LbmParams p;
  p.cols = cells;
  p.rows = 1;
  p.cell_m = 1.0;
  p.dt_s = 0.4 * p.cell_m / c0;
  p.viscosity_m2s = nu_for_tau(0.6, p.cell_m, p.dt_s);
  p.bottom = p.top = LbmSide::periodic;
  LbmFields f = fields(1, cells);
  const double xc = 0.5 * cells;
  for (int c = 0; c < cells; ++c) {
    const double s = (c + 0.5 - xc) / sigma;
    f.depth_m[c] = static_cast<float>(h0 + amp * std::exp(-0.5 * s * s));
  }
  LbmShallow sim(p, f);
  auto centroid = [&]() {
    double m = 0, mx = 0;
    for (int c = static_cast<int>(xc); c < cells; ++c) {
      const double d = sim.depth_at(0, c) - h0;
      m += d;
      mx += d * (c + 0.5);
    }
    return mx / m;
  };
  // Separate the halves (5 sigma apart), then travel until the front half is 4 sigma from the wall.
  const auto n1 = static_cast<std::int64_t>(2.5 * sigma / 0.4);
  const auto n2 = static_cast<std::int64_t>((0.5 * cells - 4 * sigma) / 0.4);
  sim.run(n1);
  const double x1 = centroid(), t1 = sim.time_s();
  sim.run(n2 - n1);
  const double x2 = centroid(), t2 = sim.time_s();
  return (x2 - x1) * p.cell_m / (t2 - t1) / c0;
}

namespace {

// Flow past a cylinder (D = 16 cells, Re = U D / nu = 100, Froude 0.3, blockage D/W = 0.1) in a
// free-slip channel with a given inflow discharge (the setting of scenes/channel.json): the
// Strouhal number f D / U of the periodic wake from zero crossings of the transverse velocity
// 3 D behind the cylinder. Returns St, or NaN when the wake is not periodic.
double cylinder_strouhal(std::int64_t steps, double* amplitude) {
  const int cols = 320, rows = 160, dcells = 16;
  const double dx = 0.01, h0 = 0.1, c0 = std::sqrt(kG * h0);
  LbmParams p;
  p.cols = cols;
  p.rows = rows;
  p.cell_m = dx;
  p.dt_s = 0.4 * dx / c0;
  const double e = dx / p.dt_s, u0 = 0.12 * e, d = dcells * dx;
  p.viscosity_m2s = u0 * d / 100.0;
  p.left = LbmSide::inflow;
  p.right = LbmSide::outflow;
  p.bottom = p.top = LbmSide::slip;
  p.inflow_discharge_m2s = u0 * h0;
  p.outflow_depth_m = h0;
  LbmFields f = fields(rows, cols);
  f.solid.assign(f.depth_m.size(), 0);
  const double cx = 0.8, cy = 0.5 * rows * dx + 0.5 * dx;  // slightly off centre: breaks the symmetry
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * cols + c;
      f.depth_m[i] = static_cast<float>(h0);
      f.ux_mps[i] = static_cast<float>(u0);
      const double x = (c + 0.5) * dx - cx, y = (r + 0.5) * dx - cy;
      if (x * x + y * y <= 0.25 * d * d) f.solid[i] = 1;
    }
  LbmShallow sim(p, f);
  const int pr = rows / 2, pc = static_cast<int>((cx + 3 * d) / dx);
  const std::int64_t warm = steps / 2;
  sim.run(warm);
  std::vector<double> v;
  v.reserve(static_cast<std::size_t>(steps - warm));
  for (std::int64_t s = warm; s < steps; ++s) {
    sim.step();
    v.push_back(sim.velocity_at(pr, pc)[1]);
  }
  double mean = 0, amp = 0;
  for (double x : v) mean += x / static_cast<double>(v.size());
  for (double x : v) amp = std::max(amp, std::abs(x - mean));
  *amplitude = amp / u0;
  std::vector<double> up;  // upward zero crossings, interpolated (unit: steps)
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i - 1] - mean < 0 && v[i] - mean >= 0)
      up.push_back(static_cast<double>(i - 1) + (mean - v[i - 1]) / (v[i] - v[i - 1]));
  if (up.size() < 4 || amp < 0.01 * u0) return NAN;
  const double period = (up.back() - up.front()) / static_cast<double>(up.size() - 1) * p.dt_s;
  return d / (period * u0);
}

// ---- the rows of each case ----------------------------------------------------------------------

std::vector<ValidationRow> wave_speed_rows() {
  const double r = lbm_wave_speed_ratio(2000);
  return {check("lbm_wave_speed", "pulse speed / sqrt(g h)", r, 1.0, std::abs(r - 1.0), 5e-3)};
}

std::vector<ValidationRow> mass_rows() {
  const double d = lbm_mass_drift(64, 64, 100000);
  return {check("lbm_mass", "relative volume change after 1e5 steps", d, 0.0, std::abs(d), 1e-5)};
}

std::vector<ValidationRow> lake_at_rest_rows() {
  const auto w = lbm_lake_at_rest(100000, LbmBedForce::centred);
  const auto nv = lbm_lake_at_rest(100000, LbmBedForce::naive);
  return {check("lbm_lake_at_rest", "max |u| (m/s), centred bed term", w.max_speed_mps, 0.0, w.max_speed_mps, 1e-4),
          check("lbm_lake_at_rest", "max |h + z_b - 0.7| (m), centred bed term", w.max_surface_error_m, 0.0,
                w.max_surface_error_m, 1e-5),
          // informative: the naive force must be clearly worse (error = centred / naive)
          check("lbm_lake_at_rest", "max |u| (m/s), naive bed term (must exceed centred x10)", nv.max_speed_mps,
                w.max_speed_mps, w.max_speed_mps / nv.max_speed_mps, 0.1),
          check("lbm_lake_at_rest", "max surface error (m), naive bed term (must exceed centred x10)",
                nv.max_surface_error_m, w.max_surface_error_m, w.max_surface_error_m / nv.max_surface_error_m, 0.1)};
}

// L1 error at 1024 cells and the convergence order from each doubling, h_L/h_R = 2 and 5.
std::vector<ValidationRow> stoker_rows() {
  std::vector<ValidationRow> rows;
  for (double ratio : {2.0, 5.0}) {
    const std::string name = "lbm_stoker_" + fmt("%g", ratio);
    double prev = NAN;
    for (int n : {256, 512, 1024, 2048}) {
      const auto r = lbm_dam_break_1d(ratio, n);
      if (n == 1024)
        rows.push_back(check(name, "L1 relative depth error, 1024 cells", r.l1_relative, 0.0, r.l1_relative, 5e-3));
      if (n >= 512)
        rows.push_back(check(name, fmt("convergence order %d->%d cells (error = e%d/e%d < 1)", n / 2, n, n, n / 2),
                             std::log2(prev / r.l1_relative), 1.0, r.l1_relative / prev, 1.0));
      prev = r.l1_relative;
    }
  }
  return rows;
}

// h_L/h_R = 10 is transcritical: refused before running (or finite if run); without the refusal
// the run must stop with an error, never go on silently.
std::vector<ValidationRow> stoker_10_rows() {
  const auto r = lbm_dam_break_1d(10.0, 1024);
  const bool ok = !r.refused.empty() || (r.stopped.empty() && std::isfinite(r.l1_relative));
  ValidationRow row = check(
      "lbm_stoker_10",
      r.refused.empty() ? "ran: L1 relative error, 1024 cells" : "refused before running: Froude number of the flow",
      r.refused.empty() ? r.l1_relative : r.froude, kLbmMaxFroude, ok ? 0.0 : 1.0, 0.0);
  const auto u = lbm_dam_break_1d(10.0, 1024, 0.55, 0.5, false);
  ValidationRow unchecked = check("lbm_stoker_10",
                                  u.stopped.empty() ? "refusal skipped: ran to the end, L1 relative error"
                                                    : "refusal skipped: step at which it stopped (negative depth)",
                                  u.stopped.empty() ? u.l1_relative : static_cast<double>(u.done_steps), 0.0,
                                  (!u.stopped.empty() || std::isfinite(u.l1_relative)) ? 0.0 : 1.0, 0.0);
  return {row, unchecked};
}

std::vector<ValidationRow> cylinder_rows() {
  double amp = 0;
  const double st = cylinder_strouhal(24000, &amp);
  return {check("lbm_cylinder", "wake amplitude max |v| / U at 3 D downstream (> 0.01: periodic)", amp, 0.0,
                amp > 0.01 ? 0.0 : 1.0, 0.0),
          check("lbm_cylinder", "Strouhal number f D / U", st, 0.165, std::abs(st - 0.165) / 0.165, 0.25)};
}

}  // namespace

std::vector<ValidationCase> lbm_validation_cases() {
  return {
      {"lbm_wave_speed", "lbm", "small long-wave pulse travels at sqrt(g h) (1 m deep, 2000 cells)", wave_speed_rows},
      {"lbm_mass", "lbm", "volume drift over 1e5 steps in a closed 64x64 box with a bed mound", mass_rows},
      {"lbm_lake_at_rest", "lbm",
       "still water 0.5 m above the Goutal-Maurel bump stays still for 1e5 steps (centred vs naive)",
       lake_at_rest_rows},
      {"lbm_stoker", "lbm", "1D wet dam break vs Stoker, h_L/h_R = 2 and 5: L1 at 1024 cells and convergence order",
       stoker_rows},
      {"lbm_stoker_10", "lbm", "h_L/h_R = 10 (transcritical): runs finite, or is refused before running",
       stoker_10_rows},
      {"lbm_cylinder", "lbm",
       "periodic wake behind a cylinder, Re = 100, blockage 0.1: Strouhal number (reference 0.165, "
       "Williamson 1988, unconfined; a loose check)",
       cylinder_rows},
  };
}

}  // namespace huygens
