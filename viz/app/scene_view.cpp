#include "scene_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>

#include "huygens/common/shipped_scenes.hpp"
#include "huygens/solvers/registry.hpp"
#include "looks.hpp"
#include "plot.hpp"

namespace huygens {

namespace {
constexpr double kSunDeg = std::numbers::pi / 180.0;
}

ShipPose SceneView::ship(std::size_t i, const ShipState& s) const {
  ShipPose p;
  if (i < hulls.size()) {
    p.length = hulls[i].length_m;
    p.beam = hulls[i].beam_m;
    p.draft = hulls[i].draft_m;
  }
  p.x = s.x_m;
  p.y = s.y_m;
  p.heading = s.heading_rad;
  return p;
}

SceneView scene_view(const RenderInfo& info) {
  SceneView v;
  v.grid.rows = info.grid.rows;
  v.grid.cols = info.grid.cols;
  v.grid.dx = info.grid.dx_m;
  v.grid.x0 = info.grid.x0_m;
  v.grid.y0 = info.grid.y0_m;
  v.ground_z = info.depth_m && *info.depth_m > 0.0 ? -*info.depth_m : -SceneView::kDeepGround;
  v.height_offset = info.rest_level_m;
  v.frame_dt = info.frame_dt_s;
  v.hulls = info.hulls;
  v.obstacles = info.obstacles;
  v.particle_box = info.particle_box_m;
  if (!info.bed_m.empty() &&
      std::any_of(info.bed_m.begin(), info.bed_m.end(), [&](float b) { return b != info.bed_m[0]; }))
    v.bed = info.bed_m;
  v.particle_spacing = info.particle_spacing_m;
  v.ambient_sea = info.ambient_sea;
  const RenderRequest& rq = info.request;
  v.look = rq.look.value_or(info.default_look);  // the scene's, else the solver's
  const double W = v.grid.cols * v.grid.dx, H = v.grid.rows * v.grid.dx;
  v.slab = std::max(W, H) > (v.particle_box ? look_unit(v.look).tank_slab_ratio : 8.0) * std::min(W, H);
  v.plan_view = rq.plan_view.value_or(false);
  v.plan_depth = info.rest_level_m != 0.0;
  v.follow_ship = !v.hulls.empty() && rq.camera.follow_ship.value_or(true);
  v.camera_request = rq.camera;
  return v;
}

void place_scene(WaterRenderer& renderer, const SceneView& view) {
  renderer.set_height_offset(view.height_offset);
  renderer.set_bed(view.bed);
  renderer.set_obstacles(view.obstacles);
  if (view.slab && view.particle_box) renderer.set_tank(*view.particle_box);
  if (look_unit(view.look).open_sea && view.ambient_sea) renderer.set_ambient_sea(*view.ambient_sea);
}

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
// How far the target sits behind a followed ship, in camera distances: the wake behind it
// fills the view's middle.
constexpr double kFollowBack = 0.35;
}  // namespace

OrbitCamera start_camera(const SceneView& view, double aspect, const ShipPose* ship) {
  const GridPlacement& g = view.grid;
  const double W = g.cols * g.dx, H = g.rows * g.dx;
  OrbitCamera c = default_camera(g.x0, g.y0, W, H);
  // a quasi-2D slab (one side 8x the other) is seen from low, along its short side
  const bool slab = view.slab;
  c.pitch = (slab ? 8.0 : 50.0) * kDeg;
  if (slab && H > W) c.yaw = 0.0;  // the eye on the +x side looking along -x
  // the whole region in view, a 15 % margin: its four corners at the rest level within 1/1.15 of
  // the image's half sizes (in perspective its near edge is wider and lower on screen than the
  // far one: the far-near extent foreshortened by sin(pitch) alone cut the near sixth of a square
  // region off at 16:9); a slab, seen from low along its short side: its long side's width
  const double t = std::tan(0.5 * c.fov_y);
  const double across = c.yaw == 0.0 ? H : W, along = c.yaw == 0.0 ? W : H;
  const std::array<glm::dvec3, 4> corners{glm::dvec3(g.x(0), g.y(0), 0.0), glm::dvec3(g.x(g.cols - 1), g.y(0), 0.0),
                                          glm::dvec3(g.x(0), g.y(g.rows - 1), 0.0),
                                          glm::dvec3(g.x(g.cols - 1), g.y(g.rows - 1), 0.0)};
  c.distance = slab ? 1.15 * across / (2.0 * t * aspect) : frame_distance(c, corners, aspect, 1.0 / 1.15);
  if (slab && view.particle_box) {
    // a particle solver's slab: its container's side, floor to lid, looked at across the slab
    // from 10 degrees up (20 for a tank over a fifth as wide as long, so its surface shows too),
    // so the water column, its fall and the surge fill the picture
    const double floor = view.ground_z, lid = (*view.particle_box)[2] - view.height_offset;
    c.pitch = (across > 5.0 * along ? 10.0 : 20.0) * kDeg;
    c.target.z = 0.5 * (floor + lid);
    // the near side (half the thin side nearer than the target) framed, floor to lid and end to end
    c.distance = 1.1 * std::max(across / (2.0 * t * aspect), (lid - floor) / (2.0 * t)) + 0.5 * along;
  }
  if (view.follow_ship && ship) {
    // the ship and its wake from the side: a Kelvin wake (half-angle 19.5 deg) over about
    // 8 hull lengths behind the ship; at sea from low, 15 deg up, the sea out to the horizon in
    // the picture's top fifth and the sun's glitter running towards the viewer
    const bool sea = look_unit(view.look).open_sea;
    c.pitch = (sea ? 15.0 : 55.0) * kDeg;
    c.distance = std::min(c.distance, (sea ? 7.0 : 11.0) * ship->length);
    follow_ship(view, *ship, c);
  }
  const CameraRequest& r = view.camera_request;
  if (r.target_m) c.target = glm::dvec3((*r.target_m)[0], (*r.target_m)[1], (*r.target_m)[2]);
  if (r.distance_m) c.distance = *r.distance_m;
  if (r.yaw_deg) c.yaw = *r.yaw_deg * kDeg;
  if (r.pitch_deg) c.pitch = *r.pitch_deg * kDeg;
  c.z_near = std::max(1e-3, 0.005 * c.distance);
  c.z_far = 20.0 * c.distance + 4.0 * std::max(W, H);
  return c;
}

