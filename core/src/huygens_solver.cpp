#include "huygens/huygens_solver.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <variant>

#include "huygens/finite.hpp"
#include "huygens/validation.hpp"

namespace huygens {

namespace {

constexpr double kBig = 1e6;

void refuse_unsupported(const JsonIn& root) {
  if (root.has("stokes") && root.boolean("stokes", false))
    root.fail("stokes", "second-order Stokes height is not yet supported by this build (use false)");
  if (root.has("ships")) {
    if (!root.raw()["ships"].is_null() && !root.raw()["ships"].is_array()) root.fail("ships", "expected an array");
    if (!root.array("ships").empty()) root.fail("ships", "ships are not yet supported by this build");
  }
  if (root.optional_object("wind")) root.fail("wind", "wind is not yet supported by this build");
  if (root.optional_object("render")) root.fail("render", "render settings are not yet supported by this build");
}

}  // namespace

HuygensScene parse_huygens_scene(const Scene& scene, const RunOptions& options) {
  const JsonIn root = scene.root();
  root.allow_only(
      {"solver", "description", "grid", "water", "time", "stokes", "initial", "drops", "ships", "wind", "render"});
  if (root.has("description")) root.string("description", "");
  HuygensScene out;
  HuygensParams& p = out.params;
  p.effort = options.measure_plans ? PlanEffort::measure : PlanEffort::estimate;

  // grid: n (power of two), length_m, margin, cutoff
  const JsonIn grid = root.object("grid");
  grid.allow_only({"n", "length_m", "margin", "cutoff", "cutoff_time_s"});
  const long long n = grid.integer("n", 16, 16384);
  if ((n & (n - 1)) != 0) grid.fail("n", "must be a power of two (FFT grid), got " + std::to_string(n));
  p.n = static_cast<int>(n);
  p.length_m = grid.number("length_m", 1e-6, kBig);
  const long long m = grid.integer("margin", 0, 16384);
  if (2 * m >= n) grid.fail("margin", "margin too large for n = " + std::to_string(n) + ": 2 * margin must be < n");
  p.margin = static_cast<int>(m);
  p.absorber = grid.boolean("cutoff", true) ? Absorber::paper_quadratic : Absorber::off;
  // 0 (default): paper 004's cutoff once per step; tau > 0: one paper cutoff per tau seconds
  p.cutoff_time_s = grid.number("cutoff_time_s", 0.0, 0.0, 1e6);
  if (p.absorber == Absorber::paper_quadratic && m < 1) grid.fail("margin", "the cutoff needs margin >= 1");

  // water (all optional): depth_m null or absent = deep water
  if (auto water = root.optional_object("water")) {
    water->allow_only({"gravity", "surface_tension", "density", "depth_m"});
    p.water.gravity = water->number("gravity", 9.81, 0.0, 1e3);
    p.water.surface_tension = water->number("surface_tension", 0.072, 0.0, 10.0);
    p.water.density = water->number("density", 1000.0, 1e-3, 1e5);
    if (auto d = water->optional_number("depth_m", 0.0, kBig)) {
      if (*d <= 0) water->fail("depth_m", "depth must be > 0 (null for deep water)");
      p.water.depth_m = *d;
    }
    if (p.water.gravity == 0 && p.water.surface_tension == 0)
      water->fail("gravity", "gravity and surface tension are both 0: no waves");
  }

  // time: dt > 0 (any value is stable), display_per_step
  const JsonIn time = root.object("time");
  time.allow_only({"dt", "display_per_step"});
  p.dt = time.number("dt", 0.0, 1e3);
  if (p.dt <= 0) time.fail("dt", "dt must be > 0");
  out.display_per_step = static_cast<int>(time.integer("display_per_step", 1, 1, 1000));

  refuse_unsupported(root);

  const double len = p.length_m;
  auto position = [&](const JsonIn& o, const char* key) { return o.number(key, 0.0, len); };
  for (const JsonIn& e : root.array("initial")) {
    const std::string type = e.string("type", "", {"gaussian", "plane_wave"});
    if (type.empty()) e.fail("type", "missing required string (\"gaussian\" or \"plane_wave\")");
    if (type == "gaussian") {
      e.allow_only({"type", "x_m", "y_m", "sigma_m", "amplitude_m"});
      GaussianSource g;
      g.x_m = position(e, "x_m");
      g.y_m = position(e, "y_m");
      g.sigma_m = e.number("sigma_m", 0.0, len);
      if (g.sigma_m <= 0) e.fail("sigma_m", "sigma must be > 0");
      g.amplitude_m = e.number("amplitude_m", -kBig, kBig);
      out.initial_gaussians.push_back(g);
    } else {
      e.allow_only({"type", "wavelength_m", "amplitude_m", "direction_deg"});
      PlaneWaveSource w;
      w.wavelength_m = e.number("wavelength_m", 0.0, kBig);
      if (w.wavelength_m < 2.0 * len / n)
        e.fail("wavelength_m", "wavelength below two grid cells (" + std::to_string(2.0 * len / n) + " m)");
      w.amplitude_m = e.number("amplitude_m", -kBig, kBig);
      w.direction_deg = e.number("direction_deg", 0.0, -360.0, 360.0);
      out.initial_plane_waves.push_back(w);
    }
  }
  for (const JsonIn& e : root.array("drops")) {
    e.allow_only({"t", "x_m", "y_m", "radius_m", "depth_m"});
    GaussianSource g;
    g.t = e.number("t", 0.0, 1e9);
    g.x_m = position(e, "x_m");
    g.y_m = position(e, "y_m");
    g.sigma_m = e.number("radius_m", 0.0, len);
    if (g.sigma_m <= 0) e.fail("radius_m", "radius must be > 0");
    g.amplitude_m = -e.number("depth_m", -kBig, kBig);
    out.drops.push_back(g);
  }
  std::stable_sort(out.drops.begin(), out.drops.end(),
                   [](const GaussianSource& a, const GaussianSource& b) { return a.t < b.t; });
  // source tables (2 N^2 floats) always: UI drops may arrive at any step and must not allocate
  p.runtime_sources = true;
  if (auto e = huygens_params_error(p); !e.empty()) root.fail_here(e);
  return out;
}

HuygensSolver::HuygensSolver(const HuygensScene& scene) : scene_(scene), prop_(scene_.params) {
  for (const auto& w : scene_.initial_plane_waves) prop_.add_plane_wave(w.wavelength_m, w.amplitude_m, w.direction_deg);
  for (const auto& g : scene_.initial_gaussians) prop_.add_gaussian(g.x_m, g.y_m, g.sigma_m, g.amplitude_m);
  // drops at t <= 0 are part of the initial state
  while (next_drop_ < scene_.drops.size() && scene_.drops[next_drop_].t <= 0.0) {
    const auto& d = scene_.drops[next_drop_++];
    prop_.add_gaussian(d.x_m, d.y_m, d.sigma_m, d.amplitude_m, -d.t);
  }
  // the drops stage exists when the scene has drops or the UI sends one (registered here)
  st_drops_ = prop_.stats().add("drops", 2 * static_cast<std::uint64_t>(prop_.n()) * prop_.n() * sizeof(float));
  prop_.height();
  if (!all_finite(prop_.eta())) throw NonFiniteError("initial", 0);
  prop_.stats().reset_counts();
}

void HuygensSolver::step() {
  prop_.propagate();
  prop_.cutoff();
  prop_.spectrum();
  if (next_drop_ < scene_.drops.size()) {
    // drops released in (t, t + dt] enter with the phase they have gained by t + dt
    const double t1 = static_cast<double>(prop_.steps() + 1) * scene_.params.dt;
    const double eps = 1e-9 * scene_.params.dt;
    if (scene_.drops[next_drop_].t <= t1 + eps) {
      StageTimer timer(prop_.stats()[st_drops_]);
      while (next_drop_ < scene_.drops.size() && scene_.drops[next_drop_].t <= t1 + eps) {
        const auto& d = scene_.drops[next_drop_++];
        prop_.add_gaussian(d.x_m, d.y_m, d.sigma_m, d.amplitude_m, std::max(0.0, t1 - d.t));
      }
      // drops are rare: check their output in full
      if (!all_finite(prop_.spectrum_view())) throw NonFiniteError("drops", prop_.steps() + 1);
    }
  }
  prop_.height();
  prop_.end_step();
}

bool HuygensSolver::apply(const Command& c) {
  const auto* d = std::get_if<cmd::Drop>(&c);
  if (!d) return false;
  const double len = scene_.params.length_m;
  if (!(d->x_m >= 0 && d->x_m <= len && d->y_m >= 0 && d->y_m <= len && d->radius_m > 0 && std::isfinite(d->depth_m)))
    return false;
  StageTimer timer(prop_.stats()[st_drops_]);
  prop_.add_gaussian(d->x_m, d->y_m, d->radius_m, -static_cast<double>(d->depth_m));
  if (!all_finite(prop_.spectrum_view())) throw NonFiniteError("drops", prop_.steps());
  prop_.height();
  return true;
}

std::vector<OutputField> HuygensSolver::outputs() {
  const std::size_t v = static_cast<std::size_t>(prop_.visible_size());
  return {OutputField{"eta", {v, v}, prop_.eta()}};
}

nlohmann::json HuygensSolver::meta() const {
  const auto& p = scene_.params;
  const int m = p.margin, n = p.n;
  const double dx = p.length_m / n;
  return nlohmann::json{
      {"solver", "huygens"},
      {"n", n},
      {"length_m", p.length_m},
      {"dx", dx},
      {"dt", p.dt},
      {"margin", m},
      {"display_per_step", scene_.display_per_step},
      {"cutoff", p.absorber == Absorber::paper_quadratic},
      {"cutoff_time_s", p.cutoff_time_s},
      {"rotation", p.rotation == Rotation::lifting ? "lifting" : "complex"},
      {"grid", {{"n", n}, {"length_m", p.length_m}, {"margin", m}, {"dx", dx}}},
      {"water",
       {{"gravity", p.water.gravity},
        {"surface_tension", p.water.surface_tension},
        {"density", p.water.density},
        {"depth_m", p.water.deep() ? nlohmann::json(nullptr) : nlohmann::json(p.water.depth_m)}}},
      {"visible",
       {{"rows", {m, n - m}},
        {"cols", {m, n - m}},
        {"shape", {n - 2 * m, n - 2 * m}},
        {"origin_m", {m * dx, m * dx}},
        {"note",
         "index ranges are half-open [start, end) into the full N x N grid; origin_m is (x, y) of cell (0, 0)"}}},
      {"fields", {{"eta", "first-order elevation Re IFFT[i k/omega Z^] (m), rows = y, cols = x"}}},
      {"transforms_per_step", prop_.transforms_per_step()},
  };
}

std::unique_ptr<Solver> make_huygens_solver(const Scene& scene, const RunOptions& options) {
  return std::make_unique<HuygensSolver>(parse_huygens_scene(scene, options));
}

}  // namespace huygens
