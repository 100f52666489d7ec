// huygens-viz: the visualizer (docs/viz.md, paper 004 section 4).
//   huygens-viz [SCENE]                                   interactive window (GLFW, GL 3.3 core)
//   huygens-viz [SCENE] --headless --frames N [--time T] --screenshot FILE.png
//   huygens-viz [SCENE] --benchmark                       per-pass render times (headless)
// The scene is read by the core (load_scene; no SCENE: the built-in default.json) and the
// viewer sees only its solver's RenderInfo and frames; shaders are compiled into the program.
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app.hpp"
#include "dye.hpp"
#include "foam.hpp"
#include "gl.hpp"
#include "huygens/common/atomic_file.hpp"
#include "huygens/common/isa.hpp"
#include "huygens/common/memory.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/pipeline/runner.hpp"
#include "huygens/pipeline/solver.hpp"
#include "scene_view.hpp"

namespace {

using namespace huygens;

void usage(std::FILE* f) {
  std::fprintf(f,
               "usage: huygens-viz [SCENE] [options]\n"
               "  SCENE                 scene JSON file (default: the built-in default.json); when no such\n"
               "                        file exists, the name of a built-in scene: %s\n"
               "  --headless            render offscreen with no display server (EGL surfaceless)\n"
               "  --frames N            frames to render in --headless mode (default 1)\n"
               "  --time T              display time of the first headless frame, s (default 0)\n"
               "  --screenshot FILE.png where the headless image (or the S key's image) goes\n"
               "  --size WxH            image / window size in pixels (default 1280x720; headless 256x256)\n"
               "  --subsample F         surface mesh subsampling factor (default 4)\n"
               "  --msaa N              samples per pixel (multisample anti-aliasing; default 4, 1 = off;\n"
               "                        a window on a software renderer such as llvmpipe: 1, since there\n"
               "                        4 samples take twice the frame time)\n"
               "  --exact               exact per-pixel Snell refraction (default: linearised coordinates)\n"
               "  --schlick             Schlick Fresnel (the default; --paper-fresnel: clamp(1 - 2.5 n.v))\n"
               "  --paper-fresnel       the paper's Fresnel f = clamp(1 - 2.5 n.v) and glint\n"
               "  --no-caustics         do not light the ground with caustics\n"
               "  --no-caption          headless perspective images without their caption (scene, time,\n"
               "                        the region's size, the floor tiles' side)\n"
               "  --solid-optics M      trace (default): the solids seen through the surface and\n"
               "                        reflected in it, traced per pixel; virtual_eye: paper 000's\n"
               "                        maps from virtual eye points; off: floor and sky only\n"
               "  --no-foam             LBM: do not draw the foam the flow carries (default: drawn)\n"
               "  --caustics-mode M     conserving (default: explicit area, float), mip_paper (the paper's\n"
               "                        MIP trick, 8-bit, accumulation blur), mip_float, explicit_u8,\n"
               "                        simple (paper 000's eq. 4 from heights and normals)\n"
               "  --view V              perspective (default); plan (the water level from above as a colour\n"
               "                        map, colour bar, axes in metres); LBM also speed, dye or foam (from\n"
               "                        above: the flow's speed, the dye and foam it carries); SPH also\n"
               "                        particles (seen from the side, coloured by speed; for a thin slab\n"
               "                        such as sph_dam_break the view that shows the flow)\n"
               "  --benchmark           print per-pass render times at 1280x720 and 640x360 (headless)\n"
               "  --auto-frames N       window: after N frames press S, then quit (smoke test)\n"
               "  --help                this text\n"
               "Exit codes: 0 ok; 1 a write or the GL context failed; 2 bad scene or usage; 3 non-finite\n"
               "  value; 4 not enough memory for the scene; 130/143 stopped by SIGINT/SIGTERM (the window\n"
               "  closes; a headless run abandons its frame and writes no image; a second signal ends\n"
               "  the program at once).\n"
               "Keys (window): space pause, R reset, F1 hide panel, S screenshot, E exact/linearised,\n"
               "  F Fresnel model, P plan view (again: speed, dye, foam or particles), U dive under the\n"
               "  surface (again: back up), Esc quit.\n"
               "Mouse: left click drops a stone, left drag on a ship moves it, right drag orbits, middle\n"
               "  drag (or shift+right) pans, wheel zooms.\n",
               shipped_scene_names());
}

struct CliOptions {
  std::string scene;  // "" = built-in default.json
  std::string screenshot;
  bool headless = false, benchmark = false, size_given = false;
  int frames = 1, w = 1280, h = 720, subsample = 4, auto_frames = 0, samples = 0;  // samples 0: the default
  /// Display time of the first headless frame (unit: s).
  double time = 0.0;
  bool exact = false, schlick = false, paper_fresnel = false, no_caustics = false, no_foam = false, no_caption = false;
  /// "" = the scene's; else perspective / plan.
  std::string view;
  /// "" = the scene's; else a CausticsMode name.
  std::string caustics_mode;
  /// "" = trace; else a SolidOptics name (--solid-optics).
  std::string solid_optics;
};

bool parse_size(const char* s, int& w, int& h) {
  char tail = 0;
  return std::sscanf(s, "%dx%d%c", &w, &h, &tail) == 2 && w > 0 && h > 0 && w <= 16384 && h <= 16384;
}

// Reads the command line into `o`; false for --help. Throws UsageError for bad usage.
bool parse_args(int argc, char** argv, CliOptions& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* {
      if (i + 1 >= argc) throw UsageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") return false;
    if (a == "--headless") {
      o.headless = true;
    } else if (a == "--frames") {
      o.frames = static_cast<int>(parse_int_arg(a, next(), 1, 1000000));
    } else if (a == "--time") {
      o.time = parse_real_arg(a, next(), 0.0, 1e9);
    } else if (a == "--screenshot") {
      o.screenshot = nonempty_arg(a, next());
    } else if (a == "--size") {
      if (!parse_size(next(), o.w, o.h)) throw UsageError("--size takes WxH with W, H in [1, 16384], e.g. 640x360");
      o.size_given = true;
    } else if (a == "--subsample") {
      o.subsample = static_cast<int>(parse_int_arg(a, next(), 1, 64));
    } else if (a == "--msaa") {
      o.samples = static_cast<int>(parse_int_arg(a, next(), 1, 16));
    } else if (a == "--exact" || a == "--schlick" || a == "--no-caustics" || a == "--benchmark") {
      (a == "--exact"         ? o.exact
       : a == "--schlick"     ? o.schlick
       : a == "--no-caustics" ? o.no_caustics
                              : o.benchmark) = true;
    } else if (a == "--paper-fresnel") {
      o.paper_fresnel = true;
    } else if (a == "--solid-optics") {
      o.solid_optics = nonempty_arg(a, next());
      if (o.solid_optics != "trace" && o.solid_optics != "virtual_eye" && o.solid_optics != "off")
        throw UsageError("--solid-optics takes trace, virtual_eye or off");
    } else if (a == "--no-foam") {
      o.no_foam = true;
    } else if (a == "--no-caption") {
      o.no_caption = true;
    } else if (a == "--view") {
      o.view = nonempty_arg(a, next());
      if (o.view != "perspective" && o.view != "plan" && o.view != "speed" && o.view != "dye" && o.view != "foam" &&
          o.view != "particles")
        throw UsageError("--view takes perspective, plan, speed, dye, foam or particles");
    } else if (a == "--caustics-mode") {
      o.caustics_mode = nonempty_arg(a, next());
      if (o.caustics_mode != "conserving" && o.caustics_mode != "mip_paper" && o.caustics_mode != "mip_float" &&
          o.caustics_mode != "explicit_u8" && o.caustics_mode != "simple")
        throw UsageError("--caustics-mode takes conserving, mip_paper, mip_float, explicit_u8 or simple");
    } else if (a == "--auto-frames") {
      o.auto_frames = static_cast<int>(parse_int_arg(a, next(), 1, 1000000));
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option " + a);
    } else if (o.scene.empty()) {
      o.scene = a;
    } else {
      throw UsageError("more than one scene given");
    }
  }
  return true;
}

int run_headless(ViewerSolver vs, const CliOptions& o, const RenderSettings& settings, bool plan,
                 PlanQuantity quantity) {
  if (o.screenshot.empty()) {
    std::fprintf(stderr, "huygens-viz: --headless needs --screenshot FILE.png\n");
    return 2;
  }
  check_output_file(o.screenshot);  // before the render, not after it
  std::error_code ec;
  if (!o.scene.empty() && std::filesystem::equivalent(o.screenshot, o.scene, ec))
    throw UsageError("--screenshot " + o.screenshot + " is the scene file; name another file");
  gl::HeadlessContext ctx;
  HeadlessOptions opt;
  opt.frames = o.frames;
  opt.time = o.time;
  opt.width = o.size_given ? o.w : 256;
  opt.height = o.size_given ? o.h : 256;
  opt.subsample = o.subsample;
  opt.samples = o.samples > 0 ? o.samples : RenderTarget::kDefaultSamples;
  opt.caption = !o.no_caption;
  opt.settings = settings;
  opt.plan = plan;
  opt.plan_quantity = quantity;
  opt.flow = !vs.solver->velocity().empty();
  const std::string name = vs.name;
  const HeadlessResult r = render_headless(std::move(vs), opt);
  gl::write_png(o.screenshot, r.image);
  std::printf("huygens-viz: %d frame(s) of %s rendered headless (%s), %lld steps, field time %.4f s\n", o.frames,
              name.c_str(), ctx.renderer().c_str(), r.steps, r.field_time);
  std::printf("huygens-viz: image written to %s (%dx%d)\n", std::filesystem::absolute(o.screenshot).string().c_str(),
              r.image.width, r.image.height);
  return 0;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Per-pass render times at one size (median of 10 frames after 2 warm-up frames) as table rows:
// wall time, and the process CPU time of the same passes (RenderTimes::cpu).
struct BenchmarkRows {
  std::vector<std::string> wall, cpu;
};
BenchmarkRows benchmark_row(WaterRenderer& renderer, const OrbitCamera& cam, const RenderSettings& settings,
                            std::span<const float> heights, int w, int h, double sim_per_frame, int samples) {
  RenderTarget target(w, h, samples);
  renderer.times.enabled = true;
  std::vector<double> pr, up, ca, gr, su, sh, tm, tot;
  std::vector<double> cup, cca, cgr, csu, csh, ctm, ctot;
  for (int i = 0; i < 12; ++i) {
    renderer.set_heights(heights);  // every frame uploads new heights, as in the app
    renderer.render(cam, settings, target);
    if (i < 2) continue;  // warm-up
    const RenderTimes& r = renderer.times;
    pr.push_back(r.prepare), up.push_back(r.upload), ca.push_back(r.caustics), gr.push_back(r.ground),
        su.push_back(r.surface), sh.push_back(r.ship), tm.push_back(r.tonemap);
    tot.push_back(r.prepare + r.upload + r.caustics + r.ground + r.surface + r.ship + r.tonemap);
    const RenderTimes::Cpu& c = r.cpu;
    cup.push_back(c.upload), cca.push_back(c.caustics), cgr.push_back(c.ground), csu.push_back(c.surface),
        csh.push_back(c.ship), ctm.push_back(c.tonemap);
    ctot.push_back(r.prepare + c.upload + c.caustics + c.ground + c.surface + c.ship + c.tonemap);
  }
  const std::string size = std::to_string(w) + "x" + std::to_string(h);
  const double total = median(tot), ctotal = median(ctot);
  return {{size, fmt("%.2f", median(pr)), fmt("%.2f", median(up)), fmt("%.2f", median(ca)), fmt("%.2f", median(gr)),
           fmt("%.2f", median(su)), fmt("%.2f", median(sh)), fmt("%.2f", median(tm)), fmt("%.2f", total),
           fmt("%.2f", median(ca) / std::max(total - median(ca), 1e-9)), fmt("%.2f", sim_per_frame),
           fmt("%.1f", 100.0 * sim_per_frame / (sim_per_frame + total)) + " %"},
          {size, fmt("%.2f", median(pr)), fmt("%.2f", median(cup)), fmt("%.2f", median(cca)), fmt("%.2f", median(cgr)),
           fmt("%.2f", median(csu)), fmt("%.2f", median(csh)), fmt("%.2f", median(ctm)), fmt("%.2f", ctotal),
           fmt("%.2f", median(cca) / std::max(ctotal - median(cca), 1e-9))}};
}

// Where the solids show (the traced image differs from the one without them by more than 2/255),
// the mean difference of paper 000's image from the traced one (unit: 1/255) and those pixels' count.
std::pair<double, std::size_t> paper_error(const gl::Image8& traced, const gl::Image8& off, const gl::Image8& paper) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k + 3 < traced.pixels.size(); k += 4) {
    int shows = 0, diff = 0;
    for (int c = 0; c < 3; ++c)
      shows = std::max(shows, std::abs(traced.pixels[k + c] - off.pixels[k + c])),
      diff += std::abs(traced.pixels[k + c] - paper.pixels[k + c]);
    if (shows > 2) sum += diff / 3.0, ++n;
  }
  return {n > 0 ? sum / static_cast<double>(n) : 0.0, n};
}

