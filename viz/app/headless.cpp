#include "headless.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "dye.hpp"
#include "foam.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/pipeline/runner.hpp"
#include "plot.hpp"

namespace huygens {
namespace {

// The perspective picture's caption: the scene's file name (no folder of this machine), the
// display time and the picture's scale (scale_text); the first of these that fits the width.
std::string perspective_caption(const std::string& name, double t, const std::string& scale, int width, int height) {
  char b[32];
  std::snprintf(b, sizeof b, "t = %.2f s", t);
  const std::string time = b;
  const std::string file = std::filesystem::path(name).filename().string();
  for (const std::string& c : {file + "   " + time + "   " + scale, time + "   " + scale, time})
    if (caption_width(c, height) <= width) return c;
  return "";
}

// The dye and the foam need the flow's history: every frame from t = 0 (the plan's dye and foam
// views, and the perspective picture of a flow, whose water the dye tints and the foam covers).
struct FlowHistory {
  bool dye_view, foam_view;
  DyeField dye;
  FoamField foam;
  double time = 0.0;  // of the newest frame advected through (unit: s)

  FlowHistory(const HeadlessOptions& opt, const GridPlacement& g, std::span<const float> bed)
      : dye_view(opt.plan ? opt.plan_quantity == PlanQuantity::dye : opt.settings.dye && opt.flow),
        foam_view(opt.plan ? opt.plan_quantity == PlanQuantity::foam : opt.settings.foam && opt.flow),
        dye(g),
        foam(g, bed) {}
  bool needed() const { return dye_view || foam_view; }
  void advance(const FramePair& frames, std::span<const float> velocity) {
    if (!needed() || !(frames.newest->info.time_s > time)) return;  // (a NaN time advances nothing)
    const double dt = frames.newest->info.time_s - time;
    if (dye_view) dye.advect(velocity, dt);
    if (foam_view) foam.step(frames.newest->eta.span(), velocity, dt);
    time = frames.newest->info.time_s;
  }
};

// Draws one frame of the pair into `target`: the plan view, or the perspective picture and its
// caption.
void draw_frame(WaterRenderer& renderer, const SceneView& view, const HeadlessOptions& opt, const OrbitCamera& cam,
                const FramePair& frames, const PlanData& data, double display_time, const std::string& name,
                RenderTarget& target) {
  if (opt.plan) {
    render_plan_view(renderer, view, data, opt.plan_quantity, frames.newest->info.time_s, name, target);
    return;
  }
  renderer.render(cam, opt.settings, target);
  if (opt.caption)
    draw_caption(perspective_caption(name, display_time, scale_text(view, opt.settings, renderer.tile_m()), opt.width,
                                     opt.height),
                 target);
}

}  // namespace

HeadlessResult render_headless(ViewerSolver scene, const HeadlessOptions& opt) {
  const SceneView view = scene_view(scene.info);
  WaterRenderer renderer(view.grid, view.ground_z, opt.subsample);
  place_scene(renderer, view);
  const GridPlacement& g = view.grid;
  const double aspect = static_cast<double>(opt.width) / opt.height;
  const std::string name = scene.name;
  OrbitCamera cam = opt.custom_camera ? opt.camera : start_camera(view, aspect, nullptr);
  bool camera_placed = opt.custom_camera;
  RenderTarget target(opt.width, opt.height, opt.samples);

  // the window's path with the manual clock: the runner computes every step at or before the
  // display time and publishes the last two into the frame ring (the pair the window would hold),
  // and the frame drawn is sampled from the ring
  RunnerParams rp;
  rp.manual_clock = true;
  Runner runner(std::move(scene.solver), rp);
  runner.start();
  std::vector<float> field(g.rows * g.cols), velocity(2 * g.rows * g.cols);
  std::vector<ShipPose> ships;
  HeadlessResult res;
  FlowHistory flow(opt, g, scene.info.bed_m);  // advanced through every frame, the last `frames` drawn
  const int skipped = flow.needed() ? static_cast<int>(std::floor(opt.time / view.frame_dt + 1e-9)) : 0;
  const double t_first = flow.needed() ? opt.time - skipped * view.frame_dt : opt.time;
  bool shown_ahead = false;  // show(t) of this frame was already called (a history frame's overlap)
  for (int k = 0; k < skipped + opt.frames; ++k) {
    // SIGINT/SIGTERM: the frame being drawn is abandoned and no image is written (main.cpp)
    stop_request::throw_if_requested(fmt("frame %d of %d abandoned; no image written", k + 1, skipped + opt.frames));
    const double t = t_first + k * view.frame_dt;
    if (!shown_ahead) runner.show(t);
    shown_ahead = false;
    if (!runner.wait_shown()) {
      runner.stop();
      runner.rethrow_if_failed();
      throw std::runtime_error("headless: the simulation ended before display time " + std::to_string(t) + " s");
    }
    const FramePair frames = runner.frames();
    if (k < skipped) {
      // a history frame is not drawn, and the pair it holds stays valid until the next frames():
      // the simulation computes the next frame while the dye and the foam advance through this one
      runner.show(t_first + (k + 1) * view.frame_dt);
      shown_ahead = true;
    }
    const bool has_velocity = frames.velocity(velocity);
    if (has_velocity) flow.advance(frames, velocity);
    if (k < skipped) continue;                    // the dye's history: not drawn
    frames.sample(runner.display_time(), field);  // the newest frame (the clock never runs ahead of it)
    renderer.set_heights(field);
    renderer.set_sea_time(runner.display_time());
    frame_ships(view, frames, runner.display_time(), ships);  // where the solver has them
    renderer.set_ships(ships);
    if (flow.dye_view && has_velocity) renderer.set_dye(flow.dye.values());
    if (flow.foam_view && has_velocity) renderer.set_foam(flow.foam.values());
    if (!opt.custom_camera && !ships.empty() && view.follow_ship) {
      if (!camera_placed) cam = start_camera(view, aspect, &ships[0]);
      follow_ship(view, ships[0], cam);
    }
    camera_placed = true;
    renderer.times.enabled = (k + 1 == opt.frames);
    const PlanData data{field, has_velocity ? std::span<const float>(velocity) : std::span<const float>{},
                        flow.dye.values(), flow.foam.values(),
                        frames.newest->has_particles ? frames.newest->particles.span() : std::span<const float>{}};
    draw_frame(renderer, view, opt, cam, frames, data, runner.display_time(), name, target);
    res.steps = frames.newest->info.step;
    res.field_time = frames.newest->info.time_s;
  }
  runner.stop();
  runner.rethrow_if_failed();
  res.image = target.read();
  res.times = renderer.times;
  return res;
}

}  // namespace huygens
