#include "headless.hpp"

#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "scene_view.hpp"

namespace huygens {

HeadlessResult render_headless(const HeadlessOptions& opt) {
  const Scene scene = load_scene(opt.scene_file);
  RunOptions ro;
  ro.measure_plans = false;  // FFTW_ESTIMATE: the same plan, hence the same image, every run
  std::unique_ptr<Solver> solver = make_solver(scene, ro);
  const SceneGeometry geo = scene_geometry(scene, *solver);
  WaterRenderer renderer(geo.grid, geo.ground_z, opt.subsample);
  renderer.set_height_offset(geo.height_offset);
  const OrbitCamera cam = opt.custom_camera ? opt.camera
                                            : default_camera(geo.grid.x0, geo.grid.y0, geo.grid.cols * geo.grid.dx,
                                                             geo.grid.rows * geo.grid.dx);
  RenderTarget target(opt.width, opt.height);
  const double dt_display = geo.dt / geo.display_per_step;
  HeadlessResult res;
  for (int k = 0; k < opt.frames; ++k) {
    const double t = opt.time + k * dt_display;
    while (solver->time() + geo.dt <= t + 1e-9 * geo.dt) solver->step();
    renderer.set_heights(solver->height());
    renderer.set_ships(solver_ship_poses(geo, *solver));  // where the solver has them
    renderer.times.enabled = (k + 1 == opt.frames);
    renderer.render(cam, opt.settings, target);
  }
  res.image = target.read();
  res.steps = solver->steps();
  res.field_time = solver->time();
  res.times = renderer.times;
  return res;
}

}  // namespace huygens