// What the solids in the water cost (RenderSettings::solid_optics): the surface pass and the frame
// at 1280x720 traced, with paper 000's maps and off, alternated 4 times (medians); and the maps'
// error against the trace where the solids show.
void print_solid_optics_cost(WaterRenderer& renderer, const OrbitCamera& cam, const RenderSettings& settings,
                             std::span<const float> heights, int samples) {
  RenderTarget target(1280, 720, samples);
  renderer.times.enabled = true;
  constexpr SolidOptics modes[3] = {SolidOptics::trace, SolidOptics::virtual_eye, SolidOptics::off};
  std::vector<double> surf[3], total[3];
  gl::Image8 img[3];
  for (int i = 0; i < 15; ++i) {
    RenderSettings s = settings;
    s.solid_optics = modes[i % 3];
    renderer.set_heights(heights);
    renderer.render(cam, s, target);
    if (i < 3) continue;
    const RenderTimes& r = renderer.times;
    surf[i % 3].push_back(r.surface);
    total[i % 3].push_back(r.upload + r.caustics + r.ground + r.surface + r.ship + r.tonemap);
    if (i >= 12) img[i % 3] = target.read();
  }
  const double so = std::max(median(surf[2]), 1e-9), fo = std::max(median(total[2]), 1e-9);
  std::printf(
      "solids in the water (1280x720, median of 4 each, alternated): surface pass %.2f ms traced (x%.2f), %.2f ms "
      "paper 000 maps (x%.2f), %.2f ms off; frame x%.2f traced, x%.2f maps\n",
      median(surf[0]), median(surf[0]) / so, median(surf[1]), median(surf[1]) / so, median(surf[2]),
      median(total[0]) / fo, median(total[1]) / fo);
  const auto [err, n] = paper_error(img[0], img[2], img[1]);
  std::printf(
      "paper 000's maps against the trace: mean |difference| %.2f/255 over the %zu pixels where the solids "
      "show\n",
      err, n);
}

