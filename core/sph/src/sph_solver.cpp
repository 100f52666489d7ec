// The Solver for "solver": "sph" scenes: parses the scene's "sph" block, steps SphSystem and
// extracts the heightfield (paper 000 eq. 5-6) when a frame or dump asks for it.
#include "huygens/sph/sph_solver.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "huygens/common/finite.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/pipeline/render_request.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/pipeline/solver_entry.hpp"
#include "huygens/sph/surface.hpp"
#include "huygens/sph/system.hpp"

namespace huygens {

namespace {

// JsonIn::vec<N> as floats (the parameter structs hold float)
template <std::size_t N>
std::array<float, N> vecf(const JsonIn& in, const std::string& key, double lo, double hi) {
  const auto v = in.vec<N>(key, lo, hi);
  std::array<float, N> out{};
  for (std::size_t k = 0; k < N; ++k) out[k] = static_cast<float>(v[k]);
  return out;
}

// The viewer draws boxes, vertical cylinders and meshes: a sphere as the cylinder around it, a mesh
// as its triangles (with its bounding box).
RenderObstacle render_obstacle(const SphObstacle& o) {
  RenderObstacle ro;
  using T = SphObstacle::Type;
  ro.kind = o.type == T::box    ? RenderObstacle::Kind::box
            : o.type == T::mesh ? RenderObstacle::Kind::mesh
                                : RenderObstacle::Kind::cylinder;
  if (o.type == T::mesh && o.mesh) {
    ro.triangles_m.reserve(9 * o.mesh->triangles.size());
    for (const auto& t : o.mesh->triangles)
      for (int c : t)
        ro.triangles_m.insert(ro.triangles_m.end(), o.mesh->vertices[c].begin(), o.mesh->vertices[c].end());
  }
  for (int a = 0; a < 3; ++a) ro.min_m[a] = o.min_m[a], ro.max_m[a] = o.max_m[a];
  ro.centre_m = {o.centre_m[0], o.centre_m[1]};
  ro.radius_m = o.radius_m;
  ro.z0_m = o.z0_m;
  ro.z1_m = o.z1_m;
  if (o.type == T::sphere) {
    ro.centre_m = {o.sphere_centre_m[0], o.sphere_centre_m[1]};
    ro.z0_m = o.sphere_centre_m[2] - o.radius_m;
    ro.z1_m = o.sphere_centre_m[2] + o.radius_m;
  }
  return ro;
}

// The arrays `comps` (one per component, in the current particle order) interleaved in particle-id
// order: out[k ids[i] + c] = comps[c][i], k = comps.size().
void by_id(std::span<const std::uint32_t> ids, std::initializer_list<std::span<const float>> comps,
           std::vector<float>& out) {
  const std::size_t k = comps.size();
  std::size_t c = 0;
  for (const auto& a : comps) {
    for (std::size_t i = 0; i < ids.size(); ++i) out[k * ids[i] + c] = a[i];
    ++c;
  }
}

class SphSolver final : public Solver {
 public:
  explicit SphSolver(const SphScene& sc) : scene_(sc), sys_(sc.params) {
    // blocks thinner than the spacing, or all inside obstacles, leave the lattice empty: refused,
    // not run with no water (an empty heightfield and empty dumps)
    if (sys_.count() == 0)
      throw SceneError("$.sph.fluid",
                       "the fluid blocks place no particle (thinner than spacing_m, or inside the "
                       "obstacles): no water to simulate");
    surface_stage_ = sys_.stats().add("surface");
    sph_heightfield_init(scene_.surface, sc.params.container_m[0], sc.params.container_m[1], hf_);
    sys_.stats()[surface_stage_].bytes = (hf_.height.size() + hf_.normal.size()) * sizeof(float);
    pos_.assign(sys_.count() * 3, 0.f);
    vel_.assign(sys_.count() * 3, 0.f);
    density_.assign(sys_.count(), 0.f);
    pressure_.assign(sys_.count(), 0.f);
  }
  MemoryEstimate memory() const override { return sph_memory(scene_); }

  void step() override {
    sys_.step();
    surface_valid_ = false;
  }
  double time() const override { return sys_.time(); }
  std::int64_t steps() const override { return sys_.steps(); }
  /// t + k dt_max: every step is at most dt_max (sph_choose_dt) and the time is their running sum.
  double time_bound(int k) const override {
    double t = sys_.time();
    for (int i = 0; i < k; ++i) t += static_cast<double>(sys_.params().dt_max_s);
    return t;
  }

