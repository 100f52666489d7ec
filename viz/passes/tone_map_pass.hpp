#pragma once
// The tone map pass (docs/viz.md "Tone map"): the half-float scene (no clamping: caustics and
// glints exceed 1) into the 8-bit display image, once at the end: identity up to the knee k, then
// k + (1 - k)(1 - exp(-(x - k)/(1 - k))) (C1, saturates at 1); off = clamp (shaders/tonemap.frag).
#include "gl.hpp"
#include "render_settings.hpp"
#include "render_target.hpp"

namespace huygens {

/// The tone curve of one channel value x >= 0 (the shader's, for the tests).
double tone_curve(double x, double knee);

class ToneMapPass {
 public:
  ToneMapPass();
  ~ToneMapPass();
  ToneMapPass(const ToneMapPass&) = delete;
  ToneMapPass& operator=(const ToneMapPass&) = delete;
  /// target.hdr() (resolved) into target's 8-bit image.
  void run(const RenderSettings& s, const RenderTarget& target) const;

 private:
  gl::Program prog_;
  GLuint empty_vao_ = 0;
};

}  // namespace huygens