// A flow's dye and foam (LBM; dye.hpp, foam.hpp): their CPU step per displayed frame (median of
// 10, unit: ms) with the solver's velocity now, and both handed to the renderer so the surface
// pass draws them as in the app. {0, 0} when the solver has no velocity on the visible grid.
std::pair<double, double> flow_step_times(Solver& solver, const ViewerSolver& vs, const SceneView& view,
                                          WaterRenderer& renderer, DyeField& dye, FoamField& foam) {
  const std::span<const float> u = solver.velocity();
  if (u.size() != 2 * view.grid.rows * view.grid.cols) return {0.0, 0.0};
  const std::span<const float> eta = solver.height();
  using clock = std::chrono::steady_clock;
  std::vector<double> d_ms, f_ms;
  for (int i = 0; i < 10; ++i) {
    auto t0 = clock::now();
    dye.advect(u, vs.info.frame_dt_s);
    d_ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
    t0 = clock::now();
    foam.step(eta, u, vs.info.frame_dt_s);
    f_ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
  }
  renderer.set_dye(dye.values());
  renderer.set_foam(foam.values());
  return {median(d_ms), median(f_ms)};
}

// Per-pass render times (median of repeated frames, glFinish around each pass) and the
// simulation's share of a frame: one full step per display_per_step frames.
int run_benchmark(ViewerSolver vs, const RenderSettings& settings, int subsample, int samples) {
  std::printf("%s\n", machine_line(omp_get_max_threads()).c_str());  // where the figures ran
  const ViewSetup setup = view_setup(vs, 1280.0 / 720.0);
  using clock = std::chrono::steady_clock;
  gl::HeadlessContext ctx;
  Solver& solver = *vs.solver;
  const SceneView view = scene_view(vs.info);
  std::vector<double> steps_ms;  // simulation: median wall time of a full step
  for (int i = 0; i < 9; ++i) {
    const auto t0 = clock::now();
    solver.step();
    steps_ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
  }
  const double step_ms = median(steps_ms), sim_per_frame = step_ms / vs.info.display_per_step;
  std::printf("huygens-viz --benchmark: scene %s, renderer %s\n", vs.name.c_str(), ctx.renderer().c_str());
  std::printf(
      "visible field %zux%zu, mesh subsampling %d, %d samples per pixel, simulation step %.2f ms (median of 9), "
      "%d displayed frames per step\n\n",
      view.grid.rows, view.grid.cols, subsample, samples, step_ms, vs.info.display_per_step);
  WaterRenderer renderer(view.grid, view.ground_z, subsample);
  place_scene(renderer, view);
  std::array<ShipState, kMaxFrameShips> states{};
  std::vector<ShipPose> ships;
  for (std::size_t i = 0; i < solver.ship_poses(states) && i < view.hulls.size(); ++i)
    ships.push_back(view.ship(i, states[i]));  // where the solver has them
  renderer.set_ships(ships);
  const GridPlacement& g = view.grid;
  OrbitCamera cam = setup.camera;
  if (view.follow_ship && !ships.empty()) follow_ship(view, ships[0], cam);
  DyeField dye(view.grid);
  FoamField foam(view.grid, vs.info.bed_m);
  const auto [dye_ms, foam_ms] = flow_step_times(solver, vs, view, renderer, dye, foam);
  Table t({"size", "mesh+normals CPU", "upload", "caustics", "ground", "surface", "ship+solids", "tone map",
           "render total", "caustics / rest", "sim/frame", "sim share"});
  Table tc({"size", "mesh+normals CPU", "upload", "caustics", "ground", "surface", "ship+solids", "tone map",
            "render total", "caustics / rest"});
  for (auto [w, h] : {std::pair{1280, 720}, std::pair{640, 360}}) {
    stop_request::throw_if_requested(fmt("the render benchmark abandoned before %dx%d", w, h));
    BenchmarkRows rows = benchmark_row(renderer, cam, settings, solver.height(), w, h, sim_per_frame, samples);
    t.add(std::move(rows.wall));
    tc.add(std::move(rows.cpu));
  }
  std::printf("%s\n", t.text().c_str());
  std::printf(
      "process CPU time of the same passes (all threads; ms; steadier than wall time on a shared machine):\n%s\n",
      tc.text().c_str());
  // the linearised refraction coefficients are recomputed on the CPU when the camera moves
  const SurfaceMeshLayout layout = make_mesh_layout(g.rows, g.cols, static_cast<std::size_t>(subsample));
  RefractionParams rp;
  rp.index = settings.index;
  rp.ground_z = view.ground_z;
  std::vector<double> lin_ms;
  for (int i = 0; i < 5; ++i) {
    const auto t0 = clock::now();
    const LinearRefraction lin = linearise_refraction(g, layout, cam.rays(), rp);
    lin_ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
  }
  std::printf("camera move: linearised refraction coefficients recomputed in %.2f ms (median of 5, CPU)\n",
              median(lin_ms));
  print_solid_optics_cost(renderer, cam, settings, solver.height(), samples);
  if (dye_ms > 0.0 || foam_ms > 0.0)
    std::printf(
        "flow (once per new frame, CPU, median of 10): dye step %.2f ms, foam step %.2f ms; drawn in the surface "
        "pass above: dye %s, foam %s\n",
        dye_ms, foam_ms, settings.dye ? "on" : "off", settings.foam ? "on" : "off");
  std::printf(
      "times in ms per displayed frame (median of 10 after 2 warm-up frames, glFinish after each pass);\n"
      "sim share = simulation time per displayed frame / (simulation + render) when both run on one core.\n"
      "load average (1 min) at the end: %.2f\n",
      load_average());
  return 0;
}

