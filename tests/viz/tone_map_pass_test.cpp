// Tests of the tone map pass (viz/passes/tone_map_pass.hpp): the half-float scene into the 8-bit
// image through the closed form of the tone curve, and a clamp when the tone map is off.
#include "tone_map_pass.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "render_test_helpers.hpp"

using namespace huygens;
using namespace huygens::test;

namespace {

// Each value of `x` written into its own column of a half-float target (glClear in a scissor box),
// then the pass: the 8-bit image.
gl::Image8 tone_map_columns(const std::vector<float>& x, const RenderSettings& s) {
  const int w = static_cast<int>(x.size()), h = 4;
  RenderTarget target(w, h, 1);
  target.bind();
  glEnable(GL_SCISSOR_TEST);
  for (int j = 0; j < w; ++j) {
    glScissor(j, 0, 1, h);
    glClearColor(x[j], 0.5f * x[j], 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  const ToneMapPass pass;
  target.resolve_scene();
  pass.run(s, target);
  return target.read();
}

}  // namespace

// The scene's linear radiance x goes through the tone curve (x below the knee k, above it
// k + (1 - k)(1 - exp(-(x - k)/(1 - k))), slope 1 at the knee, below 1), or a clamp at 1 when off,
// then the sRGB encoding. Every channel within 1/255 of the closed form (the half-float scene
// holds the values to 5e-4).
TEST_F(VizRender, ToneMapIsTheClosedFormCurveOfEachChannel) {
  const std::vector<float> x{0.0f, 0.1f, 0.25f, 0.5f, 0.79f, 0.8f, 0.85f, 0.9f, 1.0f, 1.2f, 1.5f, 2.0f, 3.0f, 10.0f};
  RenderSettings s;
  s.tone_knee = 0.8f;
  for (const bool on : {true, false}) {
    s.tone_map = on;
    const gl::Image8 img = tone_map_columns(x, s);
    for (std::size_t j = 0; j < x.size(); ++j)
      for (int c = 0; c < 2; ++c) {
        const double v = (c == 0 ? 1.0 : 0.5) * x[j];
        const double want = display(on ? tone_curve(v, s.tone_knee) : v);  // then encoded to sRGB
        EXPECT_NEAR(channel(img, static_cast<int>(j), 1, c), want, 1.0 / 255.0)
            << (on ? "tone map" : "clamp") << " of " << v << ", channel " << c;
      }
  }
  EXPECT_NEAR(tone_curve(0.8 + 1e-6, 0.8) - tone_curve(0.8, 0.8), 1e-6, 1e-9) << "slope 1 at the knee";
  EXPECT_LT(tone_curve(3.0, 0.8), 1.0) << "saturates towards 1 without reaching it";
  EXPECT_GT(tone_curve(3.0, 0.8), 0.9999);
}