  /// pos and vel (n, 3), density and pressure (n) in particle-id order, eta (rows, cols). The density
  /// and pressure are those of the last step's density pass (the positions before its move; at
  /// step 0 those of the initial positions).
  std::vector<OutputField> outputs() override {
    const std::size_t n = sys_.count();
    sys_.positions_by_id(pos_);
    by_id(sys_.ids(), {sys_.vx(), sys_.vy(), sys_.vz()}, vel_);
    by_id(sys_.ids(), {sys_.density()}, density_);
    by_id(sys_.ids(), {sys_.pressure()}, pressure_);
    auto h = height();
    return {OutputField{"pos", {n, 3}, std::span<const float>(pos_), {}, 0, true},
            OutputField{"vel", {n, 3}, std::span<const float>(vel_), {}, 0, true},
            OutputField{"density", {n}, std::span<const float>(density_), {}, 0, true},
            OutputField{"pressure", {n}, std::span<const float>(pressure_), {}, 0, true},
            OutputField{"eta", {hf_.rows, hf_.cols}, h}};
  }

  // made on the first call (a viewer's runner, when it is built), so a run without a viewer
  // does not pay the 16 bytes per particle (huygens-viz counts them in its memory estimate)
  std::span<const float> particles() override {
    if (particles_.empty()) particles_.assign(4 * sys_.count(), 0.0f);
    const auto x = sys_.x(), y = sys_.y(), z = sys_.z(), u = sys_.vx(), v = sys_.vy(), w = sys_.vz();
    for (std::size_t i = 0; i < x.size(); ++i) {
      float* p = &particles_[4 * i];
      p[0] = x[i], p[1] = y[i], p[2] = z[i], p[3] = std::sqrt(u[i] * u[i] + v[i] * v[i] + w[i] * w[i]);
    }
    return particles_;
  }

  nlohmann::json meta() const override {
    const auto& p = sys_.params();
    const auto& d = sys_.dt_stats();
    auto hist = sys_.dt_history();
    if (hist.size() > 256) hist.erase(hist.begin(), hist.end() - 256);
    return {{"solver", "sph"},
            {"particles", sys_.count()},
            {"spacing_m", p.spacing_m},
            {"support_m", sys_.support()},
            {"particle_mass_kg", sys_.mass()},
            {"rest_density_kgpm3", p.rest_density_kgpm3},
            {"sound_speed_mps", sys_.sound_speed()},
            {"viscosity_m2s", p.viscosity_m2s},
            {"artificial_viscosity", p.artificial_viscosity},
            {"impact_alpha", p.impact_alpha},
            {"impact_beta", p.impact_beta},
            {"viscosity_total_m2s", sys_.viscosity()},
            {"container_m", p.container_m},
            {"method", p.method == SphMethod::dfsph ? "dfsph" : "wcsph"},
            {"pressure_model", p.method == SphMethod::dfsph
                                   ? "divergence-free SPH (Bender and Koschier 2015), Akinci boundary"
                                   : "weakly compressible, Tait equation of state"},
            {"tait_gamma", p.tait_gamma},
            {"grid", {{"rows", hf_.rows}, {"cols", hf_.cols}, {"dx", hf_.cell_m}}},
            {"dx", hf_.cell_m},
            {"visible",
             {{"row0", 0},
              {"row1", hf_.rows},
              {"col0", 0},
              {"col1", hf_.cols},
              {"origin_m", {0.5 * hf_.cell_m, 0.5 * hf_.cell_m}},
              {"note", "origin_m is (x, y) of point (0, 0), the centre of heightfield cell (0, 0)"}}},
            {"eta_reference", "height of the iso-surface above the floor z = 0 (m); 0 where dry"},
            {"pos_order", "particle id (stable across dumps)"},
            {"fields",
             {{"pos", "particle positions (m), (n, 3), particle-id order"},
              {"vel", "particle velocities (m/s), (n, 3)"},
              {"density", "particle densities of the last density pass (kg/m^3), (n)"},
              {"pressure", "particle pressures of the last density pass (Pa), (n)"},
              {"eta", "heightfield (m), (rows, cols)"}}},
            {"surface", {{"iso", scene_.surface.iso}, {"radius_m", scene_.surface.radius_m}}},
            {"dt",
             {{"steps", d.count},
              {"last_s", d.last},
              {"min_s", d.min},
              {"max_s", d.max},
              {"mean_s", d.count ? d.sum / double(d.count) : 0.0},
              {"limiter", d.limiter},
              {"history_s", hist}}}};
  }