// The viewer's memory beyond the solver's: the frame ring's heights and rates, the surface and
// caustic meshes and the GL buffers (llvmpipe keeps its own copies), about 96 bytes per visible
// cell (measured: 452 MB more peak RSS for 1024^2 -> 2048^2 headless), plus ~150 MB of GL
// driver and program; a particle solver's frames also carry 16 bytes per particle in each of
// the ring's slots, plus the solver's own copy (Solver::particles()).
MemoryEstimate viewer_memory(const ViewerSolver& vs) {
  MemoryEstimate m = vs.solver->memory();
  m.add("viewer", static_cast<std::uint64_t>(vs.info.grid.rows) * vs.info.grid.cols * 96 + (150ull << 20));
  if (const std::size_t floats = vs.solver->particles().size(); floats > 0)
    m.add("particle frames", (RunnerParams{}.frame_slots + 1) * floats * sizeof(float));
  if (m.size_key.empty()) m.size_key = "the scene's grid";
  return m;
}

// Makes the scene's solver and runs the mode the options ask for; returns the exit code.
int run(CliOptions o) {
  const bool no_display = !std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY");
  if (!o.benchmark && !o.headless && no_display && o.auto_frames == 0) {
    // no display server: render the same scene headless and say where the image is
    o.headless = true;
    if (o.frames == 1) o.frames = 60;
    if (o.screenshot.empty()) o.screenshot = "huygens-viz.png";
    o.size_given = true;  // the window's size
    std::printf("huygens-viz: no display (DISPLAY and WAYLAND_DISPLAY are unset): rendering %d frames headless\n",
                o.frames);
  }
  RunOptions ro;
  ro.measure_plans = o.benchmark;                     // FFTW_ESTIMATE: a fast start, and the same image every run
  ViewerSolver vs = open_viewer_solver(o.scene, ro);  // the solver checked its own memory
  require_memory(viewer_memory(vs));
  // the scene's look and "render" block, then the options
  const double aspect = o.headless && !o.size_given ? 1.0 : static_cast<double>(o.w) / o.h;
  RenderSettings settings = view_setup(vs, aspect).settings;
  settings.exact_refraction = o.exact;
  if (o.schlick) settings.fresnel = FresnelModel::schlick;
  if (o.paper_fresnel) settings.fresnel = FresnelModel::paper, settings.paper_glint = true;
  if (o.no_caustics) settings.caustics = false;
  if (o.no_foam) settings.foam = false;
  if (!o.solid_optics.empty())
    settings.solid_optics = o.solid_optics == "off"           ? SolidOptics::off
                            : o.solid_optics == "virtual_eye" ? SolidOptics::virtual_eye
                                                              : SolidOptics::trace;
  if (!o.caustics_mode.empty())
    settings.caustics_mode = o.caustics_mode == "mip_paper"     ? CausticsMode::mip_paper
                             : o.caustics_mode == "mip_float"   ? CausticsMode::mip_float
                             : o.caustics_mode == "explicit_u8" ? CausticsMode::explicit_u8
                             : o.caustics_mode == "simple"      ? CausticsMode::simple
                                                                : CausticsMode::conserving;
  const bool plan = o.view.empty() ? vs.info.request.plan_view.value_or(false) : o.view != "perspective";
  const PlanQuantity quantity = o.view == "speed"       ? PlanQuantity::speed
                                : o.view == "dye"       ? PlanQuantity::dye
                                : o.view == "foam"      ? PlanQuantity::foam
                                : o.view == "particles" ? PlanQuantity::particles
                                                        : PlanQuantity::level;
  if ((quantity == PlanQuantity::speed || quantity == PlanQuantity::dye || quantity == PlanQuantity::foam) &&
      vs.solver->velocity().empty())
    throw UsageError("--view " + o.view + " needs a flow's velocity: the LBM scenes (dam_break, channel, flood)");
  if (quantity == PlanQuantity::particles && !vs.info.particle_box_m)
    throw UsageError("--view particles needs a particle solver: an SPH scene (pool, sph_dam_break, sph_wedge)");
  if (o.benchmark)
    return run_benchmark(std::move(vs), settings, o.subsample,
                         o.samples > 0 ? o.samples : RenderTarget::kDefaultSamples);
  if (o.headless) return run_headless(std::move(vs), o, settings, plan, quantity);
  WindowOptions wo;
  wo.width = o.w;
  wo.height = o.h;
  wo.subsample = o.subsample;
  wo.samples = o.samples;
  wo.settings = settings;
  wo.auto_frames = o.auto_frames;
  wo.screenshot = o.screenshot;
  wo.plan = plan;
  wo.plan_quantity = quantity;
  return run_window(std::move(vs), wo);
}

}  // namespace

int main(int argc, char** argv) {
  return huygens::run_program("huygens-viz", argv, [&]() {
    CliOptions o;
    if (!parse_args(argc, argv, o)) {
      usage(stdout);
      return 0;
    }
    stop_request::install();  // SIGINT/SIGTERM: the window closes, a headless run abandons its image
    return run(o);
  });
}
