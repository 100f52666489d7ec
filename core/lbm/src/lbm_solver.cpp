// "solver": "lbm" scenes: the "lbm" block parsed block by block (grid, water, bed, initial state,
// obstacles, boundaries, time step) into LbmScene, and LbmShallow behind the Solver interface.
// The keys and their defaults are in docs/lbm.md.
#include "huygens/lbm/lbm_solver.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>

#include "huygens/common/comm.hpp"
#include "huygens/common/npy.hpp"
#include "huygens/common/npy_read.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/lbm/shallow.hpp"
#include "huygens/lbm/stoker.hpp"
#include "huygens/pipeline/render_request.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/pipeline/solver_entry.hpp"

namespace huygens {

namespace {

using nlohmann::json;

// A velocity or acceleration [x, y] in [lo, hi]; absent or null = zero.
std::array<double, 2> vec2_or_zero(const JsonIn& o, const char* key, double lo, double hi) {
  if (!o.has(key) || o.is_null(key)) return {0.0, 0.0};
  return o.vec<2>(key, lo, hi);
}

class LbmSolver final : public Solver {
 public:
  LbmSolver(const LbmParams& p, const LbmFields& f, LbmDecomposition d) : sim_(p, f, d), ranks_(d.ranks) {
    const std::size_t n = sim_.slab().rows * static_cast<std::size_t>(p.cols);  // this rank's rows
    h_.resize(n);
    eta_.resize(n);
    u_.resize(2 * n);
    bed_.resize(n);
    sim_.bed(bed_);
  }
  MemoryEstimate memory() const override { return lbm_memory(sim_.params(), ranks_, sim_.has_mass_carry()); }

  void step() override { sim_.step(); }
  double time() const override { return sim_.time_s(); }
  std::int64_t steps() const override { return sim_.steps(); }
  /// (steps() + k) dt, as LbmShallow::time_s computes the time (exact).
  double time_bound(int k) const override { return static_cast<double>(sim_.steps() + k) * sim_.params().dt_s; }
  std::vector<OutputField> outputs() override {
    refresh();
    velocity();
    const std::size_t r = height_rows(), c = height_cols();
    if (ranks_ == 1) return {{"h", {r, c}, h_}, {"u", {r, c, 2}, u_}, {"eta", {r, c}, eta_}};
    const std::size_t rg = static_cast<std::size_t>(sim_.params().rows), r0 = sim_.slab().row0;
    return {{"h", {r, c}, h_, {rg, c}, r0}, {"u", {r, c, 2}, u_, {rg, c, 2}, r0}, {"eta", {r, c}, eta_, {rg, c}, r0}};
  }
  json meta() const override {
    const auto& p = sim_.params();
    const auto& l = sim_.lattice();
    return {{"solver", "lbm"},
            {"grid", {{"rows", p.rows}, {"cols", p.cols}, {"cell_m", p.cell_m}}},
            {"dx", p.cell_m},
            {"dt", p.dt_s},
            {"tau", l.tau},
            {"lattice_speed_mps", l.speed_mps},
            {"signal_ratio", l.signal_ratio},
            {"visible",
             {{"row0", 0},
              {"row1", p.rows},
              {"col0", 0},
              {"col1", p.cols},
              {"origin_m", {0.5 * p.cell_m, 0.5 * p.cell_m}},
              {"note", "origin_m is (x, y) of point (0, 0), the centre of cell (0, 0)"}}},
            {"fields",
             {{"h", "depth (m), 0 in obstacles"},
              {"u", "velocity (m/s), (rows, cols, 2)"},
              {"eta", "surface elevation h + z_b (m)"}}},
            {"dry_cells", "wetting and drying: h < min_depth_m is dry and passes no water on"}};
  }
  const StageStats& stats() const override { return sim_.stats(); }
  std::span<const float> velocity() override {
    sim_.velocity(u_);
    return u_;
  }
  std::span<const float> height() override {
    refresh();
    return eta_;
  }
  /// This rank's rows (all rows in one process).
  std::size_t height_rows() const override { return sim_.slab().rows; }
  std::size_t height_cols() const override { return static_cast<std::size_t>(sim_.params().cols); }
  /// Cell centres ((c + 1/2) dx, (r + 1/2) dx), the rest level (mean initial eta, the flat
  /// ground that far down), the bed, the obstacles, the fixed step; no toggles.
  RenderInfo render_info() override {
    const LbmParams& p = sim_.params();
    RenderInfo r = from_scene;
    r.grid = RenderGrid{height_rows(), height_cols(), p.cell_m, 0.5 * p.cell_m, 0.5 * p.cell_m};
    r.rest_level_m = mean_level(height());
    if (r.rest_level_m > 0.0) r.depth_m = r.rest_level_m;
    r.bed_m = bed_;
    r.dt_s = r.frame_dt_s = p.dt_s;
    r.default_look = r.rest_level_m != 0.0 ? LookRequest::shallow : LookRequest::pool;  // water over a bed
    return r;
  }
  /// The scene's render block and obstacle shapes (set by make_lbm_solver).
  RenderInfo from_scene;