  const StageStats& stats() const override { return sys_.stats(); }

  std::span<const float> height() override {
    if (!surface_valid_) {
      {
        StageTimer t(sys_.stats()[surface_stage_]);
        sph_extract_heightfield(scene_.surface, sys_.grid(), sys_.x().data(), sys_.y().data(), sys_.z().data(), hf_);
      }
      if (!all_finite(std::span<const float>(hf_.height))) throw NonFiniteError("surface", sys_.steps());
      surface_valid_ = true;
    }
    return hf_.height;
  }
  /// Drop -> a downward velocity splash of speed depth sqrt(g / radius) (the depression made in the
  /// time a gravity wave crosses the radius); SetParam "gravity_x|y|z" (m/s^2) tilts or shakes the
  /// container through the gravity vector. Everything else is refused.
  bool apply(const Command& c) override {
    if (const auto* d = std::get_if<cmd::Drop>(&c)) {
      const auto& g = sys_.gravity();
      const float gm = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      const float r = std::max(d->radius_m, sys_.params().spacing_m);
      sys_.add_velocity_splash(d->x_m, d->y_m, r, d->depth_m * std::sqrt(gm / r));
      return true;
    }
    if (const auto* sp = std::get_if<cmd::SetParam>(&c)) {
      auto g = sys_.gravity();
      int axis = sp->name == "gravity_x" ? 0 : sp->name == "gravity_y" ? 1 : sp->name == "gravity_z" ? 2 : -1;
      if (axis < 0 || !std::isfinite(sp->value) || std::fabs(sp->value) > 1000.0) return false;
      g[static_cast<std::size_t>(axis)] = static_cast<float>(sp->value);
      sys_.set_gravity(g);
      return true;
    }
    return false;
  }
  std::size_t height_rows() const override { return hf_.rows; }
  std::size_t height_cols() const override { return hf_.cols; }
  /// Heightfield cell centres ((c + 1/2) cell, (r + 1/2) cell), the rest level (mean initial
  /// height above the floor, the ground that far down), the obstacles; an adaptive step shown
  /// at 60 frames per simulated second; no toggles. Makes the height (before the first step).
  RenderInfo render_info() override {
    RenderInfo r;
    const double c = hf_.cell_m;
    r.grid = RenderGrid{hf_.rows, hf_.cols, c, 0.5 * c, 0.5 * c};
    r.rest_level_m = mean_level(height());
    if (r.rest_level_m > 0.0) r.depth_m = r.rest_level_m;
    for (const SphObstacle& o : sys_.params().obstacles) {
      r.obstacles.push_back(render_obstacle(o));
    }
    r.frame_dt_s = 1.0 / 60.0;
    const auto& box = sys_.params().container_m;
    r.particle_box_m = std::array<double, 3>{box[0], box[1], box[2]};
    r.particle_spacing_m = sys_.params().spacing_m;
    r.request = scene_.render;
    r.default_look = r.rest_level_m != 0.0 ? LookRequest::sph : LookRequest::pool;
    return r;
  }

