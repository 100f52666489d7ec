// "solver": "lbm" scenes: the D2Q9 shallow-water lattice Boltzmann solver (lbm_shallow.hpp)
// behind the Solver interface. Scene block (every key optional unless marked):
//   "lbm": {
//     "grid":   {"cols": N (req.), "rows": M (req.), "cell_m": dx (req.)},
//     "time":   {"dt_s": dt} or {"cfl": 0.5}   (dt = cfl dx / max(|u| + sqrt(g h)); default cfl 0.5)
//     "water":  {"gravity_mps2": 9.81, "viscosity_m2s": nu} or {"tau": 0.6}, "min_depth_m": 1e-4},
//     "bed":    {"type": "flat", "z_m": 0} | {"type": "bump", "x_m", "half_width_m", "height_m"}
//               (z = height (1 - ((x - x_m)/half_width)^2) inside, Goutal-Maurel shape)
//               | {"type": "npy", "file": "bed.npy"} (float32 (rows, cols), metres, relative to the scene),
//     "bed_force": "centred" | "naive",
//     "initial": {"depth_m": h | "surface_m": eta, "velocity_mps": [u, v],
//                 "regions": [{"x0_m", "x1_m", "y0_m", "y1_m", "depth_m" | "surface_m", "velocity_mps"}],
//                 "dam": {"x_m", "left_depth_m", "right_depth_m"}},
//     "boundaries": {"left"|"right"|"bottom"|"top": "wall" | "slip" | "periodic" | "inflow" | "outflow"},
//     "inflow": {"discharge_m2s": q}, "outflow": {"depth_m": h},
//     "obstacles": [{"type": "circle", "x_m", "y_m", "radius_m"} | {"type": "rect", "x0_m", "x1_m", "y0_m", "y1_m"}],
//     "force": {"accel_mps2": [ax, ay]}
//   }
// Positions are metres from the corner of cell (0, 0); cell (r, c) has its centre at ((c + 1/2) dx, (r + 1/2) dx).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "huygens/lbm/shallow.hpp"
#include "huygens/common/npy.hpp"
#include "huygens/common/report.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/lbm/stoker.hpp"

namespace huygens {

namespace {

using nlohmann::json;

LbmSide parse_side(const JsonIn& b, const char* key) {
  const std::string s = b.string(key, "wall", {"wall", "slip", "periodic", "inflow", "outflow"});
  if (s == "slip") return LbmSide::slip;
  if (s == "periodic") return LbmSide::periodic;
  if (s == "inflow") return LbmSide::inflow;
  if (s == "outflow") return LbmSide::outflow;
  return LbmSide::wall;
}

std::array<double, 2> parse_vec2(const JsonIn& o, const char* key, double lo, double hi) {
  std::array<double, 2> v{0.0, 0.0};
  if (!o.has(key) || o.is_null(key)) return v;
  const json& j = o.raw()[key];
  if (!j.is_array() || j.size() != 2) o.fail(key, "expected an array of two numbers");
  for (int i = 0; i < 2; ++i) {
    if (!j[i].is_number()) o.fail(key, "expected an array of two numbers");
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i]) || v[i] < lo || v[i] > hi) o.fail(key, "component out of range");
  }
  return v;
}

class LbmSolver final : public Solver {
 public:
  LbmSolver(const LbmParams& p, const LbmFields& f) : sim_(p, f) {
    const std::size_t n = static_cast<std::size_t>(p.rows) * p.cols;
    h_.resize(n);
    eta_.resize(n);
    u_.resize(2 * n);
    bed_.resize(n);
    sim_.bed(bed_);
  }
  void step() override { sim_.step(); }
  double time() const override { return sim_.time_s(); }
  std::int64_t steps() const override { return sim_.steps(); }
  std::vector<OutputField> outputs() override {
    refresh();
    sim_.velocity(u_);
    const std::size_t r = height_rows(), c = height_cols();
    return {{"h", {r, c}, h_}, {"u", {r, c, 2}, u_}, {"eta", {r, c}, eta_}};
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
            {"visible", {{"row0", 0}, {"row1", p.rows}, {"col0", 0}, {"col1", p.cols}}},
            {"fields",
             {{"h", "depth (m), 0 in obstacles"},
              {"u", "velocity (m/s), (rows, cols, 2)"},
              {"eta", "surface elevation h + z_b (m)"}}},
            {"dry_cells", "refused (no wetting and drying)"}};
  }
  const StageStats& stats() const override { return sim_.stats(); }
  std::span<const float> height() override {
    refresh();
    return eta_;
  }
  std::size_t height_rows() const override { return static_cast<std::size_t>(sim_.params().rows); }
  std::size_t height_cols() const override { return static_cast<std::size_t>(sim_.params().cols); }

 private:
  void refresh() {
    sim_.depth(h_);
    for (std::size_t i = 0; i < h_.size(); ++i) eta_[i] = h_[i] + bed_[i];
  }
  LbmShallow sim_;
  std::vector<float> h_, eta_, u_, bed_;
};