 private:
  void refresh() {
    sim_.depth(h_);
    for (std::size_t i = 0; i < h_.size(); ++i) eta_[i] = h_[i] + bed_[i];
  }
  LbmShallow sim_;
  int ranks_ = 1;
  std::vector<float> h_, eta_, u_, bed_;
};

// What naming a refused parameter needs from the parse.
struct ParseNotes {
  /// The time step came from dt_s (else from cfl).
  bool dt_given = false;
  /// The viscosity came from tau (else from viscosity_m2s).
  bool tau_given = false;
  /// Largest dam depth ratio h_L/h_R whose Stoker middle state has Froude <= kLbmMaxFroude.
  double dam_ratio_max = 0;
};

std::string refusal_path(const std::string& param, const ParseNotes& notes) {
  if (param == "viscosity_m2s") return notes.tau_given ? "$.lbm.water.tau" : "$.lbm.water.viscosity_m2s";
  if (param == "dt_s") return notes.dt_given ? "$.lbm.time.dt_s" : "$.lbm.time.cfl";
  if (param == "cell_m" || param == "cols") return "$.lbm.grid." + param;
  if (param == "gravity_mps2" || param == "min_depth_m") return "$.lbm.water." + param;
  if (param == "depth_m") return "$.lbm.initial";
  if (param == "bed_m") return "$.lbm.bed";
  if (param == "solid") return "$.lbm.obstacles";
  if (param == "outflow_depth_m") return "$.lbm.outflow.depth_m";
  if (param == "left" || param == "right" || param == "bottom" || param == "top") return "$.lbm.boundaries." + param;
  return "$.lbm";
}

std::size_t cell_count(const LbmParams& p) { return static_cast<std::size_t>(p.rows) * p.cols; }

// Calls fn(i, x, y) for every cell i = r cols + c, centre (x, y) = ((c + 1/2) dx, (r + 1/2) dx) (unit: m).
template <class Fn>
void for_each_cell(const LbmParams& p, Fn fn) {
  for (int r = 0; r < p.rows; ++r)
    for (int c = 0; c < p.cols; ++c)
      fn(static_cast<std::size_t>(r) * p.cols + c, (c + 0.5) * p.cell_m, (r + 0.5) * p.cell_m);
}

// The cells (index range, half-open) whose centres may lie in [lo, hi] along an axis of n cells:
// a cell more on each side than the centres strictly inside, so `fn`'s exact test decides.
std::pair<int, int> cell_span(double lo, double hi, double cell, int n) {
  const double a = std::floor(lo / cell - 0.5), b = std::ceil(hi / cell - 0.5) + 1;
  return {static_cast<int>(std::clamp(a, 0.0, double(n))), static_cast<int>(std::clamp(b, 0.0, double(n)))};
}

// A shape's box [x0, x1] x [y0, y1] (unit: m) in cells, with the margin of cell_span (an upper
// bound of the cells it covers).
std::uint64_t box_cells(const LbmParams& p, double x0, double x1, double y0, double y1) {
  const auto [c0, c1] = cell_span(x0, x1, p.cell_m, p.cols);
  const auto [r0, r1] = cell_span(y0, y1, p.cell_m, p.rows);
  return static_cast<std::uint64_t>(std::max(0, c1 - c0)) * static_cast<std::uint64_t>(std::max(0, r1 - r0));
}

// for_each_cell over the cells of the box [x0, x1] x [y0, y1] only: a shape costs its own area,
// not the grid's, so thousands of small shapes are set up in time proportional to their cells
template <class Fn>
void for_each_cell_in(const LbmParams& p, double x0, double x1, double y0, double y1, Fn fn) {
  const auto [c0, c1] = cell_span(x0, x1, p.cell_m, p.cols);
  const auto [r0, r1] = cell_span(y0, y1, p.cell_m, p.rows);
  for (int r = r0; r < r1; ++r)
    for (int c = c0; c < c1; ++c)
      fn(static_cast<std::size_t>(r) * p.cols + c, (c + 0.5) * p.cell_m, (r + 0.5) * p.cell_m);
}

// The shapes of one list (regions, obstacles) may together cover at most this many times the
// grid's cells (a later shape overwrites an earlier one: deeper overlaps only cost set-up time)
constexpr std::uint64_t kShapeCover = 64;

// Counts a shape's box against the list's bound; refuses at the list's key past it.
void count_cover(const JsonIn& owner, const char* key, const LbmParams& p, std::uint64_t& covered, double x0, double x1,
                 double y0, double y1) {
  covered += box_cells(p, x0, x1, y0, y1);
  if (covered > kShapeCover * cell_count(p))
    owner.fail(key, "the " + std::string(key) + " together cover more than " + std::to_string(kShapeCover) +
                        " times the grid's cells (each is painted over the cells of its box; later ones win): "
                        "merge or remove overlapping ones");
}

void parse_grid(const JsonIn& lb, LbmParams& p) {
  const JsonIn grid = lb.object("grid");
  grid.allow_only({"cols", "rows", "cell_m"});
  p.cols = static_cast<int>(grid.integer("cols", 1, 16384));
  p.rows = static_cast<int>(grid.integer("rows", 1, 16384));
  p.cell_m = grid.number("cell_m", 1e-6, 1e6);
}

// Gravity, the dry threshold and the viscosity; returns tau when the scene gives it instead of
// viscosity_m2s (nu = (tau - 1/2) dx^2 / (3 dt) once dt is known).
std::optional<double> parse_water(const JsonIn& lb, LbmParams& p) {
  const std::optional<JsonIn> w = lb.optional_object("water");
  if (!w) return std::nullopt;
  w->allow_only({"gravity_mps2", "viscosity_m2s", "tau", "min_depth_m"});
  if (w->has("viscosity_m2s") && w->has("tau")) w->fail("tau", "give viscosity_m2s or tau, not both");
  p.gravity_mps2 = w->number("gravity_mps2", 9.81, 1e-6, 1e3);
  p.min_depth_m = w->number("min_depth_m", p.min_depth_m, 1e-12, 1e3);
  const std::optional<double> tau = w->has("tau") ? std::optional(w->number("tau", 0.0, 100.0)) : std::nullopt;
  p.viscosity_m2s = w->number("viscosity_m2s", 1e-3, 0.0, 1e6);
  return tau;
}

// The Goutal-Maurel bump shape: z = height (1 - ((x - x_m) / half_width)^2) where |x - x_m| < half_width.
void bump_bed(const JsonIn& bed, const LbmParams& p, std::vector<float>& z) {
  bed.allow_only({"type", "x_m", "half_width_m", "height_m"});
  const double x0 = bed.number("x_m", -1e9, 1e9), w = bed.number("half_width_m", 1e-9, 1e9);
  const double hb = bed.number("height_m", -1e4, 1e4);
  for_each_cell(p, [&](std::size_t i, double x, double) {
    const double s = (x - x0) / w;
    z[i] = static_cast<float>(std::abs(s) < 1 ? hb * (1 - s * s) : 0.0);
  });
}

// A float32 (rows, cols) array in metres; a relative file name is relative to the scene file.
std::vector<float> npy_bed(const JsonIn& bed, const Scene& scene, const LbmParams& p) {
  bed.allow_only({"type", "file"});
  std::filesystem::path file = bed.string("file", "");
  if (file.empty()) bed.fail("file", "missing required file name");
  if (file.is_relative()) file = std::filesystem::path(scene.file).parent_path() / file;
  NpyArray a;
  try {
    a = read_npy(file.string());
  } catch (const std::exception& e) {
    bed.fail("file", std::string("cannot read bed: ") + e.what());
  }
  if (a.shape.size() != 2 || a.shape[0] != static_cast<std::size_t>(p.rows) ||
      a.shape[1] != static_cast<std::size_t>(p.cols))
    bed.fail("file", "bed array must have shape (rows, cols) = (" + std::to_string(p.rows) + ", " +
                         std::to_string(p.cols) + ")");
  // the same range as a flat or bump bed's heights
  if (const auto i = first_invalid(a.data, -1e4, 1e4))
    bed.fail("file", "bed value " + fmt("%g", a.data[*i]) + " at row " + std::to_string(*i / p.cols) + ", column " +
                         std::to_string(*i % p.cols) + " (flat index " + std::to_string(*i) + ") of " + file.string() +
                         " is not a finite height in [-1e4, 1e4] m");
  return std::move(a.data);
}

// "bed" (flat, bump or npy; absent = flat at 0) and "bed_force".
void parse_bed(const JsonIn& lb, const Scene& scene, LbmParams& p, LbmFields& f) {
  f.bed_m.assign(cell_count(p), 0.0f);
  if (auto bed = lb.optional_object("bed")) {
    const std::string type = bed->string("type", "flat", {"flat", "bump", "npy"});
    if (type == "flat") {
      bed->allow_only({"type", "z_m"});
      std::fill(f.bed_m.begin(), f.bed_m.end(), static_cast<float>(bed->number("z_m", 0.0, -1e4, 1e4)));
    } else if (type == "bump") {
      bump_bed(*bed, p, f.bed_m);
    } else {
      f.bed_m = npy_bed(*bed, scene, p);
    }
  }
  const std::string bed_force = lb.string("bed_force", "centred", {"centred", "naive"});
  p.bed_force = bed_force == "naive" ? LbmBedForce::naive : LbmBedForce::centred;
}

// The water level of object o ("depth_m", or "surface_m" minus the bed, 0 where the bed stands
// above the surface: dry land) at cell i; neither: unchanged.
void set_level(const JsonIn& o, std::size_t i, LbmFields& f) {
  if (o.has("depth_m"))
    f.depth_m[i] = static_cast<float>(o.number("depth_m", -1e4, 1e4));
  else if (o.has("surface_m"))
    f.depth_m[i] = std::max(0.0f, static_cast<float>(o.number("surface_m", -1e4, 1e4) - f.bed_m[i]));
}

// The flow a dam releases (Stoker 1957): it bounds the time step and is refused when transcritical.
struct DamFlow {
  /// Largest |u| + sqrt(g h) of the Stoker solution (unit: m/s); 0 = no dam.
  double signal_speed_mps = 0;
  /// Froude number of the Stoker middle state.
  double froude = 0;
  /// Largest depth ratio h_L/h_R whose middle state has Froude <= kLbmMaxFroude.
  double ratio_max = 0;
};

// Froude number u_m / sqrt(g h_m) of the Stoker middle state.
double middle_froude(const StokerSolution& s) {
  return s.middle_velocity_mps / std::sqrt(s.params.gravity_mps2 * s.middle_depth_m);
}

// "dam": left_depth_m for x < x_m, right_depth_m beyond, and the flow it releases.
DamFlow parse_dam(const JsonIn& dam, const LbmParams& p, LbmFields& f) {
  dam.allow_only({"x_m", "left_depth_m", "right_depth_m"});
  const double xd = dam.number("x_m", -1e9, 1e9);
  const double hl = dam.number("left_depth_m", 0.0, 1e4), hr = dam.number("right_depth_m", 0.0, 1e4);
  for_each_cell(p, [&](std::size_t i, double x, double) { f.depth_m[i] = static_cast<float>(x < xd ? hl : hr); });
  DamFlow flow;
  const double g = p.gravity_mps2;
  if (hl != hr && std::min(hl, hr) < p.min_depth_m) {  // onto a dry bed: the front moves at 2 sqrt(g h) (Ritter)
    flow.signal_speed_mps = 2.0 * std::sqrt(g * std::max(hl, hr));
    return flow;
  }
  if (hl == hr) return flow;
  const StokerSolution st = stoker_solve({std::max(hl, hr), std::min(hl, hr), g});
  flow.signal_speed_mps = st.max_signal_speed_mps;
  flow.froude = middle_froude(st);
  double lo = 1.0001, hi = 100.0;  // bisection on the ratio
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (middle_froude(stoker_solve({1.0, 1.0 / mid, g})) > kLbmMaxFroude ? hi : lo) = mid;
  }
  flow.ratio_max = lo;
  return flow;
}

// A region or obstacle that holds no cell centre (outside the grid, x1 <= x0, smaller than a cell)
// would do nothing: a misplaced shape is refused rather than run without it.
[[noreturn]] void fail_no_cell(const JsonIn& shape, const char* what) {
  shape.fail_here(std::string("the ") + what +
                  " holds no cell centre of the grid (outside it, x1 <= x0 or y1 <= y0, or smaller than a cell)");
}

// "regions": rectangles [x0, x1) x [y0, y1) (unit: m) with their own level and velocity.
void parse_regions(const JsonIn& init, const LbmParams& p, LbmFields& f) {
  std::uint64_t covered = 0;
  for (const JsonIn& reg : init.array("regions")) {
    reg.allow_only({"x0_m", "x1_m", "y0_m", "y1_m", "depth_m", "surface_m", "velocity_mps"});
    const double x0 = reg.number("x0_m", -1e9, -1e9, 1e9), x1 = reg.number("x1_m", 1e9, -1e9, 1e9);
    const double y0 = reg.number("y0_m", -1e9, -1e9, 1e9), y1 = reg.number("y1_m", 1e9, -1e9, 1e9);
    if (reg.has("depth_m") && reg.has("surface_m")) reg.fail("surface_m", "give depth_m or surface_m, not both");
    const bool has_u = reg.has("velocity_mps");
    const auto u = vec2_or_zero(reg, "velocity_mps", -1e4, 1e4);
    count_cover(init, "regions", p, covered, x0, x1, y0, y1);
    std::size_t cells = 0;
    for_each_cell_in(p, x0, x1, y0, y1, [&](std::size_t i, double x, double y) {
      if (x < x0 || x >= x1 || y < y0 || y >= y1) return;
      ++cells;
      set_level(reg, i, f);
      if (has_u) {
        f.ux_mps[i] = static_cast<float>(u[0]);
        f.uy_mps[i] = static_cast<float>(u[1]);
      }
    });
    if (cells == 0) fail_no_cell(reg, "region");
  }
}

// "initial": a uniform level and velocity, then the dam, then the regions (later ones win).
DamFlow parse_initial(const JsonIn& lb, const LbmParams& p, LbmFields& f) {
  const std::size_t n = cell_count(p);
  f.depth_m.assign(n, 0.0f);
  f.ux_mps.assign(n, 0.0f);
  f.uy_mps.assign(n, 0.0f);
  const JsonIn init = lb.object("initial");
  init.allow_only({"depth_m", "surface_m", "velocity_mps", "regions", "dam"});
  if (init.has("depth_m") && init.has("surface_m")) init.fail("surface_m", "give depth_m or surface_m, not both");
  if (!init.has("depth_m") && !init.has("surface_m") && !init.has("dam"))
    init.fail_here("needs depth_m, surface_m or a dam");
  const auto u0 = vec2_or_zero(init, "velocity_mps", -1e4, 1e4);
  for (std::size_t i = 0; i < n; ++i) {
    set_level(init, i, f);
    f.ux_mps[i] = static_cast<float>(u0[0]);
    f.uy_mps[i] = static_cast<float>(u0[1]);
  }
  DamFlow flow;
  if (auto dam = init.optional_object("dam")) flow = parse_dam(*dam, p, f);
  parse_regions(init, p, f);
  return flow;
}

// "obstacles": solid circles (centre x_m, y_m, radius_m) and rectangles [x0, x1) x [y0, y1).
void parse_obstacles(const JsonIn& lb, const LbmParams& p, LbmFields& f, std::vector<RenderObstacle>& shapes) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  f.solid.assign(cell_count(p), 0);
  std::uint64_t covered = 0;
  for (const JsonIn& ob : lb.array("obstacles")) {
    const std::string type = ob.string("type", "", {"circle", "rect"});
    if (type == "circle") {
      ob.allow_only({"type", "x_m", "y_m", "radius_m"});
      const double cx = ob.number("x_m", -1e9, 1e9), cy = ob.number("y_m", -1e9, 1e9);
      const double rad = ob.number("radius_m", 0.0, 1e9);
      count_cover(lb, "obstacles", p, covered, cx - rad, cx + rad, cy - rad, cy + rad);
      std::size_t cells = 0;
      for_each_cell_in(p, cx - rad, cx + rad, cy - rad, cy + rad, [&](std::size_t i, double xc, double yc) {
        const double x = xc - cx, y = yc - cy;
        if (x * x + y * y <= rad * rad) f.solid[i] = 1, ++cells;
      });
      if (cells == 0) fail_no_cell(ob, "obstacle");
      RenderObstacle s;
      s.kind = RenderObstacle::Kind::cylinder;
      s.centre_m = {cx, cy};
      s.radius_m = rad;
      s.z0_m = -kInf, s.z1_m = kInf;
      shapes.push_back(s);
    } else {
      ob.allow_only({"type", "x0_m", "x1_m", "y0_m", "y1_m"});
      const double x0 = ob.number("x0_m", -1e9, 1e9), x1 = ob.number("x1_m", -1e9, 1e9);
      const double y0 = ob.number("y0_m", -1e9, 1e9), y1 = ob.number("y1_m", -1e9, 1e9);
      count_cover(lb, "obstacles", p, covered, x0, x1, y0, y1);
      std::size_t cells = 0;
      for_each_cell_in(p, x0, x1, y0, y1, [&](std::size_t i, double x, double y) {
        if (x >= x0 && x < x1 && y >= y0 && y < y1) f.solid[i] = 1, ++cells;
      });
      if (cells == 0) fail_no_cell(ob, "obstacle");
      RenderObstacle s;
      s.min_m = {x0, y0, -kInf};
      s.max_m = {x1, y1, kInf};
      shapes.push_back(s);
    }
  }
}