 private:
  SphScene scene_;
  SphSystem sys_;
  SphHeightfield hf_;
  std::vector<float> pos_, vel_, density_, pressure_;  // outputs(), in particle-id order
  std::vector<float> particles_;                       // x, y, z, |v| per particle (particles())
  int surface_stage_ = -1;
  bool surface_valid_ = false;
};

}  // namespace

namespace {

// The top-level keys of the "sph" block: fluid, viscosities, sound speed, gravity, container.
void parse_fluid_params(const JsonIn& s, SphParams& p) {
  p.spacing_m = static_cast<float>(s.number("spacing_m", 1e-4, 10.0));
  p.support_factor = static_cast<float>(s.number("support_factor", 2.0, 1.5, 4.0));
  p.rest_density_kgpm3 = static_cast<float>(s.number("rest_density_kgpm3", 1000.0, 1.0, 1e5));
  p.viscosity_m2s = static_cast<float>(s.number("viscosity_m2s", p.viscosity_m2s, 0.0, 10.0));
  p.artificial_viscosity = static_cast<float>(s.number("artificial_viscosity", p.artificial_viscosity, 0.0, 1.0));
  if (p.artificial_viscosity < SphParams::min_artificial_viscosity)
    s.fail("artificial_viscosity", "below " + num(SphParams::min_artificial_viscosity, 3) +
                                       " the poly6/spiky kernel mix pumps energy into the fluid (unstable); refused");
  p.impact_alpha = static_cast<float>(s.number("impact_alpha", p.impact_alpha, 0.0, 1.0));
  p.impact_beta = static_cast<float>(s.number("impact_beta", p.impact_beta, 0.0, 10.0));
  p.wall_alpha = static_cast<float>(s.number("wall_alpha", p.wall_alpha, 0.0, 10.0));
  if (auto c = s.optional_number("sound_speed_mps", 1e-3, 1e5)) p.sound_speed_mps = static_cast<float>(*c);
  if (s.has("gravity_mps2")) p.gravity_mps2 = vecf<3>(s, "gravity_mps2", -1000.0, 1000.0);
  p.container_m = vecf<3>(s, "container_m", 1e-4, 1e4);
  for (int a = 0; a < 3; ++a)
    if (p.container_m[a] < 2 * p.spacing_m)
      throw SceneError(s.child_path("container_m") + "[" + std::to_string(a) + "]",
                       "the container must be at least two particle spacings wide");
}

// "fluid": at least one block inside the container, at most ~2e7 particles.
void parse_fluid_blocks(const JsonIn& s, SphParams& p) {
  const auto blocks = s.array("fluid");
  if (blocks.empty()) s.fail("fluid", "at least one fluid block is required");
  double count = 0;
  for (const auto& b : blocks) {
    b.allow_only({"min_m", "max_m"});
    SphFluidBlock fb;
    fb.min_m = vecf<3>(b, "min_m", 0.0, 1e4);
    fb.max_m = vecf<3>(b, "max_m", 0.0, 1e4);
    for (int a = 0; a < 3; ++a) {
      if (fb.max_m[a] <= fb.min_m[a]) b.fail("max_m", "max_m must exceed min_m on every axis");
      if (fb.max_m[a] > p.container_m[a] + 1e-6f) b.fail("max_m", "the fluid block sticks out of the container");
    }
    count += double(fb.max_m[0] - fb.min_m[0]) * (fb.max_m[1] - fb.min_m[1]) * (fb.max_m[2] - fb.min_m[2]) /
             (double(p.spacing_m) * p.spacing_m * p.spacing_m);
    p.fluid.push_back(fb);
  }
  if (count > 2e7)
    s.fail("fluid", "the fluid blocks hold about " + std::to_string(long(count)) +
                        " particles; more than 2e7 is refused (memory)");
}

// A sound speed the scene sets must keep the Mach number below 0.3 (density error ~ Ma^2).
void check_sound_speed(const JsonIn& s, const SphParams& p) {
  if (!(p.sound_speed_mps > 0.f)) return;
  float top = 0.f;
  for (const auto& b : p.fluid) top = std::max(top, b.max_m[2]);
  const auto& gv = p.gravity_mps2;
  const float g = std::sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]);
  const float vref = std::sqrt(2.f * g * top);
  if (p.sound_speed_mps < 3.f * vref)
    s.fail("sound_speed_mps", "below 3 sqrt(2 g H) = " + num(3 * vref, 4) +
                                  " m/s the Mach number exceeds 0.3 and density errors exceed 10 %; refused");
}

