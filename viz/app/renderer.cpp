#include "renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>

#include "caustics_stage.hpp"
#include "plan_pass.hpp"

namespace huygens {

namespace {

// CPU time of this process, all its threads (llvmpipe's rasteriser threads included) (unit: ms).
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

WaterRenderer::WaterRenderer(const GridPlacement& grid, double ground_z, int subsample)
    : grid_(grid),
      ground_z_(ground_z),
      subsample_(std::max(1, subsample)),
      eta_(grid.rows * grid.cols, 0.0f),
      surface_((gl::check("before WaterRenderer"), grid), ground_z, subsample_),
      ground_(grid, ground_z, surface_.layout()),
      flat_light_tex_(1, 1, GL_R8),
      caustics_(make_caustics_stage(grid, ground_z)) {
  const std::uint8_t one = 255;
  flat_light_tex_.upload(&one, GL_RED, GL_UNSIGNED_BYTE);
  gl::check("WaterRenderer");
}

WaterRenderer::~WaterRenderer() {
  glUseProgram(0);  // a deleted program must not stay current (others restore "the previous program")
  caustics_.reset();
  if (GLenum e = glGetError(); e != GL_NO_ERROR) std::fprintf(stderr, "~WaterRenderer: GL error 0x%04X\n", e);
}

void WaterRenderer::set_heights(std::span<const float> eta) {
  const auto t0 = std::chrono::steady_clock::now();
  const float off = offset_;
  std::transform(eta.begin(), eta.end(), eta_.begin(), [off](float v) { return v - off; });
  footprints_.apply(eta_, grid_.dx);
  surface_.prepare(eta_);
  times.prepare = elapsed_ms(t0);
}

void WaterRenderer::set_bed(std::span<const float> bed) {
  std::vector<float> z(bed.begin(), bed.end());
  for (float& b : z) b -= offset_;
  ground_.set_bed(z);
}

void WaterRenderer::set_obstacles(std::span<const RenderObstacle> obstacles) {
  footprints_.build(grid_, obstacles, offset_);
  solids_.set_obstacles(obstacles, solids_frame());
  prisms_ = prisms(obstacles, solids_frame());
  traced_.set_prisms(prisms_);
  mesh_objects_.clear();
  for (const RenderObstacle& o : obstacles) {
    if (o.kind != RenderObstacle::Kind::mesh) continue;
    EyeObject e;
    append_mesh_solids(std::span<const RenderObstacle>(&o, 1), solids_frame(), e.tri);
    e.lo = glm::dvec3(o.min_m[0], o.min_m[1], o.min_m[2] - offset_);
    e.hi = glm::dvec3(o.max_m[0], o.max_m[1], o.max_m[2] - offset_);
    mesh_objects_.push_back(std::move(e));
  }
}

ShadingScene WaterRenderer::shading_scene(const RenderSettings& s) const {
  ShadingScene scene;
  scene.grid = grid_;
  scene.ground_z = ground_z_;
  scene.tile_m = ground_.tile_m();
  if (s.caustics && caustics_ && caustics_->available())
    scene.caustics =
        ShadingScene::Caustics{glm::vec2(caustics_->origin()), glm::vec2(caustics_->extent()), caustics_->scale()};
  scene.far_sea = sky_.far_sea(s);
  scene.solids = &traced_;
  scene.eye_maps = eye_maps_.get();
  return scene;
}

// The frame's uploads: view-dependent coefficients, the floor's pattern, the sea's slopes, the heights.
void WaterRenderer::upload_frame(const OrbitCamera& camera, const RenderSettings& s) {
  ground_.update_pattern(s);
  sky_.update(s);
  surface_.upload(camera, s.index);
}

// The state other passes may have changed (the caustics pass blends, masks and uses its own
// viewport), and a cleared target.
void WaterRenderer::reset_scene_state() {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

void WaterRenderer::render(const OrbitCamera& camera, const RenderSettings& s, const RenderTarget& target) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  double c0 = process_cpu_ms();
  auto lap = [&](double& slot, double& cpu_slot) {
    if (!times.enabled) return;
    glFinish();
    slot = elapsed_ms(t0);
    cpu_slot = process_cpu_ms() - c0;
    t0 = clock::now();
    c0 = process_cpu_ms();
  };
  if (times.enabled) glFinish(), t0 = clock::now(), c0 = process_cpu_ms();

  upload_frame(camera, s);
  lap(times.upload, times.cpu.upload);
  // the caustics into their texture (lights the ground; flat light when off), then what the lit
  // programs read of them (the pass sizes its texture on its first run)
  if (s.caustics && caustics_ && caustics_->available()) caustics_->run(eta_, ships_, s);
  lap(times.caustics, times.cpu.caustics);
  // the hulls afloat on this frame's heights (float_ship): drawn, and met by the surface's rays
  afloat_.assign(ships_.begin(), ships_.end());
  for (ShipPose& sp : afloat_) float_ship(grid_, eta_, sp);
  traced_.set_hulls(s.draw_ship ? std::span<const ShipPose>(afloat_) : std::span<const ShipPose>());
  if (s.solid_optics == SolidOptics::virtual_eye) build_eye_maps(camera, s);
  const ShadingScene scene = shading_scene(s);

  const double aspect = static_cast<double>(target.width()) / target.height();
  const FrameContext f{camera, s, glm::mat4(camera.projection(aspect) * camera.view())};
  target.bind();
  reset_scene_state();
  ground_.bind_pattern();
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, scene.caustics ? caustics_->texture() : flat_light_tex_.id());
  if (s.draw_water) surface_.draw(f, scene, ground_.bed());
  if (s.draw_water && !s.deep_water) surface_.draw_sides(f, flat_);
  lap(times.surface, times.cpu.surface);
  solids_.draw(f, flat_, afloat_, solids_frame());
  lap(times.ship, times.cpu.ship);
  // the ground seen directly, drawn after the water and solids so the depth test skips what they
  // cover, then the sky where nothing was drawn
  ground_.draw(f, scene);
  sky_.draw(f, scene);
  lap(times.ground, times.cpu.ground);
  target.resolve_scene();
  tone_.run(s, target);
  lap(times.tonemap, times.cpu.tonemap);