LbmSide parse_side(const JsonIn& b, const char* key) {
  const std::string s = b.string(key, "wall", {"wall", "slip", "periodic", "inflow", "outflow"});
  if (s == "slip") return LbmSide::slip;
  if (s == "periodic") return LbmSide::periodic;
  if (s == "inflow") return LbmSide::inflow;
  if (s == "outflow") return LbmSide::outflow;
  return LbmSide::wall;
}

// "boundaries", the "inflow" discharge the left inflow side needs, the "outflow" depth and the
// uniform "force".
void parse_boundaries(const JsonIn& lb, LbmParams& p) {
  if (auto b = lb.optional_object("boundaries")) {
    b->allow_only({"left", "right", "bottom", "top"});
    p.left = parse_side(*b, "left");
    p.right = parse_side(*b, "right");
    p.bottom = parse_side(*b, "bottom");
    p.top = parse_side(*b, "top");
  }
  if (auto in = lb.optional_object("inflow")) {
    in->allow_only({"discharge_m2s"});
    p.inflow_discharge_m2s = in->number("discharge_m2s", 0.0, 1e6);
    if (p.left != LbmSide::inflow) lb.fail("inflow", "given, but $.lbm.boundaries.left is not \"inflow\"");
  } else if (p.left == LbmSide::inflow) {
    lb.fail("inflow", "missing: an inflow side needs {\"discharge_m2s\": q}");
  }
  if (auto out = lb.optional_object("outflow")) {
    out->allow_only({"depth_m"});
    p.outflow_depth_m = out->number("depth_m", 0.0, 0.0, 1e4);
    if (p.right != LbmSide::outflow) lb.fail("outflow", "given, but $.lbm.boundaries.right is not \"outflow\"");
  }
  if (auto fo = lb.optional_object("force")) {
    fo->allow_only({"accel_mps2"});
    p.accel_mps2 = vec2_or_zero(*fo, "accel_mps2", -1e4, 1e4);
  }
}

