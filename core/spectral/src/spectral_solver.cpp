#include "huygens/spectral/spectral_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <variant>

#include "huygens/common/comm.hpp"
#include "huygens/common/finite.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/common/time_interp.hpp"
#include "huygens/pipeline/render_request.hpp"
#include "huygens/pipeline/solver_entry.hpp"
#include "huygens/spectral/ambient_slopes.hpp"
#include "huygens/spectral/cutoff.hpp"
#include "huygens/spectral/slab_solver.hpp"

namespace huygens {

namespace {

constexpr double kBig = 1e6;

// grid: n (power of two), length_m, margin, cutoff (bool), cutoff_time_s, round_trip_every
void parse_grid(const JsonIn& root, HuygensParams& p) {
  const JsonIn grid = root.object("grid");
  grid.allow_only({"n", "length_m", "margin", "cutoff", "cutoff_time_s", "round_trip_every"});
  const long long n = grid.integer("n", 16, 32768);  // 32768: on MPI ranks (docs/scale.md)
  if ((n & (n - 1)) != 0) grid.fail("n", "must be a power of two (FFT grid), got " + std::to_string(n));
  p.n = static_cast<int>(n);
  p.length_m = grid.number("length_m", 1e-6, kBig);
  const long long m = grid.integer("margin", 0, 16384);
  if (2 * m >= n) grid.fail("margin", "margin too large for n = " + std::to_string(n) + ": 2 * margin must be < n");
  p.margin = static_cast<int>(m);
  p.absorber = grid.boolean("cutoff", true) ? Absorber::paper_quadratic : Absorber::off;
  // 0 (default): paper 004's cutoff once per step; tau > 0: one paper cutoff per tau seconds
  p.cutoff_time_s = grid.number("cutoff_time_s", 0.0, 0.0, 1e6);
  // K: the spatial round trip every K steps; 0 (default) = auto_round_trip_every (cutoff.hpp),
  // resolved in parse_huygens_scene once dt and the water are known
  p.round_trip_every = static_cast<int>(grid.integer("round_trip_every", 0, 0, 64));
  if (p.absorber == Absorber::paper_quadratic && m < 1) grid.fail("margin", "the cutoff needs margin >= 1");
}

// Smallest non-zero gravity, surface tension and depth: below them the dispersion relation is
// degenerate in float arithmetic (docs/robustness.md).
constexpr double kMinGravity = 1e-3, kMinTension = 1e-6, kMinDepth = 1e-6;

// A value that is 0 or in [lo, hi], with both alternatives named in the error.
double zero_or_at_least(const JsonIn& j, const char* key, double def, double lo, double hi) {
  const double v = j.number(key, def, 0.0, hi);
  if (v != 0.0 && v < lo) j.fail(key, fmt("must be 0 or in [%g, %g], got %g", lo, hi, v));
  return v;
}

// water (all optional): depth_m null or absent = deep water
void parse_water(const JsonIn& root, Water& w) {
  const auto water = root.optional_object("water");
  if (!water) return;
  water->reject_renamed(
      {{"gravity", "gravity_mps2"}, {"surface_tension", "surface_tension_npm"}, {"density", "density_kgpm3"}});
  water->allow_only({"gravity_mps2", "surface_tension_npm", "density_kgpm3", "depth_m"});
  w.gravity_mps2 = zero_or_at_least(*water, "gravity_mps2", 9.81, kMinGravity, 1e3);
  w.surface_tension_npm = zero_or_at_least(*water, "surface_tension_npm", 0.072, kMinTension, 10.0);
  w.density_kgpm3 = water->number("density_kgpm3", 1000.0, 1e-3, 1e5);
  if (auto d = water->optional_number("depth_m", 0.0, kBig)) {
    if (*d < kMinDepth) water->fail("depth_m", "depth must be >= 1e-6 m (null for deep water)");
    w.depth_m = *d;
  }
  if (w.gravity_mps2 == 0 && w.surface_tension_npm == 0)
    water->fail("gravity_mps2", "gravity and surface tension are both 0: no waves");
}

// The slowest wave of the grid (k1 = 2 pi / L) must move: with c = omega(k1) / k1 below 1e-6 m/s
// the dispersion is degenerate (k / omega overflows a float in the Stokes and source tables).
void check_dispersion(const JsonIn& root, const HuygensParams& p) {
  const double k1 = 2.0 * std::numbers::pi / p.length_m, c = omega(p.water, k1) / k1;
  if (!(c >= 1e-6) || !std::isfinite(c))
    root.fail("water", fmt("the longest wave of the grid (%g m) moves at %g m/s, below 1e-6 m/s: raise gravity_mps2, "
                           "surface_tension_npm or depth_m",
                           p.length_m, c));
}

// time: dt_s > 0 (any value is stable), display_per_step
void parse_time(const JsonIn& root, HuygensScene& out) {
  const JsonIn time = root.object("time");
  time.reject_renamed({{"dt", "dt_s"}});
  time.allow_only({"dt_s", "display_per_step"});
  out.params.dt_s = time.number("dt_s", 0.0, 1e3);
  if (out.params.dt_s <= 0) time.fail("dt_s", "dt_s must be > 0");
  out.display_per_step = static_cast<int>(time.integer("display_per_step", 1, 1, 1000));
}

GaussianSource parse_gaussian(const JsonIn& e, double len) {
  e.allow_only({"type", "x_m", "y_m", "sigma_m", "amplitude_m"});
  GaussianSource g;
  g.x_m = e.number("x_m", 0.0, len);
  g.y_m = e.number("y_m", 0.0, len);
  g.sigma_m = e.number("sigma_m", 0.0, len);
  if (g.sigma_m <= 0) e.fail("sigma_m", "sigma must be > 0");
  g.amplitude_m = e.number("amplitude_m", -kBig, kBig);
  return g;
}

PlaneWaveSource parse_plane_wave(const JsonIn& e, double len, int n) {
  e.allow_only({"type", "wavelength_m", "amplitude_m", "direction_deg"});
  PlaneWaveSource w;
  w.wavelength_m = e.number("wavelength_m", 0.0, kBig);
  if (w.wavelength_m < 2.0 * len / n)
    e.fail("wavelength_m", "wavelength below two grid cells (" + std::to_string(2.0 * len / n) + " m)");
  w.amplitude_m = e.number("amplitude_m", -kBig, kBig);
  w.direction_deg = e.number("direction_deg", 0.0, -360.0, 360.0);
  return w;
}

// initial: gaussian elevations at rest and progressive plane waves
void parse_initial(const JsonIn& root, HuygensScene& out) {
  for (const JsonIn& e : root.array("initial")) {
    const std::string type = e.string("type", "", {"gaussian", "plane_wave"});
    if (type.empty()) e.fail("type", "missing required string (\"gaussian\" or \"plane_wave\")");
    if (type == "gaussian")
      out.initial_gaussians.push_back(parse_gaussian(e, out.params.length_m));
    else
      out.initial_plane_waves.push_back(parse_plane_wave(e, out.params.length_m, out.params.n));
  }
}

// drops: {t_s, x_m, y_m, radius_m, depth_m}, sorted by time
void parse_drops(const JsonIn& root, HuygensScene& out) {
  const double len = out.params.length_m;
  for (const JsonIn& e : root.array("drops")) {
    e.reject_renamed({{"t", "t_s"}});
    e.allow_only({"t_s", "x_m", "y_m", "radius_m", "depth_m"});
    GaussianSource g;
    g.t_s = e.number("t_s", 0.0, 1e9);
    g.x_m = e.number("x_m", 0.0, len);
    g.y_m = e.number("y_m", 0.0, len);
    g.sigma_m = e.number("radius_m", 0.0, len);
    if (g.sigma_m <= 0) e.fail("radius_m", "radius must be > 0");
    g.amplitude_m = -e.number("depth_m", -kBig, kBig);
    out.drops.push_back(g);
  }
  std::stable_sort(out.drops.begin(), out.drops.end(),
                   [](const GaussianSource& a, const GaussianSource& b) { return a.t_s < b.t_s; });
}

// True when the hull (with 3 blur radii) fits a quarter of a patch of `patch` cells of dx.
bool hull_fits(const HullParams& h, int patch, double dx) {
  return 0.25 * patch * dx >= 0.5 * std::max(h.length_m, h.beam_m) + 3.0 * h.blur();
}

// The ship patch: 2M, enlarged until every hull fits a quarter of it; a ship moving more than
// a quarter of its patch per step is refused
void size_ship_patch(const JsonIn& root, HuygensScene& out) {
  const HuygensParams& p = out.params;
  const double dx = p.length_m / p.n;
  int patch = std::max(2, 2 * p.margin);
  for (const Ship& sh : out.ships)
    while (patch < p.n && !hull_fits(sh.hull, patch, dx)) patch += 2;
  out.ship_patch = std::min(patch, p.n);
  for (std::size_t i = 0; i < out.ships.size(); ++i)
    if (!hull_fits(out.ships[i].hull, out.ship_patch, dx))
      root.fail("ships", "ship " + std::to_string(i) + ": the hull (with its blur) does not fit a quarter of the grid");
  // each ship costs a P x P transform and its kernels every step (ship_waves.hpp): their work is
  // bounded by kShipWork grid transforms, ships P^2 <= kShipWork N^2
  constexpr std::uint64_t kShipWork = 16;
  const std::uint64_t p2 = static_cast<std::uint64_t>(out.ship_patch) * out.ship_patch;
  const std::uint64_t most = kShipWork * static_cast<std::uint64_t>(p.n) * p.n / p2;
  if (out.ships.size() > most)
    root.fail("ships", std::to_string(out.ships.size()) + " ships of a " + std::to_string(out.ship_patch) +
                           "^2 patch: " + "their waves would cost more than " + std::to_string(kShipWork) +
                           " grid transforms per step (ships x patch^2 <= " + std::to_string(kShipWork) +
                           " n^2); this grid takes at most " + std::to_string(most) + " ships");
}

void check_ship_steps(const JsonIn& root, const HuygensScene& out) {
  const HuygensParams& p = out.params;
  try {
    ShipWaves probe(p.water, p.n, p.length_m, out.ship_patch, out.ships, PlanEffort::estimate);
    probe.check_step(p.dt_s);
  } catch (const std::invalid_argument& e) {
    root.fail("ships", e.what());
  }
}

// the features each cost nothing when the scene does not name them: stokes, ships, wind
void parse_features(const JsonIn& root, HuygensScene& out) {
  out.stokes = root.boolean("stokes", false);
  if (root.has("ships") && !root.raw()["ships"].is_null() && !root.raw()["ships"].is_array())
    root.fail("ships", "expected an array of ships");
  out.ships = parse_ships(root);
  if (auto w = root.optional_object("wind")) {
    out.wind = parse_wind(*w);
    out.has_wind = true;
  }
  // what the viewer is asked for (caustics, blur), handed on as RenderInfo::request
  out.render = parse_render_request(root);
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
  parse_grid(root, p);
  parse_water(root, p.water);
  check_dispersion(root, p);
  parse_time(root, out);
  parse_features(root, out);
  parse_initial(root, out);
  parse_drops(root, out);
  // source tables (2 N^2 floats) at construction for timed drops, which enter inside a step;
  // a scene without them makes the tables on the first UI drop (between steps, see apply())
  p.runtime_sources = !out.drops.empty();
  // Stokes or wind: the StokesHeight stage makes the height; the propagator makes none
  p.external_height = out.stokes || out.has_wind;
  // ships add to the spatial field: force the FFT round trip even without the cutoff
  p.spatial = !out.ships.empty();
  if (!out.ships.empty()) size_ship_patch(root, out);
  if (p.round_trip_every == 0) p.round_trip_every = auto_round_trip_every(p);
  if (auto e = huygens_params_error(p); !e.empty()) root.fail_here(e);
    // before the ship probe, the first allocation; on ranks, what one rank allocates
#ifdef HUYGENS_HAVE_MPI
  require_memory(comm::size() > 1 ? huygens_slab_memory(out, comm::size()) : huygens_memory(out));
#else
  require_memory(huygens_memory(out));
#endif
  if (!out.ships.empty()) check_ship_steps(root, out);
  return out;
}

MemoryEstimate huygens_memory(const HuygensScene& s) {
  const HuygensParams& p = s.params;
  const std::uint64_t n2 = static_cast<std::uint64_t>(p.n) * p.n, q2 = (p.n / 2 + 1) * std::uint64_t(p.n / 2 + 1);
  const std::uint64_t v2 = static_cast<std::uint64_t>(p.n - 2 * p.margin) * (p.n - 2 * p.margin);
  const std::uint64_t c = sizeof(cfloat), f = sizeof(float);
  MemoryEstimate m;
  m.size_key = "$.grid.n";
  // Z^, S and (without Stokes or wind) the packed height H; the quadrant rotation tables
  std::uint64_t prop = 2 * c * n2 + (p.rotation == Rotation::lifting ? 3 : 2) * f * q2;
  if (!p.external_height) prop += c * n2 + 2 * f * q2 + 2 * f * v2;  // H, alpha, beta, eta, etadot
  m.add("propagator", prop);
  if (p.runtime_sources) m.add("drop tables", 2 * f * n2);
  if (s.stokes || s.has_wind)  // StokesHeight (stokes.hpp) and the solver's eta, etadot
    m.add("stokes height", (s.stokes ? 3 : 2) * f * q2 + (s.stokes ? 3 : 1) * c * n2 + 2 * f * v2);
  if (s.has_wind) m.add("wind sea", sizeof(double) * n2 + 2 * c * n2 + 2 * c * q2);  // omega, W^(0), W^(t), P
  if (s.display_per_step > 1) m.add("interpolation", 3 * f * v2);
  if (!s.ships.empty()) {  // the patch buffer, omega, and two cached kernels per ship (ship_waves.hpp)
    const std::uint64_t p2 = static_cast<std::uint64_t>(s.ship_patch) * s.ship_patch;
    // with the round trip every K steps: K patches per ship kept, K - 1 delay tables
    const std::uint64_t k = static_cast<std::uint64_t>(std::max(1, p.round_trip_every));
    m.add("ship patches", c * p2 * (1 + (2 + k) * s.ships.size() + (k - 1)) + sizeof(double) * p2, "$.ships");
  }
  return m;
}

HuygensSolver::HuygensSolver(const HuygensScene& scene)
    : HuygensSolver(scene, whole_grid_layout(scene.params.n, scene.params.effort)) {}

HuygensSolver::HuygensSolver(const HuygensScene& scene, GridLayout layout)
    : scene_(scene), prop_(scene_.params, std::move(layout)) {
  const auto& p = scene_.params;
  const GridLayout& g = prop_.layout();
  vis_ = g.visible(p.margin);
  const std::size_t vv = static_cast<std::size_t>(vis_.count) * prop_.visible_size();
  if (!scene_.ships.empty()) {
    ships_ = std::make_unique<ShipWaves>(p.water, p.n, p.length_m, scene_.ship_patch, scene_.ships, p.effort);
    ships_->check_step(p.dt_s);
    if (prop_.round_trip_every() > 1) ships_->reserve_gather(prop_.round_trip_every());
  }
  if (scene_.has_wind)
    wind_ = g.whole ? std::make_unique<WindSea>(scene_.wind, p.water, p.n, p.length_m, p.dt_s)
                    : std::make_unique<WindSea>(scene_.wind, p.water, p.n, p.length_m, p.dt_s,
                                                WindRows{g.spectrum_row(0), static_cast<int>(g.krows), g.transposed});
  // a slab makes every height in this stage (the packed height reads Z^(-k), on another rank)
  if (scene_.stokes || wind_ || !g.whole) {
    stokes_ = std::make_unique<StokesHeight>(p.water, p.length_m, scene_.stokes, g, p.margin);
    eta_ = AlignedBuffer<float>(vv);
    etadot_ = AlignedBuffer<float>(vv);
  }
  height_standin_ = !g.whole && !scene_.stokes && !wind_;
  if (scene_.display_per_step > 1) {
    eta0_ = AlignedBuffer<float>(vv);
    etadot0_ = AlignedBuffer<float>(vv);
    frame_ = AlignedBuffer<float>(vv);
  }
  initial_state();
}

void HuygensSolver::initial_state() {
  const auto& p = scene_.params;
  for (const auto& w : scene_.initial_plane_waves) prop_.add_plane_wave(w.wavelength_m, w.amplitude_m, w.direction_deg);
  for (const auto& g : scene_.initial_gaussians) prop_.add_gaussian(g.x_m, g.y_m, g.sigma_m, g.amplitude_m);
  // drops at t <= 0 are part of the initial state
  while (next_drop_ < scene_.drops.size() && scene_.drops[next_drop_].t_s <= 0.0) {
    const auto& d = scene_.drops[next_drop_++];
    prop_.add_gaussian(d.x_m, d.y_m, d.sigma_m, d.amplitude_m, -d.t_s);
  }
  // the drops stage exists for the scene's drops and for the UI's (registered here; it owns
  // the source tables once they exist)
  st_drops_ = prop_.stats().add("drops", prop_.source_bytes());
  if (ships_) st_ships_ = prop_.stats().add("ships", ships_->bytes());
  if (wind_) st_wind_ = prop_.stats().add("wind", wind_->bytes());
  if (stokes_)
    st_stokes_ = prop_.stats().add(scene_.stokes ? "height_stokes"
                                   : wind_       ? "height_wind"
                                                 : "height",
                                   stokes_->bytes());
  if (scene_.still_skip && !ships_ && !wind_ && scene_.still_check_every > 0) {
    // ships and wind keep the sea alive: no still state with them
    const double k1 = 2.0 * std::numbers::pi / p.length_m, a = scene_.still_amplitude_m;
    still_energy_ = 0.5 * (p.water.density_kgpm3 * p.water.gravity_mps2 + p.water.surface_tension_npm * k1 * k1) * a *
                    a * p.length_m * p.length_m;
    st_still_ = prop_.stats().add("still", 0);
  }
  // the stages in step order: the first that failed is named
  const StageStats& st = prop_.stats();
  step_order_ = {st.find("propagate"), st.find("cutoff"), st_ships_, st.find("spectrum"), st_drops_, st_wind_,
                 st.find("height"),    st_stokes_};
  prop_.checks().clear();
  make_height(0);
  // every rank agrees (a slab's height failure is recorded, not thrown, and shows here)
  double bad = all_finite(eta_view()) ? 0.0 : 1.0;
  prop_.layout().sum_over_ranks({&bad, 1});
  if (bad > 0) throw NonFiniteError("initial", 0);
  prop_.stats().reset_counts();
}

void HuygensSolver::make_height(std::int64_t step) {
  if (!stokes_) {
    prop_.height();
    return;
  }
  const int n = prop_.n();
  bool ok = true;
  {
    StageTimer timer(prop_.stats()[st_stokes_]);
    const float scale = 1.0f / (static_cast<float>(n) * static_cast<float>(n));
    // with wind: the sea W^(0) P is formed inside the height pass (read once, never written)
    ok = wind_ && wind_on_
             ? stokes_->compute(prop_.spectrum_view().data(), scale, *wind_, eta_.data(), etadot_.data())
             : stokes_->compute(prop_.spectrum_view().data(), scale, nullptr, eta_.data(), etadot_.data());
    prop_.stats()[st_stokes_].transforms += static_cast<std::uint64_t>(stokes_->transforms_per_call());
    prop_.stats()[st_stokes_].sent += stokes_->sent_bytes_per_call();
  }
  if (ok) return;
  // a slab's first-order height is named as HuygensPropagator::height names its own
  const int blame = height_standin_ ? prop_.height_blame() : -1;
  prop_.checks().fail(prop_.stats(), blame < 0 ? st_stokes_ : blame, step);
}

double HuygensSolver::transforms_per_step() const {
  return prop_.transforms_per_step() + (stokes_ ? stokes_->transforms_per_call() : 0);
}

bool HuygensSolver::drop_due() const {
  if (next_drop_ >= scene_.drops.size()) return false;
  const double t1 = static_cast<double>(prop_.steps() + 1) * scene_.params.dt_s;
  return scene_.drops[next_drop_].t_s <= t1 + 1e-9 * scene_.params.dt_s;
}

void HuygensSolver::settle_step(bool energy_due) {
  StageChecks& checks = prop_.checks();
  checks.energy() = energy_due ? prop_.spectrum_norm2() : 0.0;
  checks.settle(prop_.layout().sum_over_ranks, prop_.stats(), step_order_, prop_.steps() + 1);
  if (!energy_due || !(prop_.energy_bound_of(checks.energy()) < still_energy_)) return;
  // below the threshold: a flat sea at rest (the residual is dropped, so that waking up later
  // starts from exactly zero instead of a frozen, unrotated residual)
  prop_.clear();
  for (auto* b : {&eta_, &etadot_, &eta0_, &etadot0_}) std::fill(b->data(), b->data() + b->size(), 0.0f);
  still_ = true;
}

void HuygensSolver::keep_previous_step() {
  // after a cmd::Drop: eta0_ needs the current height; otherwise the step makes it
  if (height_dirty_ && scene_.display_per_step > 1) refresh_height();
  height_dirty_ = false;
  if (scene_.display_per_step <= 1) return;
  // keep the previous full step for the displayed frames in between: with the height stage
  // the solver owns eta_, so the buffers trade places (make_height rewrites all of eta_);
  // otherwise the propagator owns the height and it is copied
  if (stokes_) {
    std::swap(eta0_, eta_);
    std::swap(etadot0_, etadot_);
  } else {
    const auto e = eta_view(), d = etadot_view();
    std::memcpy(eta0_.data(), e.data(), e.size() * sizeof(float));
    std::memcpy(etadot0_.data(), d.data(), d.size() * sizeof(float));
  }
}

void HuygensSolver::add_ships(double t0) {
  // the ships write into the same buffer as propagate and cutoff: each patch is checked
  // before it is added (every step; P^2 per ship), so a non-finite value from the kernels
  // is named "ships" and never blamed on propagate
  if (prop_.inject_due_for_test(st_ships_)) ships_->poison_next_add_for_test();
  bool ok = false;
  {
    StageTimer timer(prop_.stats()[st_ships_]);
    // every process makes every patch (P x P, small) and adds the rows it holds
    const GridLayout& g = prop_.layout();
    const int r0 = static_cast<int>(g.row0), rows = static_cast<int>(g.rows);
    if (prop_.round_trip_every() == 1) {
      ok = ships_->add_rows(prop_.field().data(), r0, rows, t0, scene_.params.dt_s);
    } else {
      // the round trip every K steps: each step's patch enters at the next round trip, turned
      // by the steps still ahead (ShipWaves::gather)
      ok = ships_->gather(t0, scene_.params.dt_s, prop_.steps_to_round_trip());
      if (ok && prop_.round_trip_now()) ships_->scatter_rows(prop_.field().data(), r0, rows);
    }
  }
  if (!ok) prop_.checks().fail(prop_.stats(), st_ships_, prop_.steps() + 1);
}

void HuygensSolver::release_drops() {
  // drops released in (t, t + dt] enter with the phase they have gained by t + dt
  const double t1 = static_cast<double>(prop_.steps() + 1) * scene_.params.dt_s;
  const double eps = 1e-9 * scene_.params.dt_s;
  StageTimer timer(prop_.stats()[st_drops_]);
  while (next_drop_ < scene_.drops.size() && scene_.drops[next_drop_].t_s <= t1 + eps) {
    const auto& d = scene_.drops[next_drop_++];
    prop_.add_gaussian(d.x_m, d.y_m, d.sigma_m, d.amplitude_m, std::max(0.0, t1 - d.t_s));
  }
  if (prop_.inject_due_for_test(st_drops_)) prop_.spectrum_data()[1] = NAN;
  // drops are rare: check their output in full
  if (!all_finite(prop_.spectrum_view())) prop_.checks().fail(prop_.stats(), st_drops_, prop_.steps() + 1);
}

void HuygensSolver::step() {
  if (still_) {
    if (!drop_due()) {
      // still sea: no transform, no pass over the field; time advances
      StageTimer timer(prop_.stats()[st_still_]);
      prop_.end_step();
      return;
    }
    still_ = false;  // a timed drop wakes it: the normal step below releases it
  }
  keep_previous_step();
  prop_.checks().clear();
  const double t0 = prop_.time();
  prop_.propagate();
  prop_.cutoff();
  if (ships_) add_ships(t0);
  prop_.spectrum();
  if (drop_due()) release_drops();
  if (wind_) {
    StageTimer timer(prop_.stats()[st_wind_]);
    wind_->advance();
  }
  make_height(prop_.steps() + 1);
  // the still check every still_check_every steps: one pass over Z^, summed with the records
  const bool energy_due = st_still_ >= 0 && (prop_.steps() + 1) % scene_.still_check_every == 0;
  settle_step(energy_due);
  prop_.end_step();
}

std::vector<OutputField> HuygensSolver::display_outputs(int j) {
  const int d = scene_.display_per_step;
  if (j == 0 || d <= 1) return outputs();
  refresh_height();
  if (j < 0 || j >= d || prop_.steps() < 1) return {};
  const auto e1 = eta_view(), d1 = etadot_view();
  hermite_interpolate(eta0_.data(), etadot0_.data(), e1.data(), d1.data(), e1.size(), hermite_weights(j, d),
                      scene_.params.dt_s, frame_.data());
  auto out = outputs();
  out[0].data = frame_.span();
  return out;
}

std::size_t HuygensSolver::ship_poses(std::span<ShipState> out) const {
  if (!ships_) return 0;
  const std::size_t k = std::min(out.size(), static_cast<std::size_t>(ships_->ships()));
  for (std::size_t i = 0; i < k; ++i) {
    const ShipPoseNow p = ships_->pose(static_cast<int>(i), prop_.time());
    out[i] = ShipState{p.x_m, p.y_m, p.heading_rad, p.speed_mps};
  }
  return k;
}

bool HuygensSolver::apply(const Command& c) {
  if (!prop_.layout().whole) return false;  // commands reach one process only (docs/scale.md)
  if (const auto* t = std::get_if<cmd::Toggle>(&c)) return toggle(*t);
  if (const auto* s = std::get_if<cmd::ShipTarget>(&c)) {
    // between steps: the ship leaves its path now (no transform, no allocation)
    if (!ships_) return false;
    return ships_->steer(s->ship, prop_.time(), s->x_m, s->y_m, s->vx_mps, s->vy_mps);
  }
  const auto* d = std::get_if<cmd::Drop>(&c);
  if (!d) return false;
  const double len = scene_.params.length_m;
  if (!(d->x_m >= 0 && d->x_m <= len && d->y_m >= 0 && d->y_m <= len && d->radius_m > 0 && std::isfinite(d->depth_m)))
    return false;
  // the first UI drop of a scene without timed drops makes the source tables (2 N^2 floats,
  // one pass of the dispersion): here, between steps, on the simulation thread
  prop_.stats()[st_drops_].bytes = prop_.reserve_sources();
  StageTimer timer(prop_.stats()[st_drops_]);
  prop_.add_gaussian(d->x_m, d->y_m, d->radius_m, -static_cast<double>(d->depth_m));
  if (!all_finite(prop_.spectrum_view())) throw NonFiniteError("drops", prop_.steps());
  // the height follows lazily (the next step makes it anyway; see refresh_height)
  height_dirty_ = true;
  still_ = false;
  return true;
}

std::vector<OutputField> HuygensSolver::outputs() {
  refresh_height();
  const std::size_t v = static_cast<std::size_t>(prop_.visible_size());
  OutputField f{"eta", {static_cast<std::size_t>(vis_.count), v}, eta_view()};
  if (!prop_.layout().whole) {  // a slab: its rows of the global visible region
    f.global_shape = {v, v};
    f.row0 = static_cast<std::size_t>(vis_.row0);
  }
  return {f};
}

nlohmann::json HuygensSolver::meta() const { return huygens_meta(scene_, transforms_per_step(), still_energy_); }

nlohmann::json huygens_meta(const HuygensScene& scene, double transforms_per_step, double still_energy_j) {
  const auto& p = scene.params;
  const int m = p.margin, n = p.n;
  const double dx = p.length_m / n;
  return nlohmann::json{
      {"solver", "huygens"},
      {"n", n},
      {"length_m", p.length_m},
      {"dx", dx},
      {"dt", p.dt_s},
      {"margin", m},
      {"display_per_step", scene.display_per_step},
      {"cutoff", p.absorber == Absorber::paper_quadratic},
      {"cutoff_time_s", p.cutoff_time_s},
      {"round_trip_every", p.round_trip_every},
      {"rotation", p.rotation == Rotation::lifting ? "lifting" : "complex"},
      {"grid", {{"n", n}, {"length_m", p.length_m}, {"margin", m}, {"dx", dx}}},
      {"water",
       {{"gravity_mps2", p.water.gravity_mps2},
        {"surface_tension_npm", p.water.surface_tension_npm},
        {"density_kgpm3", p.water.density_kgpm3},
        {"depth_m", p.water.deep() ? nlohmann::json(nullptr) : nlohmann::json(p.water.depth_m)}}},
      {"visible",
       {{"rows", {m, n - m}},
        {"cols", {m, n - m}},
        {"shape", {n - 2 * m, n - 2 * m}},
        {"origin_m", {m * dx, m * dx}},
        {"note",
         "index ranges are half-open [start, end) into the full N x N grid; origin_m is (x, y) of cell (0, 0)"}}},
      {"fields",
       {{"eta", scene.stokes ? "elevation to second order (paper 004 eq. 3: Re IFFT[i k/omega Z^] + Re chi^2) (m), "
                               "rows = y, cols = x"
                             : "first-order elevation Re IFFT[i k/omega Z^] (m), rows = y, cols = x"}}},
      {"stokes", scene.stokes},
      {"ships", static_cast<int>(scene.ships.size())},
      {"ship_patch", scene.ships.empty() ? 0 : scene.ship_patch},
      {"wind", scene.has_wind ? nlohmann::json{{"speed_mps", scene.wind.speed_mps},
                                               {"direction_deg", scene.wind.direction_deg},
                                               {"seed", scene.wind.seed},
                                               {"fetch_m", scene.wind.fetch_m},
                                               {"gamma", scene.wind.gamma},
                                               {"spectrum", "JONSWAP"}}
                              : nlohmann::json(nullptr)},
      {"transforms_per_step", transforms_per_step},
      {"still_energy_j", still_energy_j},
      {"transforms_per_displayed_frame", transforms_per_step / static_cast<double>(scene.display_per_step)},
  };
}

bool HuygensSolver::toggle(const cmd::Toggle& t) {
  if (!prop_.layout().whole) return false;
  if (t.feature == "wind") {
    if (!wind_) return false;  // no sea in the scene: nothing is allocated to switch on
    wind_on_ = t.on;
    height_dirty_ = true;
    return true;
  }
  if (!(t.feature == "stokes")) return false;
  if (t.on == (stokes_ && stokes_->second_order())) return true;
  const HuygensParams& p = scene_.params;
  if (!t.on && !p.external_height) {
    stokes_spare_ = std::move(stokes_);  // back to the propagator's own packed height
  } else {
    // between steps (allocation and planning allowed): the other order, made once and kept
    if (!stokes_spare_ || stokes_spare_->second_order() != t.on)
      stokes_spare_ = std::make_unique<StokesHeight>(p.water, p.n, p.length_m, t.on, p.effort, p.margin);
    std::swap(stokes_, stokes_spare_);
    if (eta_.size() == 0) {  // a scene without a height stage: its buffers and stage now
      const std::size_t vv = static_cast<std::size_t>(prop_.visible_size()) * prop_.visible_size();
      eta_ = AlignedBuffer<float>(vv);
      etadot_ = AlignedBuffer<float>(vv);
    }
    if (st_stokes_ < 0) st_stokes_ = prop_.stats().add("height_stokes", 0);
  }
  if (st_stokes_ >= 0)
    prop_.stats()[st_stokes_].bytes = (stokes_ ? stokes_->bytes() : 0) + (stokes_spare_ ? stokes_spare_->bytes() : 0);
  height_dirty_ = true;  // the next step or read makes the height the new way
  return true;
}

RenderInfo HuygensSolver::render_info() {
  const HuygensParams& p = scene_.params;
  const double dx = p.length_m / p.n;
  RenderInfo r;
  r.grid = RenderGrid{height_rows(), height_cols(), dx, p.margin * dx, p.margin * dx};
  if (!p.water.deep()) r.depth_m = p.water.depth_m;
  for (const Ship& s : scene_.ships) r.hulls.push_back(RenderHull{s.hull.length_m, s.hull.beam_m, s.hull.draft_m});
  r.dt_s = p.dt_s;
  r.display_per_step = scene_.display_per_step;
  r.frame_dt_s = p.dt_s / scene_.display_per_step;
  r.toggles.push_back(RenderToggle{"stokes", "Stokes (2nd order)", stokes_ && stokes_->second_order()});
  if (wind_) r.toggles.push_back(RenderToggle{"wind", "wind", wind_on_});
  // the sea beyond, at most 1024^2 modes: the same sea's longest waves (modes are keyed by their
  // signed indices), a 1024^2 transform per frame and 40 MB at most beside the solver's memory
  if (wind_)
    r.ambient_sea = RenderAmbientSea{
        std::make_shared<AmbientSeaSlopes>(scene_.wind, p.water, std::min(p.n, kMaxAmbientModes), p.length_m),
        scene_.wind.speed_mps};
  r.request = scene_.render;
  r.default_look = wind_ ? LookRequest::ocean : LookRequest::pool;  // open sea with wind, else a pool
  return r;
}

std::unique_ptr<Solver> make_huygens_solver(const Scene& scene, const RunOptions& options) {
#ifdef HUYGENS_HAVE_MPI
  // under mpirun with more than one rank: the slab solver (one process: this solver, unchanged)
  // (HUYGENS_SLAB_SOLVER=1 with MPI started, e.g. HUYGENS_MPI_INIT=1, runs the slab solver on one rank: the reference
  // of the CLI's rank-count tests, tests/mpi/near_dumps.cmake)
  const char* force = std::getenv("HUYGENS_SLAB_SOLVER");
  if (comm::size() > 1 || (force && std::string(force) == "1" && comm::active()))
    return std::make_unique<HuygensSlabSolver>(parse_huygens_scene(scene, options), comm::world());
#endif
  return std::make_unique<HuygensSolver>(parse_huygens_scene(scene, options));
}

namespace {

// The estimate of the largest of `ranks`: the slab solver's own (what a run under mpirun checks)
// when MPI is built, else each part scaled to ceil(N / P) rows.
MemoryEstimate huygens_rank_memory(const HuygensScene& s, int ranks) {
  const MemoryEstimate whole = huygens_memory(s);
#ifdef HUYGENS_HAVE_MPI
  if (ranks > 1) return huygens_slab_memory(s, ranks);
#endif
  const std::uint64_t n = static_cast<std::uint64_t>(s.params.n);
  const std::uint64_t rows = (n + static_cast<std::uint64_t>(ranks) - 1) / static_cast<std::uint64_t>(ranks);
  MemoryEstimate m;
  m.size_key = whole.size_key;
  for (const MemoryEstimate::Part& part : whole.parts)
    m.add(part.name, part.name == "ship patches" ? part.bytes : (part.bytes * rows + n - 1) / n, part.key);
  return m;
}

SceneSizing huygens_sizing(const Scene& scene) {
  const long long n = scene.root().object("grid").integer("n", 16, 1 << 20);
  return SceneSizing{"huygens", std::to_string(n) + " x " + std::to_string(n), static_cast<int>(n), true};
}

}  // namespace

SolverEntry huygens_solver_entry() {
  SolverEntry e;
  e.name = "huygens";
  e.summary = "FFT Huygens propagation with Kelvin ships, wind and second-order Stokes (paper 000)";
  e.make = [](const Scene& s, const RunOptions& o) { return make_huygens_solver(s, o); };
  e.sizing = huygens_sizing;
  e.rank_memory = [](const Scene& scene) -> std::function<MemoryEstimate(int)> {
    const MemoryCheckOff sizing_only;  // parsed to be sized, not run
    auto hs = std::make_shared<const HuygensScene>(parse_huygens_scene(scene));
    return [hs](int p) { return huygens_rank_memory(*hs, p); };
  };
  e.bench_scene = std::string(shipped_scene_text("default.json"));
  e.bench_steps = 200;
  return e;
}

}  // namespace huygens
