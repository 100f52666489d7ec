#pragma once
// Headless capture (docs/design.md 5.4): a scene stepped synchronously with its fixed time step
// and seeds, rendered into an offscreen target with no window and no display server
// (the caller makes a GL context current: gl::HeadlessContext, EGL surfaceless). The same
// options give the same image.
//
// Frame k (k = 0 .. frames-1) shows display time T + k dt / display_per_step; the solver is
// stepped until its time is the last full step at or before the display time (no
// interpolation: deterministic, and exact at step times). The image is the last frame.
#include <string>

#include "camera.hpp"
#include "gl.hpp"
#include "renderer.hpp"

namespace huygens {

struct HeadlessOptions {
  std::string scene_file;
  /// Frames to render (unit: frames).
  int frames = 1;
  /// Display time of the first frame (unit: s).
  double time = 0.0;
  /// Image size (unit: px).
  int width = 256, height = 256;
  /// Mesh subsampling factor (unit: grid points per vertex spacing).
  int subsample = 4;
  RenderSettings settings;
  /// Camera; unset = default_camera() of the scene's visible region.
  bool custom_camera = false;
  OrbitCamera camera;
};

struct HeadlessResult {
  gl::Image8 image;
  /// Solver steps taken and the simulated time of the last frame's field (unit: s).
  long long steps = 0;
  double field_time = 0.0;
  RenderTimes times;
};

/// Renders the scene as described. Throws SceneError for a bad scene, gl::GlError for GL.
HeadlessResult render_headless(const HeadlessOptions& opt);

}  // namespace huygens
