#pragma once
// Headless capture (docs/viz.md): the scene's solver runs on the same Runner and frame ring as the
// window, with the runner's manual clock instead of the wall clock, and is drawn into an
// offscreen target with no window and no display server (the caller makes a GL context current:
// gl::HeadlessContext, EGL surfaceless). The same options give the same image.
//
// Frame k (k = 0 .. frames-1) shows display time T + k frame_dt (RenderInfo::frame_dt_s); the
// runner computes every step at or before it and publishes the last two (docs/pipeline.md,
// Solver::time_bound), and the frame drawn is the newest (the last full
// step at or before the display time: no interpolation, deterministic, exact at step times).
// The image is the last frame. A flow's dye and foam are advected through every frame from
// t = 0 (frame_dt apart), drawing only the last `frames` of them.
#include <string>

#include "camera.hpp"
#include "gl.hpp"
#include "renderer.hpp"
#include "scene_view.hpp"

namespace huygens {

struct HeadlessOptions {
  /// Frames to render (unit: frames).
  int frames = 1;
  /// Display time of the first frame (unit: s).
  double time = 0.0;
  /// Image size (unit: px).
  int width = 256, height = 256;
  /// Mesh subsampling factor (unit: grid points per vertex spacing).
  int subsample = 4;
  /// The perspective picture gets a caption: scene, time, the region's size, the floor tiles'.
  bool caption = true;
  /// Samples per pixel (RenderTarget; 1 = no anti-aliasing).
  int samples = RenderTarget::kDefaultSamples;
  RenderSettings settings;
  /// Camera; unset = the scene's start-up camera (start_camera), following its first ship when
  /// the scene's view does.
  bool custom_camera = false;
  OrbitCamera camera;
  /// The plan view (render_plan_view) instead of the perspective picture, and what it shows.
  bool plan = false;
  PlanQuantity plan_quantity = PlanQuantity::level;
  /// The scene's frames carry a velocity (Solver::velocity not empty): the perspective picture shows
  /// the dye and the foam it carries from t = 0 (RenderSettings::dye, foam).
  bool flow = false;
};

struct HeadlessResult {
  gl::Image8 image;
  /// Solver steps and the simulated time of the last frame's field (unit: s).
  long long steps = 0;
  double field_time = 0.0;
  RenderTimes times;
};

/// Renders `scene`'s solver as described (make it with open_viewer_solver and RunOptions with
/// measure_plans = false for the same image every run). Throws gl::GlError for GL, and what the
/// solver threw (NonFiniteError naming the stage) when the simulation stopped.
HeadlessResult render_headless(ViewerSolver scene, const HeadlessOptions& opt);

}  // namespace huygens
