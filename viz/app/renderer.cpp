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
  traced_.set_prisms(prisms(obstacles, solids_frame()));
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
  const ShadingScene scene = shading_scene(s);

  const double aspect = static_cast<double>(target.width()) / target.height();
  const FrameContext f{camera, s, glm::mat4(camera.projection(aspect) * camera.view())};
  target.bind();
  reset_scene_state();
  ground_.bind_pattern();
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, scene.caustics ? caustics_->texture() : flat_light_tex_.id());
  // the hulls afloat on this frame's heights (float_ship): drawn, and met by the surface's rays
  afloat_.assign(ships_.begin(), ships_.end());
  for (ShipPose& sp : afloat_) float_ship(grid_, eta_, sp);
  traced_.set_hulls(s.draw_ship ? std::span<const ShipPose>(afloat_) : std::span<const ShipPose>());
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

void WaterRenderer::render_plan(std::span<const float> values, const std::string& quantity, double unit_scale,
                                const std::string& unit, bool diverging, const std::string& title,
                                const RenderTarget& target, std::optional<glm::vec3> hue) {
  const PlanRequest rq{quantity, unit, title, unit_scale, diverging, hue, plan_reserve_right};
  plan = draw_plan_view(grid_, footprints_, ships_, values, rq, target);
}

}  // namespace huygens