// "mesh": a closed OBJ triangle mesh (path relative to the scene file: read_scene_file), scaled then
// moved by position_m.
void parse_mesh(const JsonIn& o, const Scene& scene, SphObstacle& ob) {
  o.allow_only({"type", "file", "position_m", "scale"});
  const std::string file = o.string("file", "");
  if (file.empty()) o.fail("file", "the OBJ file of the mesh is required");
  const std::array<float, 3> pos = o.has("position_m") ? vecf<3>(o, "position_m", -1e4, 1e4) : std::array<float, 3>{};
  const float scale = static_cast<float>(o.number("scale", 1.0, 1e-6, 1e6));
  SphMesh m;
  try {
    const std::string shown =
        scene.embedded ? file : (std::filesystem::path(scene.dir) / std::filesystem::path(file)).string();
    m = sph_parse_obj(read_scene_file(scene, file), shown);
  } catch (const std::runtime_error& e) {
    o.fail("file", e.what());
  }
  for (auto& v : m.vertices)
    for (int a = 0; a < 3; ++a) v[a] = v[a] * scale + pos[a];
  ob.set_mesh(std::move(m));
}

// An obstacle whose bounding box misses the container [0, L]^3 holds no boundary particle and
// touches no fluid: a misplaced obstacle (units, coordinates) is refused rather than run without it.
void check_in_container(const JsonIn& o, const SphObstacle& ob, const std::array<float, 3>& container) {
  std::array<float, 3> lo = ob.min_m, hi = ob.max_m;
  if (ob.type == SphObstacle::Type::sphere)
    for (int a = 0; a < 3; ++a)
      lo[a] = ob.sphere_centre_m[a] - ob.radius_m, hi[a] = ob.sphere_centre_m[a] + ob.radius_m;
  if (ob.type == SphObstacle::Type::cylinder)
    for (int a = 0; a < 3; ++a)
      lo[a] = a < 2 ? ob.centre_m[a] - ob.radius_m : ob.z0_m, hi[a] = a < 2 ? ob.centre_m[a] + ob.radius_m : ob.z1_m;
  for (int a = 0; a < 3; ++a)
    if (hi[a] <= 0.f || lo[a] >= container[a])
      o.fail_here("the obstacle lies outside the container [0, " + num(container[0], 4) + "] x [0, " +
                  num(container[1], 4) + "] x [0, " + num(container[2], 4) + "] m (its extent on axis " +
                  std::string(1, char('x' + a)) + ": [" + num(lo[a], 4) + ", " + num(hi[a], 4) + "] m)");
}

SphObstacle parse_obstacle(const JsonIn& o, const Scene& scene) {
  SphObstacle ob;
  const std::string type = o.string("type", "", {"box", "cylinder", "sphere", "mesh"});
  if (type == "box") {
    o.allow_only({"type", "min_m", "max_m"});
    ob.type = SphObstacle::Type::box;
    ob.min_m = vecf<3>(o, "min_m", -1e4, 1e4);
    ob.max_m = vecf<3>(o, "max_m", -1e4, 1e4);
    for (int a = 0; a < 3; ++a)
      if (ob.max_m[a] <= ob.min_m[a]) o.fail("max_m", "max_m must exceed min_m on every axis");
    return ob;
  }
  if (type == "sphere") {
    o.allow_only({"type", "centre_m", "radius_m"});
    ob.type = SphObstacle::Type::sphere;
    ob.sphere_centre_m = vecf<3>(o, "centre_m", -1e4, 1e4);
    ob.radius_m = static_cast<float>(o.number("radius_m", 1e-6, 1e4));
    return ob;
  }
  if (type == "mesh") {
    parse_mesh(o, scene, ob);
    return ob;
  }
  o.allow_only({"type", "centre_m", "radius_m", "z0_m", "z1_m"});
  ob.type = SphObstacle::Type::cylinder;
  ob.centre_m = vecf<2>(o, "centre_m", -1e4, 1e4);
  ob.radius_m = static_cast<float>(o.number("radius_m", 1e-6, 1e4));
  ob.z0_m = static_cast<float>(o.number("z0_m", 0.0, -1e4, 1e4));
  ob.z1_m = static_cast<float>(o.number("z1_m", -1e4, 1e4));
  if (ob.z1_m <= ob.z0_m) o.fail("z1_m", "z1_m must exceed z0_m");
  return ob;
}

// "time": the factors of the adaptive step and its largest value.
void parse_time(const JsonIn& s, SphParams& p) {
  const auto t = s.optional_object("time");
  if (!t) return;
  t->allow_only({"cfl", "force", "viscous", "dt_max_s"});
  p.cfl = static_cast<float>(t->number("cfl", p.cfl, 1e-3, 0.5));
  p.force_factor = static_cast<float>(t->number("force", p.force_factor, 1e-3, 0.5));
  p.viscous_factor = static_cast<float>(t->number("viscous", p.viscous_factor, 1e-3, 0.25));
  p.dt_max_s = static_cast<float>(t->number("dt_max_s", p.dt_max_s, 1e-7, 1.0));
}