  glBindVertexArray(0);
  glUseProgram(0);
  glActiveTexture(GL_TEXTURE0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("WaterRenderer::render");
}

namespace {

// The mean height of the visible heights `eta` over the object's footprint grown by a quarter on
// each side: paper 000's plane round the object (its normal kept vertical); 0 off the grid.
double plane_round(const GridPlacement& g, std::span<const float> eta, const EyeObject& o) {
  const glm::dvec2 pad = 0.25 * (glm::dvec2(o.hi) - glm::dvec2(o.lo));
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < g.rows; ++i) {
    if (g.y(i) < o.lo.y - pad.y || g.y(i) > o.hi.y + pad.y) continue;
    for (std::size_t j = 0; j < g.cols; ++j)
      if (g.x(j) >= o.lo.x - pad.x && g.x(j) <= o.hi.x + pad.x) sum += eta[i * g.cols + j], ++n;
  }
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

}  // namespace

// Paper 000's objects this frame (prisms, meshes, hulls afloat), each with the plane round it, drawn
// into their maps from their virtual eyes.
void WaterRenderer::build_eye_maps(const OrbitCamera& camera, const RenderSettings& s) {
  if (!eye_maps_) eye_maps_ = std::make_unique<VirtualEyeMaps>();
  eye_objects_.clear();
  for (const Prism& p : prisms_) {
    EyeObject e;
    append_prism_solids(std::span<const Prism>(&p, 1), e.tri);
    const glm::dvec2 r = p.cylinder ? glm::dvec2(p.hi.x) : glm::dvec2(0.0);
    e.lo = glm::dvec3(p.cylinder ? p.lo - r : p.lo, p.z0), e.hi = glm::dvec3(p.cylinder ? p.lo + r : p.hi, p.z1);
    eye_objects_.push_back(std::move(e));
  }
  eye_objects_.insert(eye_objects_.end(), mesh_objects_.begin(), mesh_objects_.end());
  for (const ShipPose& sp : s.draw_ship ? std::span<const ShipPose>(afloat_) : std::span<const ShipPose>()) {
    EyeObject e;
    e.kind = 0;
    append_hull(sp, e.tri);
    e.lo = e.hi = glm::dvec3(e.tri[0], e.tri[1], e.tri[2]);
    for (std::size_t k = 0; k + 2 < e.tri.size(); k += 3)
      e.lo = glm::min(e.lo, glm::dvec3(e.tri[k], e.tri[k + 1], e.tri[k + 2])),
      e.hi = glm::max(e.hi, glm::dvec3(e.tri[k], e.tri[k + 1], e.tri[k + 2]));
    eye_objects_.push_back(std::move(e));
  }
  for (EyeObject& e : eye_objects_) e.plane = plane_round(grid_, eta_, e);
  eye_maps_->build(eye_objects_, camera.eye(), s);
}

void WaterRenderer::render_plan(std::span<const float> values, const std::string& quantity, double unit_scale,
                                const std::string& unit, bool diverging, const std::string& title,
                                const RenderTarget& target, std::optional<glm::vec3> hue) {
  const PlanRequest rq{quantity, unit, title, unit_scale, diverging, hue, plan_reserve_right};
  plan = draw_plan_view(grid_, footprints_, ships_, values, rq, target);
}

}  // namespace huygens