std::string refusal_path(const std::string& param, bool dt_given, bool tau_given) {
  if (param == "viscosity_m2s") return tau_given ? "$.lbm.water.tau" : "$.lbm.water.viscosity_m2s";
  if (param == "dt_s") return dt_given ? "$.lbm.time.dt_s" : "$.lbm.time.cfl";
  if (param == "cell_m" || param == "cols") return "$.lbm.grid." + param;
  if (param == "gravity_mps2" || param == "min_depth_m") return "$.lbm.water." + param;
  if (param == "depth_m") return "$.lbm.initial";
  if (param == "bed_m") return "$.lbm.bed";
  if (param == "solid") return "$.lbm.obstacles";
  if (param == "outflow_depth_m") return "$.lbm.outflow.depth_m";
  if (param == "left" || param == "right" || param == "bottom" || param == "top") return "$.lbm.boundaries." + param;
  return "$.lbm";
}

}  // namespace

std::unique_ptr<Solver> make_lbm_solver(const Scene& scene, const RunOptions&) {
  const JsonIn root = scene.root();
  root.allow_only({"solver", "lbm", "description", "render"});
  const JsonIn lb = root.object("lbm");
  lb.allow_only({"grid", "time", "water", "bed", "bed_force", "initial", "boundaries", "inflow", "outflow", "obstacles",
                 "force"});
  LbmParams p;
  const JsonIn grid = lb.object("grid");
  grid.allow_only({"cols", "rows", "cell_m"});
  p.cols = static_cast<int>(grid.integer("cols", 1, 16384));
  p.rows = static_cast<int>(grid.integer("rows", 1, 16384));
  p.cell_m = grid.number("cell_m", 1e-6, 1e6);
  const double dx = p.cell_m;
  const std::size_t n = static_cast<std::size_t>(p.rows) * p.cols;

  if (auto w = lb.optional_object("water")) {
    w->allow_only({"gravity_mps2", "viscosity_m2s", "tau", "min_depth_m"});
    if (w->has("viscosity_m2s") && w->has("tau")) w->fail("tau", "give viscosity_m2s or tau, not both");
    p.gravity_mps2 = w->number("gravity_mps2", 9.81, 1e-6, 1e3);
    p.min_depth_m = w->number("min_depth_m", p.min_depth_m, 1e-12, 1e3);
  }
  const std::optional<JsonIn> water = lb.optional_object("water");
  const bool tau_given = water && water->has("tau");
  const double tau = tau_given ? water->number("tau", 0.0, 100.0) : 0.0;
  p.viscosity_m2s = water ? water->number("viscosity_m2s", 1e-3, 0.0, 1e6) : 1e-3;
  const double g = p.gravity_mps2;

  // Bed.
  LbmFields f;
  f.bed_m.assign(n, 0.0f);
  if (auto bed = lb.optional_object("bed")) {
    const std::string type = bed->string("type", "flat", {"flat", "bump", "npy"});
    if (type == "flat") {
      bed->allow_only({"type", "z_m"});
      std::fill(f.bed_m.begin(), f.bed_m.end(), static_cast<float>(bed->number("z_m", 0.0, -1e4, 1e4)));
    } else if (type == "bump") {
      bed->allow_only({"type", "x_m", "half_width_m", "height_m"});
      const double x0 = bed->number("x_m", -1e9, 1e9), w = bed->number("half_width_m", 1e-9, 1e9);
      const double hb = bed->number("height_m", -1e4, 1e4);
      for (int r = 0; r < p.rows; ++r)
        for (int c = 0; c < p.cols; ++c) {
          const double s = ((c + 0.5) * dx - x0) / w;
          f.bed_m[static_cast<std::size_t>(r) * p.cols + c] =
              static_cast<float>(std::abs(s) < 1 ? hb * (1 - s * s) : 0.0);
        }
    } else {
      bed->allow_only({"type", "file"});
      std::filesystem::path file = bed->string("file", "");
      if (file.empty()) bed->fail("file", "missing required file name");
      if (file.is_relative()) file = std::filesystem::path(scene.file).parent_path() / file;
      NpyArray a;
      try {
        a = read_npy(file.string());
      } catch (const std::exception& e) {
        bed->fail("file", std::string("cannot read bed: ") + e.what());
      }
      if (a.shape.size() != 2 || a.shape[0] != static_cast<std::size_t>(p.rows) ||
          a.shape[1] != static_cast<std::size_t>(p.cols))
        bed->fail("file", "bed array must have shape (rows, cols) = (" + std::to_string(p.rows) + ", " +
                              std::to_string(p.cols) + ")");
      f.bed_m = a.data;
    }
  }
  std::string bed_force = lb.string("bed_force", "centred", {"centred", "naive"});
  p.bed_force = bed_force == "naive" ? LbmBedForce::naive : LbmBedForce::centred;

  // Initial depth and velocity.
  f.depth_m.assign(n, 0.0f);
  f.ux_mps.assign(n, 0.0f);
  f.uy_mps.assign(n, 0.0f);
  double expected_speed = 0, expected_froude = 0, dam_ratio_max = 0;
  const JsonIn init = lb.object("initial");
  init.allow_only({"depth_m", "surface_m", "velocity_mps", "regions", "dam"});
  auto set_level = [&](const JsonIn& o, std::size_t i) {
    if (o.has("depth_m"))
      f.depth_m[i] = static_cast<float>(o.number("depth_m", -1e4, 1e4));
    else if (o.has("surface_m"))
      f.depth_m[i] = static_cast<float>(o.number("surface_m", -1e4, 1e4) - f.bed_m[i]);
  };
  if (init.has("depth_m") && init.has("surface_m")) init.fail("surface_m", "give depth_m or surface_m, not both");
  if (!init.has("depth_m") && !init.has("surface_m") && !init.has("dam"))
    init.fail_here("needs depth_m, surface_m or a dam");
  const auto u0 = parse_vec2(init, "velocity_mps", -1e4, 1e4);
  for (std::size_t i = 0; i < n; ++i) {
    set_level(init, i);
    f.ux_mps[i] = static_cast<float>(u0[0]);
    f.uy_mps[i] = static_cast<float>(u0[1]);
  }
  if (auto dam = init.optional_object("dam")) {
    dam->allow_only({"x_m", "left_depth_m", "right_depth_m"});
    const double xd = dam->number("x_m", -1e9, 1e9);
    const double hl = dam->number("left_depth_m", 0.0, 1e4), hr = dam->number("right_depth_m", 0.0, 1e4);
    for (int r = 0; r < p.rows; ++r)
      for (int c = 0; c < p.cols; ++c)
        f.depth_m[static_cast<std::size_t>(r) * p.cols + c] = static_cast<float>((c + 0.5) * dx < xd ? hl : hr);
    // The flow the dam releases: its largest signal speed bounds the time step (Stoker).
    if (hl != hr && std::min(hl, hr) > 0) {
      const auto st = stoker_solve({std::max(hl, hr), std::min(hl, hr), g});
      expected_speed = st.max_signal_speed_mps;
      expected_froude = st.middle_velocity_mps / std::sqrt(g * st.middle_depth_m);
      // Largest depth ratio whose middle state stays below the Froude limit (bisection).
      double lo = 1.0001, hi = 100.0;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        const auto s = stoker_solve({1.0, 1.0 / mid, g});
        (s.middle_velocity_mps / std::sqrt(g * s.middle_depth_m) > kLbmMaxFroude ? hi : lo) = mid;
      }
      dam_ratio_max = lo;
    }
  }
  for (const JsonIn& reg : init.array("regions")) {
    reg.allow_only({"x0_m", "x1_m", "y0_m", "y1_m", "depth_m", "surface_m", "velocity_mps"});
    const double x0 = reg.number("x0_m", -1e9, -1e9, 1e9), x1 = reg.number("x1_m", 1e9, -1e9, 1e9);
    const double y0 = reg.number("y0_m", -1e9, -1e9, 1e9), y1 = reg.number("y1_m", 1e9, -1e9, 1e9);
    if (reg.has("depth_m") && reg.has("surface_m")) reg.fail("surface_m", "give depth_m or surface_m, not both");
    const bool has_u = reg.has("velocity_mps");
    const auto u = parse_vec2(reg, "velocity_mps", -1e4, 1e4);
    for (int r = 0; r < p.rows; ++r)
      for (int c = 0; c < p.cols; ++c) {
        const double x = (c + 0.5) * dx, y = (r + 0.5) * dx;
        if (x < x0 || x >= x1 || y < y0 || y >= y1) continue;
        const std::size_t i = static_cast<std::size_t>(r) * p.cols + c;
        set_level(reg, i);
        if (has_u) {
          f.ux_mps[i] = static_cast<float>(u[0]);
          f.uy_mps[i] = static_cast<float>(u[1]);
        }
      }
  }

  // Obstacles.
  f.solid.assign(n, 0);
  for (const JsonIn& ob : lb.array("obstacles")) {
    const std::string type = ob.string("type", "", {"circle", "rect"});
    if (type == "circle") {
      ob.allow_only({"type", "x_m", "y_m", "radius_m"});
      const double cx = ob.number("x_m", -1e9, 1e9), cy = ob.number("y_m", -1e9, 1e9);
      const double rad = ob.number("radius_m", 0.0, 1e9);
      for (int r = 0; r < p.rows; ++r)
        for (int c = 0; c < p.cols; ++c) {
          const double x = (c + 0.5) * dx - cx, y = (r + 0.5) * dx - cy;
          if (x * x + y * y <= rad * rad) f.solid[static_cast<std::size_t>(r) * p.cols + c] = 1;
        }
    } else {
      ob.allow_only({"type", "x0_m", "x1_m", "y0_m", "y1_m"});
      const double x0 = ob.number("x0_m", -1e9, 1e9), x1 = ob.number("x1_m", -1e9, 1e9);
      const double y0 = ob.number("y0_m", -1e9, 1e9), y1 = ob.number("y1_m", -1e9, 1e9);
      for (int r = 0; r < p.rows; ++r)
        for (int c = 0; c < p.cols; ++c) {
          const double x = (c + 0.5) * dx, y = (r + 0.5) * dx;
          if (x >= x0 && x < x1 && y >= y0 && y < y1) f.solid[static_cast<std::size_t>(r) * p.cols + c] = 1;
        }
    }
  }

  // Boundaries, inflow, outflow, force.
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
    p.accel_mps2 = parse_vec2(*fo, "accel_mps2", -1e4, 1e4);
  }

  // Time step: given, or from a lattice CFL number on the largest signal speed.
  bool dt_given = false;
  double smax = expected_speed;
  for (std::size_t i = 0; i < n; ++i)
    if (!f.solid[i] && f.depth_m[i] > 0)
      smax = std::max(smax, std::hypot(f.ux_mps[i], f.uy_mps[i]) + std::sqrt(g * f.depth_m[i]));
  if (auto t = lb.optional_object("time")) {
    t->allow_only({"dt_s", "cfl"});
    if (t->has("dt_s") && t->has("cfl")) t->fail("cfl", "give dt_s or cfl, not both");
    dt_given = t->has("dt_s");
    if (dt_given)
      p.dt_s = t->number("dt_s", 1e-12, 1e6);
    else
      p.dt_s = t->number("cfl", 0.5, 1e-6, 10.0) * dx / std::max(smax, 1e-12);
  } else {
    p.dt_s = 0.5 * dx / std::max(smax, 1e-12);
  }
  p.expected_signal_speed_mps = expected_speed;
  p.expected_froude = expected_froude;
  if (tau_given) p.viscosity_m2s = (tau - 0.5) * dx * dx / (3.0 * p.dt_s);

  try {
    return std::make_unique<LbmSolver>(p, f);
  } catch (const LbmRefused& e) {
    if (e.parameter() == "expected_froude")
      throw SceneError(
          "$.lbm.initial.dam.right_depth_m",
          std::string(e.what()) + "; for this dam use a depth ratio h_L/h_R <= " + fmt("%.2f", dam_ratio_max));
    throw SceneError(refusal_path(e.parameter(), dt_given, tau_given), e.what());
  }
}

}  // namespace huygens