// "surface": heightfield columns, iso-radius (at most the support radius) and iso value.
SphSurfaceParams parse_surface(const JsonIn& s, const SphParams& p) {
  SphSurfaceParams out;
  out.cell_m = p.spacing_m;
  out.radius_m = p.support();
  bool iso_given = false;
  if (auto f = s.optional_object("surface")) {
    f->allow_only({"cell_m", "radius_factor", "iso"});
    out.cell_m = static_cast<float>(f->number("cell_m", p.spacing_m, 1e-5, 1e4));
    const double rf = f->number("radius_factor", p.support_factor, 0.5, 4.0);
    if (rf > p.support_factor + 1e-6)
      f->fail("radius_factor", "the iso-radius must not exceed the support radius (support_factor)");
    out.radius_m = static_cast<float>(rf * p.spacing_m);
    if (auto iso = f->optional_number("iso", 1e-6, 1e6)) {
      out.iso = static_cast<float>(*iso);
      iso_given = true;
    }
    const double cells = std::ceil(p.container_m[0] / out.cell_m) * std::ceil(p.container_m[1] / out.cell_m);
    if (cells > 1.7e7) f->fail("cell_m", "the heightfield would have more than 1.7e7 columns");
  }
  if (!iso_given) out.iso = sph_flat_iso(out.radius_m, p.spacing_m);
  return out;
}

}  // namespace

namespace {

// Boundary particles a set-up samples, from the surface areas (unit: 1): layers per dx^2 of every
// wall and obstacle surface, meshes at up to 3 points per dx^2 (their sub-triangle sampling).
double boundary_estimate(const SphParams& p) {
  const double dx = p.spacing_m, K = sph_boundary_layers(p.support(), p.spacing_m), pi = 3.14159265358979;
  const auto& c = p.container_m;
  double area = 2.0 * (double(c[0]) * c[1] + double(c[1]) * c[2] + double(c[0]) * c[2]);
  for (const auto& o : p.obstacles) {
    const double R = o.radius_m;
    if (o.type == SphObstacle::Type::box) {
      const double e[3] = {double(o.max_m[0]) - o.min_m[0], double(o.max_m[1]) - o.min_m[1],
                           double(o.max_m[2]) - o.min_m[2]};
      area += 2.0 * (e[0] * e[1] + e[1] * e[2] + e[0] * e[2]);
    } else if (o.type == SphObstacle::Type::cylinder) {
      area += 2.0 * pi * R * (double(o.z1_m) - o.z0_m) + 2.0 * pi * R * R;
    } else if (o.type == SphObstacle::Type::sphere) {
      area += 4.0 * pi * R * R;
    } else {
      for (const auto& t : o.mesh->triangles) {
        const auto &a = o.mesh->vertices[t[0]], &b = o.mesh->vertices[t[1]], &d = o.mesh->vertices[t[2]];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        area += 3.0 * 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      }
    }
  }
  return area * K / (dx * dx);
}

}  // namespace

SphScene parse_sph_scene(const Scene& scene) {
  const JsonIn root = scene.root();
  root.allow_only({"solver", "sph", "description", "render"});
  root.string("description", "");  // a string, as in the Huygens scene
  const JsonIn s = root.object("sph");
  s.reject_renamed({{"viscosity_m2ps", "viscosity_m2s"}});
  s.allow_only({"method", "spacing_m", "support_factor", "rest_density_kgpm3", "viscosity_m2s", "artificial_viscosity",
                "impact_alpha", "impact_beta", "wall_alpha", "sound_speed_mps", "gravity_mps2", "container_m", "fluid",
                "obstacles", "boundary", "time", "surface"});
  // walls and obstacles are boundary particles (the mirror images and the position clamp are gone)
  s.string("boundary", "particles", {"particles"});
  SphScene out;
  SphParams& p = out.params;
  // the pressure solver: an unknown name is a SceneError at $.sph.method listing both
  p.method = s.string("method", "wcsph", {"wcsph", "dfsph"}) == "dfsph" ? SphMethod::dfsph : SphMethod::wcsph;
  parse_fluid_params(s, p);
  parse_fluid_blocks(s, p);
  check_sound_speed(s, p);
  for (const auto& o : s.array("obstacles")) {
    p.obstacles.push_back(parse_obstacle(o, scene));
    check_in_container(o, p.obstacles.back(), p.container_m);
  }
  parse_time(s, p);
  const double nb = boundary_estimate(p);
  if (nb > 2e7)
    s.fail(p.obstacles.empty() ? "container_m" : "obstacles",
           "the walls and obstacles would take about " + std::to_string(long(nb)) +
               " boundary particles; more than 2e7 is refused (memory)");
  out.surface = parse_surface(s, p);
  out.render = parse_render_request(root);
  require_memory(sph_memory(out));
  return out;
}

