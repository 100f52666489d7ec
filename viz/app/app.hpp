#pragma once
// Entry points of huygens-viz besides the headless capture: the interactive window
// (window_app.cpp) and the render benchmark.
#include <string>

#include "headless.hpp"
#include "scene_view.hpp"

namespace huygens {

struct WindowOptions {
  int width = 1280, height = 720;
  int subsample = 4;
  /// Samples per pixel (RenderTarget; 1 = no anti-aliasing); 0: RenderTarget::kDefaultSamples on a
  /// GPU, 1 on a software renderer (llvmpipe: 4 samples take twice the frame time there).
  int samples = 0;
  RenderSettings settings;
  /// Smoke-test automation: after this many frames press S (screenshot) and then quit
  /// through the same key path a user takes; 0 = run until the window is closed.
  int auto_frames = 0;
  /// Where S saves screenshots ("" = huygens-viz-NNNN.png in the working directory).
  std::string screenshot;
  /// Start with the simulation paused.
  bool paused = false;
  /// Start in the plan view (P toggles it), showing this.
  bool plan = false;
  PlanQuantity plan_quantity = PlanQuantity::level;
};

/// Runs `scene`'s solver in the window until it is closed; returns the process exit code.
int run_window(ViewerSolver scene, const WindowOptions& opt);

}  // namespace huygens
