// huygens-viz: the visualizer (docs/design.md section 5, paper 004 section 4).
//   huygens-viz [SCENE]                                   interactive window (GLFW, GL 3.3 core)
//   huygens-viz SCENE --headless --frames N [--time T] --screenshot FILE.png
//   huygens-viz [SCENE] --benchmark                       per-pass render times (headless)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>

#include "app.hpp"
#include "gl.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "scene_view.hpp"

#ifndef HUYGENS_SCENES_DIR
#define HUYGENS_SCENES_DIR "scenes"
#endif

namespace {

void usage(std::FILE* f) {
  std::fprintf(f,
               "usage: huygens-viz [SCENE] [options]\n"
               "  SCENE                 scene JSON (default: %s/default.json)\n"
               "  --headless            render offscreen with no display server (EGL surfaceless)\n"
               "  --frames N            frames to render in --headless mode (default 1)\n"
               "  --time T              display time of the first headless frame, s (default 0)\n"
               "  --screenshot FILE.png where the headless image (or the S key's image) goes\n"
               "  --size WxH            image / window size in pixels (default 1280x720; headless 256x256)\n"
               "  --subsample F         surface mesh subsampling factor (default 4)\n"
               "  --exact               exact per-pixel Snell refraction (default: linearised coordinates)\n"
               "  --schlick             Schlick Fresnel instead of the paper's clamp(1 - 2.5 n.v)\n"
               "  --no-caustics         do not light the ground with caustics\n"
               "  --benchmark           print per-pass render times at 1280x720 and 640x360 (headless)\n"
               "  --auto-frames N       window: after N frames press S, then quit (smoke test)\n"
               "  --help                this text\n"
               "Keys (window): space pause, R reset, F1 hide panel, S screenshot, E exact/linearised,\n"
               "  F Fresnel model, Esc quit. Mouse: left click drops a stone, left drag on a ship moves it,\n"
               "  right drag orbits, middle drag (or shift+right) pans, wheel zooms.\n",
               HUYGENS_SCENES_DIR);
}

bool parse_size(const char* s, int& w, int& h) { return std::sscanf(s, "%dx%d", &w, &h) == 2 && w > 0 && h > 0; }

int run_benchmark(const std::string& scene_file, huygens::RenderSettings settings, int subsample);

}  // namespace

int main(int argc, char** argv) {
  using namespace huygens;
  std::string scene = std::string(HUYGENS_SCENES_DIR) + "/default.json";
  std::string screenshot;
  bool headless = false, benchmark = false, size_given = false;
  int frames = 1, w = 1280, h = 720, subsample = 4, auto_frames = 0;
  double time = 0.0;
  RenderSettings settings;
  bool exact = false, schlick = false, no_caustics = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> const char* {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++i];
      };
      if (a == "--help" || a == "-h") {
        usage(stdout);
        return 0;
      } else if (a == "--headless") {
        headless = true;
      } else if (a == "--frames") {
        frames = std::stoi(next());
        if (frames < 1) throw std::invalid_argument("--frames must be >= 1");
      } else if (a == "--time") {
        time = std::stod(next());
        if (time < 0) throw std::invalid_argument("--time must be >= 0");
      } else if (a == "--screenshot") {
        screenshot = next();
      } else if (a == "--size") {
        if (!parse_size(next(), w, h)) throw std::invalid_argument("--size takes WxH, e.g. 640x360");
        size_given = true;
      } else if (a == "--subsample") {
        subsample = std::stoi(next());
        if (subsample < 1 || subsample > 64) throw std::invalid_argument("--subsample must be in [1, 64]");
      } else if (a == "--exact") {
        exact = true;
      } else if (a == "--schlick") {
        schlick = true;
      } else if (a == "--no-caustics") {
        no_caustics = true;
      } else if (a == "--benchmark") {
        benchmark = true;
      } else if (a == "--auto-frames") {
        auto_frames = std::stoi(next());
      } else if (!a.empty() && a[0] == '-') {
        throw std::invalid_argument("unknown option " + a);
      } else {
        scene = a;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "huygens-viz: %s\n", e.what());
    usage(stderr);
    return 2;
  }

  try {
    apply_scene_render_block(scene, settings);
    settings.exact_refraction = exact;
    if (schlick) settings.fresnel = FresnelModel::schlick;
    if (no_caustics) settings.caustics = false;
    if (benchmark) return run_benchmark(scene, settings, subsample);
    const bool no_display = !std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY");
    if (!headless && no_display && auto_frames == 0) {
      // no display server: render the same scene headless and say where the image is
      headless = true;
      if (frames == 1) frames = 60;
      if (screenshot.empty()) screenshot = "huygens-viz.png";
      size_given = true;  // the window's size
      std::printf("huygens-viz: no display (DISPLAY and WAYLAND_DISPLAY are unset): rendering %d frames headless\n",
                  frames);
    }
    if (headless) {
      if (screenshot.empty()) {
        std::fprintf(stderr, "huygens-viz: --headless needs --screenshot FILE.png\n");
        return 2;
      }
      gl::HeadlessContext ctx;
      HeadlessOptions opt;
      opt.scene_file = scene;
      opt.frames = frames;
      opt.time = time;
      opt.width = size_given ? w : 256;
      opt.height = size_given ? h : 256;
      opt.subsample = subsample;
      opt.settings = settings;
      const HeadlessResult r = render_headless(opt);
      gl::write_png(screenshot, r.image);
      std::printf("huygens-viz: %d frame(s) of %s rendered headless (%s), %lld steps, field time %.4f s\n", frames,
                  scene.c_str(), ctx.renderer().c_str(), r.steps, r.field_time);
      std::printf("huygens-viz: image written to %s (%dx%d)\n", std::filesystem::absolute(screenshot).string().c_str(),
                  r.image.width, r.image.height);
      return 0;
    }
    WindowOptions wo;
    wo.scene_file = scene;
    wo.width = w;
    wo.height = h;
    wo.subsample = subsample;
    wo.settings = settings;
    wo.auto_frames = auto_frames;
    wo.screenshot = screenshot;
    return run_window(wo);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "huygens-viz: scene error: %s\n", e.what());
    return 2;
  } catch (const NonFiniteError& e) {
    std::fprintf(stderr, "huygens-viz: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "huygens-viz: %s\n", e.what());
    return 1;
  }
}