MemoryEstimate sph_memory(const SphScene& scene) {
  const SphParams& p = scene.params;
  double particles = 0;  // the lattice fill of every fluid block, as parse_fluid_blocks counts it
  for (const auto& b : p.fluid)
    particles += double(b.max_m[0] - b.min_m[0]) * (b.max_m[1] - b.min_m[1]) * (b.max_m[2] - b.min_m[2]) /
                 (double(p.spacing_m) * p.spacing_m * p.spacing_m);
  const double h = p.support(), cells = std::ceil(p.container_m[0] / h) * std::ceil(p.container_m[1] / h) *
                                        std::ceil(p.container_m[2] / h);
  const double columns =
      std::ceil(p.container_m[0] / scene.surface.cell_m + 1) * std::ceil(p.container_m[1] / scene.surface.cell_m + 1);
  MemoryEstimate m;
  m.size_key = "$.sph.spacing_m";
  // 22 float arrays per particle (system.hpp), the grid's cell and order per particle, a dump's
  // (n, 3) positions and velocities, (n) densities and pressures; the grid's two cell arrays; the
  // heightfield's columns (height, normals) (DFSPH: 17 more, system.hpp)
  const double arrays = p.method == SphMethod::dfsph ? 39 : 22;
  m.add("particles", static_cast<std::uint64_t>(particles * (arrays * 4 + 2 * 4 + 8 * 4)),
        "$.sph.fluid (its blocks' volume / $.sph.spacing_m^3)");
  m.add("neighbour grid", static_cast<std::uint64_t>(cells * 2 * 4), "$.sph.container_m / $.sph.spacing_m");
  m.add("heightfield", static_cast<std::uint64_t>(columns * 4 * 4), "$.sph.container_m / $.sph.surface.cell_m");
  // 9 float arrays per boundary particle (system.hpp) and the 7 of its sample
  m.add("boundary particles", static_cast<std::uint64_t>(boundary_estimate(p) * 16 * 4),
        "$.sph.container_m and $.sph.obstacles / $.sph.spacing_m");
  return m;
}

std::unique_ptr<Solver> make_sph_solver(const SphScene& scene) { return std::make_unique<SphSolver>(scene); }

std::unique_ptr<Solver> make_sph_solver(const Scene& scene, const RunOptions&) {
  SphScene sc = parse_sph_scene(scene);
  try {
    return make_sph_solver(sc);
  } catch (const std::invalid_argument& e) {
    throw SceneError("$.sph", e.what());
  }
}

SolverEntry sph_solver_entry() {
  SolverEntry e;
  e.name = "sph";
  e.summary = "3D SPH (WCSPH or DFSPH) with boundary particles and a heightfield surface (paper 000)";
  e.make = [](const Scene& s, const RunOptions& o) { return make_sph_solver(s, o); };
  // not distributed: one process holds it all, whatever the ranks (docs/scale.md)
  e.sizing = [](const Scene&) { return SceneSizing{"sph", "", 1 << 16, false}; };
  e.rank_memory = [](const Scene& scene) -> std::function<MemoryEstimate(int)> {
    const MemoryCheckOff sizing_only;
    const MemoryEstimate m = sph_memory(parse_sph_scene(scene));
    return [m](int) { return m; };
  };
  e.bench_scene = std::string(shipped_scene_text("pool.json"));
  e.bench_steps = 200;
  return e;
}

}  // namespace huygens