// "time": dt_s, or dt = cfl dx / max(|u| + sqrt(g h)) over the initial fluid cells and the dam's
// flow (default cfl 0.5). Returns whether dt_s was given.
bool parse_time(const JsonIn& lb, const LbmFields& f, double expected_speed_mps, LbmParams& p) {
  const double g = p.gravity_mps2, dx = p.cell_m;
  double smax = expected_speed_mps;
  for (std::size_t i = 0; i < f.depth_m.size(); ++i)
    if (!f.solid[i] && f.depth_m[i] > 0)
      smax = std::max(smax, std::hypot(f.ux_mps[i], f.uy_mps[i]) + std::sqrt(g * f.depth_m[i]));
  const std::optional<JsonIn> t = lb.optional_object("time");
  if (!t) {
    p.dt_s = 0.5 * dx / std::max(smax, 1e-12);
    return false;
  }
  t->allow_only({"dt_s", "cfl"});
  if (t->has("dt_s") && t->has("cfl")) t->fail("cfl", "give dt_s or cfl, not both");
  if (t->has("dt_s")) {
    p.dt_s = t->number("dt_s", 1e-12, 1e6);
    return true;
  }
  p.dt_s = t->number("cfl", 0.5, 1e-6, 10.0) * dx / std::max(smax, 1e-12);
  return false;
}