namespace {

// Per-pass render times (median of repeated frames, glFinish around each pass) and the
// simulation's share of a frame: one full step per display_per_step frames.
int run_benchmark(const std::string& scene_file, huygens::RenderSettings settings, int subsample) {
  using namespace huygens;
  using clock = std::chrono::steady_clock;
  gl::HeadlessContext ctx;
  const Scene scene = load_scene(scene_file);
  std::unique_ptr<Solver> solver = make_solver(scene, RunOptions{});
  const SceneGeometry geo = scene_geometry(scene, *solver);
  // simulation: median wall time of a full step
  std::vector<double> steps_ms;
  for (int i = 0; i < 9; ++i) {
    const auto t0 = clock::now();
    solver->step();
    steps_ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  const double step_ms = median(steps_ms);
  const double sim_per_frame = step_ms / geo.display_per_step;
  std::printf("huygens-viz --benchmark: scene %s, renderer %s\n", scene_file.c_str(), ctx.renderer().c_str());
  std::printf(
      "visible field %zux%zu, mesh subsampling %d, simulation step %.2f ms (median of 9), "
      "%d displayed frames per step\n\n",
      geo.grid.rows, geo.grid.cols, subsample, step_ms, geo.display_per_step);
  WaterRenderer renderer(geo.grid, geo.ground_z, subsample);
  renderer.set_height_offset(geo.height_offset);
  renderer.set_heights(solver->height());
  renderer.set_ships(solver_ship_poses(geo, *solver));  // where the solver has them
  const OrbitCamera cam =
      default_camera(geo.grid.x0, geo.grid.y0, geo.grid.cols * geo.grid.dx, geo.grid.rows * geo.grid.dx);
  Table t({"size", "mesh+normals CPU", "upload", "caustics", "ground", "surface", "ship", "render total", "sim/frame",
           "sim share"});
  for (auto [w, h] : {std::pair{1280, 720}, std::pair{640, 360}}) {
    RenderTarget target(w, h);
    renderer.times.enabled = true;
    std::vector<double> pr, up, ca, gr, su, sh, tot;
    for (int i = 0; i < 12; ++i) {
      renderer.set_heights(solver->height());  // every frame uploads new heights, as in the app
      renderer.render(cam, settings, target);
      if (i < 2) continue;  // warm-up
      const RenderTimes& r = renderer.times;
      pr.push_back(r.prepare), up.push_back(r.upload), ca.push_back(r.caustics), gr.push_back(r.ground),
          su.push_back(r.surface), sh.push_back(r.ship);
      tot.push_back(r.prepare + r.upload + r.caustics + r.ground + r.surface + r.ship);
    }
    const double total = median(tot);
    t.add({std::to_string(w) + "x" + std::to_string(h), fmt("%.2f", median(pr)), fmt("%.2f", median(up)),
           fmt("%.2f", median(ca)), fmt("%.2f", median(gr)), fmt("%.2f", median(su)), fmt("%.2f", median(sh)),
           fmt("%.2f", total), fmt("%.2f", sim_per_frame),
           fmt("%.1f", 100.0 * sim_per_frame / (sim_per_frame + total)) + " %"});
  }
  std::printf("%s\n", t.text().c_str());
  {
    // the linearised refraction coefficients are recomputed on the CPU when the camera moves
    const SurfaceMeshLayout layout =
        make_mesh_layout(geo.grid.rows, geo.grid.cols, static_cast<std::size_t>(subsample));
    RefractionParams rp;
    rp.index = settings.index;
    rp.ground_z = geo.ground_z;
    std::vector<double> lin_ms;
    for (int i = 0; i < 5; ++i) {
      const auto t0 = clock::now();
      const LinearRefraction lin = linearise_refraction(geo.grid, layout, cam.rays(), rp);
      lin_ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
    }
    std::printf("camera move: linearised refraction coefficients recomputed in %.2f ms (median of 5, CPU)\n",
                median(lin_ms));
  }
  std::printf(
      "times in ms per displayed frame (median of 10 after 2 warm-up frames, glFinish after each pass);\n"
      "sim share = simulation time per displayed frame / (simulation + render) when both run on one core.\n");
  return 0;
}

}  // namespace