void follow_ship(const SceneView& view, const ShipPose& ship, OrbitCamera& camera) {
  // the target behind the ship, kept at least the view's half height at the target,
  // d tan(fov_y / 2), inside the simulated water (at most its middle): near an edge the view
  // stays on the waves rather than on the flat water beyond, and the ship, within that margin
  // of the target, stays in view
  const double back = kFollowBack * camera.distance;
  const GridPlacement& g = view.grid;
  const double half = camera.distance * std::tan(0.5 * camera.fov_y);
  auto keep = [&](double v, double lo, double hi) {
    const double m = std::min(half, 0.5 * (hi - lo));
    return std::clamp(v, lo + m, hi - m);
  };
  const double x = keep(ship.x - back * std::cos(ship.heading), g.x(0), g.x(g.cols - 1));
  const double y = keep(ship.y - back * std::sin(ship.heading), g.y(0), g.y(g.rows - 1));
  camera.target = glm::dvec3(x, y, 0.0);
}

RenderSettings look_settings(const SceneView& view, const RenderRequest& request, const OrbitCamera& camera) {
  RenderSettings s;
  // the sun where the camera is (azimuth and elevation): the refracted view ray and the sun's
  // refracted ray then coincide at the centre of the view, so the caustics a wave makes are
  // seen through that wave (paper 004 sec. 5 draws them along the sun, D tan(theta_t) away)
  // (an eye under the water: the sun mirrored above the surface, the light still comes from above)
  glm::dvec3 to_eye = -camera.forward();
  to_eye.z = std::abs(to_eye.z);
  s.sun_dir = glm::vec3(static_cast<float>(to_eye.x), static_cast<float>(to_eye.y), static_cast<float>(to_eye.z));
  look_unit(view.look).settings(view, camera, s);
  apply_render_request(request, s);
  return s;
}

std::string scale_text(const SceneView& view, const RenderSettings& s, double tile_m) {
  char b[128];
  const int n =
      std::snprintf(b, sizeof b, "region %.3g x %.3g m", view.grid.cols * view.grid.dx, view.grid.rows * view.grid.dx);
  if (!s.deep_water && s.ground == GroundPattern::tiles)
    std::snprintf(b + n, sizeof b - static_cast<std::size_t>(n), ", tiles %g m", tile_m);
  return b;
}

void frame_ships(const SceneView& view, const FramePair& frames, double t, std::vector<ShipPose>& out) {
  out.clear();
  ShipState s;
  for (std::size_t i = 0; i < view.hulls.size() && frames && frames.ship(i, t, s); ++i) out.push_back(view.ship(i, s));
}

void apply_render_request(const RenderRequest& request, RenderSettings& s) {
  if (request.caustics) s.caustics = *request.caustics;
  if (request.foam) s.foam = *request.foam;
  if (request.blur) {
    s.blur = *request.blur != BlurMode::none;
    s.blur_float = *request.blur == BlurMode::float_target;
  }
  if (request.caustics_mode) {
    s.caustics_mode = *request.caustics_mode == CausticsModeRequest::mip_paper     ? CausticsMode::mip_paper
                      : *request.caustics_mode == CausticsModeRequest::mip_float   ? CausticsMode::mip_float
                      : *request.caustics_mode == CausticsModeRequest::explicit_u8 ? CausticsMode::explicit_u8
                      : *request.caustics_mode == CausticsModeRequest::simple      ? CausticsMode::simple
                                                                                   : CausticsMode::conserving;
  }
  if (request.sun_elevation_deg || request.sun_azimuth_deg) {
    const glm::vec3 d = glm::normalize(s.sun_dir);
    const double el = request.sun_elevation_deg ? *request.sun_elevation_deg * kSunDeg : std::asin(d.z);
    const double az = request.sun_azimuth_deg ? *request.sun_azimuth_deg * kSunDeg : std::atan2(d.y, d.x);
    s.sun_dir = glm::vec3(static_cast<float>(std::cos(el) * std::cos(az)),
                          static_cast<float>(std::cos(el) * std::sin(az)), static_cast<float>(std::sin(el)));
  }
}