// lbm_check() of the parsed scene; a refusal becomes a SceneError at the key that set the parameter.
void check_scene(const LbmScene& s, const ParseNotes& notes) {
  try {
    lbm_check(s.params, s.fields);
  } catch (const LbmRefused& e) {
    if (e.parameter() == "expected_froude")
      throw SceneError(
          "$.lbm.initial.dam.right_depth_m",
          std::string(e.what()) + "; for this dam use a depth ratio h_L/h_R <= " + fmt("%.2f", notes.dam_ratio_max));
    throw SceneError(refusal_path(e.parameter(), notes), e.what());
  }
}

}  // namespace

MemoryEstimate lbm_memory(const LbmParams& p, int ranks, bool carry) {
  const std::uint64_t cells = static_cast<std::uint64_t>(p.rows) * p.cols;
  // the largest rank's rows (row_slab: the first ranks hold one row more) and its lattice rows:
  // one rank has a ghost row each side, several ranks two halo rows each side and an image row
  const std::uint64_t rows = (static_cast<std::uint64_t>(p.rows) + ranks - 1) / ranks;
  const std::uint64_t lattice = (rows + (ranks > 1 ? 5 : 2)) * (p.cols + 2);
  MemoryEstimate m;
  m.size_key = "$.lbm.grid (rows x cols)";
  // two sets of 9 populations, depth now and next, bed, the wet/dry outflow limiter (floats), the
  // solid flags (bytes)
  m.add("lattice", lattice * (18 * 4 + 4 * 4 + 1));
  if (carry) m.add("mass carry", lattice * 4);  // a scene that starts dry: the wet/dry pass's carry
  // the scene's fields (bed, depth, ux, uy, solid): every rank parses the whole scene
  m.add("scene fields", cells * (4 * 4 + 1));
  m.add("output fields", rows * p.cols * 5 * 4);  // this rank's rows of h, eta, u, v, bed
  if (ranks > 1) m.add("halo buffers", 4 * 11 * 4 * static_cast<std::uint64_t>(p.cols));  // halo.cpp
  return m;
}

