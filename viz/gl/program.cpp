// Shader programs: compile/link from strings or from files in shaders/, errors with the log.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "gl.hpp"

#ifndef HUYGENS_SHADER_DIR
#error "HUYGENS_SHADER_DIR must be defined by the build (path of shaders/)"
#endif

namespace huygens::gl {
namespace {

const char* stage_name(GLenum type) {
  switch (type) {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    case GL_GEOMETRY_SHADER:
      return "geometry";
    default:
      return "shader";
  }
}

GLuint compile(GLenum type, std::string_view src, std::string_view name) {
  GLuint s = glCreateShader(type);
  const char* p = src.data();
  const GLint n = static_cast<GLint>(src.size());
  glShaderSource(s, 1, &p, &n);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(len > 1 ? len : 1), '\0');
    glGetShaderInfoLog(s, len, nullptr, log.data());
    glDeleteShader(s);
    throw GlError(std::string("compile of ") + stage_name(type) + " shader '" + std::string(name) + "' failed:\n" +
                  log.c_str());
  }
  return s;
}

}  // namespace

void check(std::string_view where) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ": GL error 0x%04X", e);
    while (glGetError() != GL_NO_ERROR) {
    }
    throw GlError(std::string(where) + buf);
  }
}

std::string shader_path(std::string_view file) { return std::string(HUYGENS_SHADER_DIR) + "/" + std::string(file); }

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw GlError("cannot read '" + path + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Program::~Program() {
  if (id_) glDeleteProgram(id_);
}

Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}

namespace {
// binds `id` for the duration of a uniform update and restores the previous program
// (glProgramUniform* would need GL 4.1 / ARB_separate_shader_objects)
struct UseGuard {
  GLint previous = 0;
  explicit UseGuard(GLuint id) {
    glGetIntegerv(GL_CURRENT_PROGRAM, &previous);
    if (GLuint(previous) != id) glUseProgram(id);
  }
  UseGuard(const UseGuard&) = delete;
  UseGuard& operator=(const UseGuard&) = delete;
  // (the previous program may have been deleted meanwhile: it lived only while current)
  ~UseGuard() { glUseProgram(previous && glIsProgram(GLuint(previous)) ? GLuint(previous) : 0); }
};
}  // namespace

void Program::set(const char* name, int v) const {
  UseGuard g(id_);
  glUniform1i(loc(name), v);
}
void Program::set(const char* name, float v) const {
  UseGuard g(id_);
  glUniform1f(loc(name), v);
}
void Program::set(const char* name, float x, float y) const {
  UseGuard g(id_);
  glUniform2f(loc(name), x, y);
}
void Program::set(const char* name, float x, float y, float z) const {
  UseGuard g(id_);
  glUniform3f(loc(name), x, y, z);
}
void Program::set(const char* name, float x, float y, float z, float w) const {
  UseGuard g(id_);
  glUniform4f(loc(name), x, y, z, w);
}
void Program::set_mat3(const char* name, const float* m) const {
  UseGuard g(id_);
  glUniformMatrix3fv(loc(name), 1, GL_FALSE, m);
}
void Program::set_mat4(const char* name, const float* m) const {
  UseGuard g(id_);
  glUniformMatrix4fv(loc(name), 1, GL_FALSE, m);
}

Program program_from_strings(std::string_view vertex_src, std::string_view fragment_src, std::string_view name,
                             std::string_view geometry_src) {
  GLuint vs = compile(GL_VERTEX_SHADER, vertex_src, name);
  GLuint gs = 0;
  GLuint fs = 0;
  try {
    if (!geometry_src.empty()) gs = compile(GL_GEOMETRY_SHADER, geometry_src, name);
    fs = compile(GL_FRAGMENT_SHADER, fragment_src, name);
  } catch (...) {
    glDeleteShader(vs);
    if (gs) glDeleteShader(gs);
    throw;
  }
  GLuint p = glCreateProgram();
  glAttachShader(p, vs);
  if (gs) glAttachShader(p, gs);
  glAttachShader(p, fs);
  glLinkProgram(p);
  glDeleteShader(vs);
  if (gs) glDeleteShader(gs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(p, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(len > 1 ? len : 1), '\0');
    glGetProgramInfoLog(p, len, nullptr, log.data());
    glDeleteProgram(p);
    throw GlError("link of program '" + std::string(name) + "' failed:\n" + log.c_str());
  }
  return Program(p);
}

Program program_from_files(const std::string& vertex_file, const std::string& fragment_file,
                           const std::string& geometry_file) {
  auto resolve = [](const std::string& f) { return (!f.empty() && f[0] == '/') ? f : shader_path(f); };
  const std::string vs = read_text_file(resolve(vertex_file));
  const std::string fs = read_text_file(resolve(fragment_file));
  const std::string gs = geometry_file.empty() ? std::string() : read_text_file(resolve(geometry_file));
  return program_from_strings(vs, fs, vertex_file + " + " + fragment_file, gs);
}

std::string_view fullscreen_vertex_shader() {
  return R"(#version 330 core
out vec2 uv;
void main() {
  // one triangle covering the viewport: (-1,-1), (3,-1), (-1,3)
  vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
  uv = 0.5 * p + 0.5;
  gl_Position = vec4(p, 0.0, 1.0);
}
)";
}

}  // namespace huygens::gl