ViewSetup view_setup(const ViewerSolver& vs, double aspect) {
  ViewSetup v;
  v.view = scene_view(vs.info);
  std::array<ShipState, kMaxFrameShips> states{};
  std::optional<ShipPose> ship;
  if (!v.view.hulls.empty() && vs.solver->ship_poses(states) > 0) ship = v.view.ship(0, states[0]);
  v.camera = start_camera(v.view, aspect, ship ? &*ship : nullptr);
  v.settings = look_settings(v.view, vs.info.request, v.camera);
  return v;
}

void render_plan_view(WaterRenderer& renderer, const SceneView& view, const PlanData& data, PlanQuantity quantity,
                      double t_s, const std::string& name, const RenderTarget& target) {
  const std::span<const float> field = data.field, velocity = data.velocity, dye = data.dye;
  std::string base = name;
  if (const auto slash = base.find_last_of('/'); slash != std::string::npos) base = base.substr(slash + 1);
  char title[160];
  std::snprintf(title, sizeof title, "%s   t = %.2f s", base.c_str(), t_s);
  if (quantity == PlanQuantity::particles && view.particle_box && !data.particles.empty()) {
    renderer.plan = render_particles(data.particles, *view.particle_box, 0.5 * view.particle_spacing, view.obstacles,
                                     title, renderer.plan_reserve_right, target);
    return;
  }
  // over terrain, dry land (thinner than the perspective's kDryDepth) is NaN, drawn sand, in every
  // quantity: a dry cell's speed is a thin film's noise, and no water carries its dye or foam
  const bool terrain = view.plan_depth && view.bed.size() == field.size();
  const std::string label = std::string(title) + (terrain ? "   sand: dry land" : "");
  auto dry = [&](std::size_t k) { return terrain && field[k] - view.bed[k] < WaterRenderer::kDryDepth; };
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  std::vector<float> v;
  if (quantity == PlanQuantity::speed && velocity.size() == 2 * field.size()) {
    v.resize(field.size());
    double range = 0.0;
    for (std::size_t k = 0; k < v.size(); ++k) {
      v[k] = dry(k) ? kNaN : std::hypot(velocity[2 * k], velocity[2 * k + 1]);
      if (std::isfinite(v[k])) range = std::max(range, static_cast<double>(v[k]));
    }
    const bool cm = range < 2.0;
    renderer.render_plan(v, "speed", cm ? 100.0 : 1.0, cm ? "cm/s" : "m/s", false, label, target);
    return;
  }
  const bool carried = quantity == PlanQuantity::dye || quantity == PlanQuantity::foam;
  const std::span<const float> tracer = quantity == PlanQuantity::dye ? dye : data.foam;
  if (carried && tracer.size() == field.size()) {
    v.assign(tracer.begin(), tracer.end());
    for (std::size_t k = 0; k < v.size(); ++k)
      if (dry(k)) v[k] = kNaN;
    // the dye from white to the colour the perspective view tints it with, the foam on viridis
    const std::optional<glm::vec3> hue =
        quantity == PlanQuantity::dye ? std::optional<glm::vec3>(RenderSettings{}.dye_colour) : std::nullopt;
    renderer.render_plan(v, quantity == PlanQuantity::dye ? "dye" : "foam", 1.0, "1", false, label, target, hue);
    return;
  }
  // a height about rest (m); LBM/SPH: the depth above the bed (the height itself on a flat bed,
  // the surface minus the bed over terrain)
  v.assign(field.begin(), field.end());
  double range = 0.0;
  if (!view.plan_depth)
    for (float& x : v) x -= static_cast<float>(view.height_offset);
  else if (terrain)
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = dry(k) ? kNaN : v[k] - view.bed[k];
  for (float x : v)
    if (std::isfinite(x)) range = std::max(range, static_cast<double>(std::abs(x)));
  const double scale = range < 0.02 ? 1000.0 : range < 2.0 ? 100.0 : 1.0;
  const std::string unit = scale == 1000.0 ? "mm" : scale == 100.0 ? "cm" : "m";
  renderer.render_plan(v, view.plan_depth ? "depth" : "height", scale, unit, !view.plan_depth, label, target);
}

ViewerSolver open_viewer_solver(const std::string& arg, const RunOptions& options) {
  ViewerSolver v;
  v.scene = open_scene(arg, &v.name);
  v.options = options;
  v.solver = make_solver(v.scene, options);
  v.info = v.solver->render_info();
  return v;
}

}  // namespace huygens
