#include "tone_map_pass.hpp"

#include <algorithm>
#include <cmath>

namespace huygens {

double tone_curve(double x, double knee) {
  if (x <= knee) return x;
  return knee + (1.0 - knee) * (1.0 - std::exp(-(x - knee) / (1.0 - knee)));
}

ToneMapPass::ToneMapPass()
    : prog_(gl::program_from_strings(gl::fullscreen_vertex_shader(), gl::shader_source("tonemap.frag"), "tonemap")) {
  glGenVertexArrays(1, &empty_vao_);
}

ToneMapPass::~ToneMapPass() { glDeleteVertexArrays(1, &empty_vao_); }

void ToneMapPass::run(const RenderSettings& s, const RenderTarget& target) const {
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo());
  glViewport(0, 0, target.width(), target.height());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  prog_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, target.hdr().id());
  glUniform1i(prog_.loc("u_hdr"), 0);
  glUniform1i(prog_.loc("u_on"), s.tone_map ? 1 : 0);
  glUniform1f(prog_.loc("u_knee"), s.tone_knee);
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace huygens