bool lbm_scene_may_start_dry(const Scene& scene) {
  LbmParams p;
  parse_grid(scene.root().object("lbm"), p);
  const std::uint64_t fields = static_cast<std::uint64_t>(p.rows) * p.cols * (4 * 4 + 1);  // as lbm_memory
  if (fields > available_memory() / 2) return true;  // its fields cannot be built here: counted
  const MemoryCheckOff sizing_only;
  const LbmScene s = parse_lbm_scene(scene);
  return lbm_starts_dry(s.params, s.fields);
}

MemoryEstimate lbm_scene_memory(const Scene& scene, int ranks, bool carry) {
  LbmParams p;
  parse_grid(scene.root().object("lbm"), p);
  return lbm_memory(p, ranks, carry);
}

LbmScene parse_lbm_scene(const Scene& scene) {
  const JsonIn root = scene.root();
  root.allow_only({"solver", "lbm", "description", "render"});
  root.string("description", "");  // a string, as in the Huygens scene
  const JsonIn lb = root.object("lbm");
  LbmScene s;
  s.render = parse_render_request(root);
  lb.allow_only({"grid", "time", "water", "bed", "bed_force", "initial", "boundaries", "inflow", "outflow", "obstacles",
                 "force"});
  LbmParams& p = s.params;
  parse_grid(lb, p);
  require_memory(lbm_memory(p, comm::size()));  // before the bed and initial fields, the first allocations
  const std::optional<double> tau = parse_water(lb, p);
  parse_bed(lb, scene, p, s.fields);
  const DamFlow dam = parse_initial(lb, p, s.fields);
  parse_obstacles(lb, p, s.fields, s.obstacles);
  if (lbm_starts_dry(p, s.fields)) require_memory(lbm_memory(p, comm::size(), true));  // plus the carry plane
  parse_boundaries(lb, p);
  ParseNotes notes;
  notes.dt_given = parse_time(lb, s.fields, dam.signal_speed_mps, p);
  notes.tau_given = tau.has_value();
  notes.dam_ratio_max = dam.ratio_max;
  p.expected_signal_speed_mps = dam.signal_speed_mps;
  p.expected_froude = dam.froude;
  if (tau) p.viscosity_m2s = (*tau - 0.5) * p.cell_m * p.cell_m / (3.0 * p.dt_s);
  check_scene(s, notes);
  return s;
}

