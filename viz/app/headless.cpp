#include "headless.hpp"

#include <stdexcept>
#include <vector>

#include "huygens/pipeline/runner.hpp"

namespace huygens {

HeadlessResult render_headless(ViewerSolver scene, const HeadlessOptions& opt) {
  const SceneView view = scene_view(scene.info);
  WaterRenderer renderer(view.grid, view.ground_z, opt.subsample);
  renderer.set_height_offset(view.height_offset);
  renderer.set_obstacles(view.obstacles);
  const GridPlacement& g = view.grid;
  const double aspect = static_cast<double>(opt.width) / opt.height;
  const std::string name = scene.name;
  OrbitCamera cam = opt.custom_camera ? opt.camera : start_camera(view, aspect, nullptr);
  bool camera_placed = opt.custom_camera;
  RenderTarget target(opt.width, opt.height);

  // the window's path with the manual clock: the runner publishes every step at or before the
  // display time into the frame ring, and the frame drawn is sampled from the ring
  RunnerParams rp;
  rp.manual_clock = true;
  Runner runner(std::move(scene.solver), rp);
  runner.start();
  std::vector<float> field(g.rows * g.cols);
  std::vector<ShipPose> ships;
  HeadlessResult res;
  for (int k = 0; k < opt.frames; ++k) {
    const double t = opt.time + k * view.frame_dt;
    runner.show(t);
    if (!runner.wait_shown()) {
      runner.stop();
      runner.rethrow_if_failed();
      throw std::runtime_error("headless: the simulation ended before display time " + std::to_string(t) + " s");
    }
    const FramePair frames = runner.frames();
    frames.sample(runner.display_time(), field);  // the newest frame (the clock never runs ahead of it)
    renderer.set_heights(field);
    frame_ships(view, frames, runner.display_time(), ships);  // where the solver has them
    renderer.set_ships(ships);
    if (!opt.custom_camera && !ships.empty() && view.follow_ship) {
      if (!camera_placed) cam = start_camera(view, aspect, &ships[0]);
      follow_ship(view, ships[0], cam);
    }
    camera_placed = true;
    renderer.times.enabled = (k + 1 == opt.frames);
    if (opt.plan)
      render_plan_view(renderer, view, field, frames.newest->info.time_s, name, target);
    else
      renderer.render(cam, opt.settings, target);
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
