#include "flat_drawer.hpp"

#include <glm/gtc/type_ptr.hpp>
#include <string>

namespace huygens {

FlatDrawer::FlatDrawer()
    : prog_(gl::program_from_strings(gl::shader_source("ship.vert"),
                                     "#version 330 core\n" + std::string(gl::shader_source("solid_colour.glsl")) +
                                         std::string(gl::shader_source("ship.frag")),
                                     "ship.vert + ship.frag")) {
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
}

FlatDrawer::~FlatDrawer() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void FlatDrawer::draw(const std::vector<float>& tri, FlatKind kind, const FrameContext& f) const {
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(tri.size() * sizeof(float)), tri.data(), GL_STREAM_DRAW);
  prog_.use();
  glUniformMatrix4fv(prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(f.mvp));
  glUniform3fv(prog_.loc("u_sun_dir"), 1, glm::value_ptr(f.s.sun_dir));
  const glm::vec3 eye(f.camera.eye());
  glUniform3fv(prog_.loc("u_eye"), 1, glm::value_ptr(eye));
  glUniform1i(prog_.loc("u_solid"), static_cast<int>(kind));
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(tri.size() / 3));
  glUniform1i(prog_.loc("u_solid"), 0);
}

}  // namespace huygens
