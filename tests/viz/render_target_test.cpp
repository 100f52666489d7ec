// Tests of the render target (viz/passes/render_target.hpp): multisampling.
#include <gtest/gtest.h>

#include "render_test_helpers.hpp"

using namespace huygens;
using namespace huygens::test;

// Multisample anti-aliasing (RenderTarget): a white triangle whose hypotenuse crosses a 64 x 64
// target diagonally, resolved into the half-float scene texture. With 4 samples the pixels the
// edge cuts are partly covered (values strictly between 0 and 1: about one per row), with 1
// sample every pixel is 0 or 1.
TEST_F(VizRender, MultisampledTargetBlendsThePixelsAnEdgeCuts) {
  const gl::Program white = gl::program_from_strings(
      "#version 330 core\nconst vec2 p[3] = vec2[3](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 0.9));\n"
      "void main() { gl_Position = vec4(p[gl_VertexID], 0.0, 1.0); }\n",
      "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n", "white");
  GLuint vao = 0;
  glGenVertexArrays(1, &vao);
  const auto partial = [&](int samples) {
    RenderTarget t(64, 64, samples);
    t.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    white.use();
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    t.resolve_scene();
    std::vector<float> px(64 * 64 * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t.hdr_fbo());
    glReadPixels(0, 0, 64, 64, GL_RGBA, GL_FLOAT, px.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    int n = 0;
    for (std::size_t k = 0; k < px.size(); k += 4) n += px[k] > 0.01f && px[k] < 0.99f;
    return std::make_pair(n, t.samples());
  };
  const auto [one, s1] = partial(1);
  const auto [four, s4] = partial(4);
  glDeleteVertexArrays(1, &vao);
  EXPECT_EQ(s1, 1);
  ASSERT_EQ(s4, 4) << "the driver offers 4 samples";
  EXPECT_EQ(one, 0);
  EXPECT_GE(four, 48) << "about one partly covered pixel per row the edge crosses (61 rows)";
  std::printf("partly covered pixels: %d with 1 sample, %d with 4\n", one, four);
}
