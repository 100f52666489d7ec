#include "headless.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "dye.hpp"
#include "foam.hpp"
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
  // the dye and the foam need the flow's history: every frame from t = 0, the last `frames`
  // drawn (the plan's dye and foam views, and the perspective picture of a flow, whose water
  // the dye tints and the foam covers)
  const bool dye_view = opt.plan ? opt.plan_quantity == PlanQuantity::dye : opt.settings.dye && opt.flow;
  const bool foam_view = opt.plan ? opt.plan_quantity == PlanQuantity::foam : opt.settings.foam && opt.flow;
  DyeField dye(g);
  FoamField foam(g, scene.info.bed_m);
  const bool history = dye_view || foam_view;
  const int skipped = history ? static_cast<int>(std::floor(opt.time / view.frame_dt + 1e-9)) : 0;
  const double t_first = history ? opt.time - skipped * view.frame_dt : opt.time;
  double flow_time = 0.0;
  bool has_velocity = false;
  bool shown_ahead = false;  // show(t) of this frame was already called (a history frame's overlap)
  for (int k = 0; k < skipped + opt.frames; ++k) {
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
    has_velocity = frames.velocity(velocity);
    if (history && has_velocity && frames.newest->info.time_s > flow_time) {
      const double dt = frames.newest->info.time_s - flow_time;
      if (dye_view) dye.advect(velocity, dt);
      if (foam_view) foam.step(frames.newest->eta.span(), velocity, dt);
      flow_time = frames.newest->info.time_s;
    }
    if (k < skipped) continue;                    // the dye's history: not drawn
    frames.sample(runner.display_time(), field);  // the newest frame (the clock never runs ahead of it)
    renderer.set_heights(field);
    renderer.set_sea_time(runner.display_time());
    frame_ships(view, frames, runner.display_time(), ships);  // where the solver has them
    renderer.set_ships(ships);
    if (dye_view && has_velocity) renderer.set_dye(dye.values());
    if (foam_view && has_velocity) renderer.set_foam(foam.values());
    if (!opt.custom_camera && !ships.empty() && view.follow_ship) {
      if (!camera_placed) cam = start_camera(view, aspect, &ships[0]);
      follow_ship(view, ships[0], cam);
    }
    camera_placed = true;
    renderer.times.enabled = (k + 1 == opt.frames);
    if (opt.plan)
      render_plan_view(
          renderer, view,
          PlanData{field, has_velocity ? std::span<const float>(velocity) : std::span<const float>{}, dye.values(),
                   foam.values(),
                   frames.newest->has_particles ? frames.newest->particles.span() : std::span<const float>{}},
          opt.plan_quantity, frames.newest->info.time_s, name, target);
    else
      renderer.render(cam, opt.settings, target);
    if (!opt.plan && opt.caption)
      draw_caption(perspective_caption(name, runner.display_time(), scale_text(view, opt.settings, renderer.tile_m()),
                                       opt.width, opt.height),
                   target);
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