std::unique_ptr<Solver> make_lbm_solver(const LbmScene& scene) {
  std::unique_ptr<LbmSolver> solver;
  try {  // on MPI ranks (comm.hpp) each holds its rows
    solver = std::make_unique<LbmSolver>(scene.params, scene.fields, LbmDecomposition{comm::size(), comm::rank()});
  } catch (const LbmRefused& e) {
    throw SceneError("$.lbm.grid.rows", e.what());
  }
  solver->from_scene.request = scene.render;
  solver->from_scene.obstacles = scene.obstacles;
  return solver;
}

std::unique_ptr<Solver> make_lbm_solver(const Scene& scene, const RunOptions&) {
  return make_lbm_solver(parse_lbm_scene(scene));
}

namespace {

// at least 3 rows per rank (docs/scale.md)
SceneSizing lbm_sizing(const Scene& scene) {
  const JsonIn g = scene.root().object("lbm").object("grid");
  const long long rows = g.integer("rows", 1, 16384), cols = g.integer("cols", 1, 16384);
  return SceneSizing{"lbm", std::to_string(rows) + " rows x " + std::to_string(cols) + " cols",
                     static_cast<int>(std::max(1LL, rows / 3)), true, "3 rows per rank at least"};
}

}  // namespace

SolverEntry lbm_solver_entry() {
  SolverEntry e;
  e.name = "lbm";
  e.summary = "lattice Boltzmann shallow water (D2Q9) with beds, wet/dry fronts and obstacles";
  e.make = [](const Scene& s, const RunOptions& o) { return make_lbm_solver(s, o); };
  e.sizing = lbm_sizing;
  e.rank_memory = [](const Scene& scene) -> std::function<MemoryEstimate(int)> {
    const bool carry = lbm_scene_may_start_dry(scene);
    return [&scene, carry](int p) { return lbm_scene_memory(scene, p, carry); };
  };
  e.bench_scene = std::string(shipped_scene_text("dam_break.json"));
  e.bench_steps = 200;
  return e;
}

}  // namespace huygens
