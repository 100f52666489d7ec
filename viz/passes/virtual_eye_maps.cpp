#include "virtual_eye_maps.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "refraction.hpp"
#include "virtual_eye.hpp"

namespace huygens {

VirtualEyeMaps::VirtualEyeMaps()
    : prog_(gl::program_from_strings(gl::shader_source("env_solid.vert"),
                                     "#version 330 core\n" + std::string(gl::shader_source("solid_colour.glsl")) +
                                         std::string(gl::shader_source("env_solid.frag")),
                                     "env_solid")),
      atlas_(kTile * kTilesAcross, kTile * kTilesAcross, GL_RGBA32F),
      fbo_(atlas_) {
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, atlas_.width(), atlas_.height());
  fbo_.bind();
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
  gl::check("VirtualEyeMaps");
}

VirtualEyeMaps::~VirtualEyeMaps() {
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteRenderbuffers(1, &depth_);
}

namespace {

// A perspective camera at `from` that sees the box lo-hi whole (square, the field of view the
// largest angle of a corner from the box's middle, 5 % more, at most 170 degrees).
glm::mat4 box_camera(const glm::dvec3& from, const glm::dvec3& lo, const glm::dvec3& hi) {
  const glm::dvec3 mid = 0.5 * (lo + hi), f = glm::normalize(mid - from);
  double half = 0.0, nearest = 1e30, farthest = 0.0;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const glm::dvec3 d = p - from;
    half = std::max(half, std::acos(std::clamp(glm::dot(glm::normalize(d), f), -1.0, 1.0)));
    nearest = std::min(nearest, glm::dot(d, f)), farthest = std::max(farthest, glm::length(d));
  }
  const glm::dvec3 up = std::abs(f.z) > 0.999 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
  const double fov = std::min(2.0 * 1.05 * half, 170.0 * 3.14159265358979 / 180.0);
  const double z_near = std::max(1e-3 * farthest, 0.5 * nearest);
  return glm::mat4(glm::perspective(fov, 1.0, z_near, 2.0 * farthest) * glm::lookAt(from, mid, up));
}

// Where the unit direction d from the tile's eye shows in the tile (uv in [0, 1]^2).
glm::dvec2 tile_uv(const glm::mat4& vp, const glm::dvec3& eye_v, const glm::dvec3& d) {
  const glm::dvec4 c = glm::dmat4(vp) * glm::dvec4(eye_v + d, 1.0);
  return 0.5 * glm::dvec2(c) / c.w + 0.5;
}

}  // namespace

VirtualEyeMaps::Tile VirtualEyeMaps::draw_tile(const EyeObject& o, const glm::dvec3& eye_v, bool above, int tile,
                                               const glm::vec3& light) {
  glm::dvec3 lo = o.lo, hi = o.hi;
  (above ? lo.z : hi.z) = o.plane;
  Tile t{box_camera(eye_v, lo, hi), glm::vec3(eye_v)};
  if (hi.z <= lo.z) return t;  // nothing on this side of the plane
  glViewport((tile % kTilesAcross) * kTile, (tile / kTilesAcross) * kTile, kTile, kTile);
  glUniformMatrix4fv(prog_.loc("u_vp"), 1, GL_FALSE, glm::value_ptr(t.vp));
  glUniform1f(prog_.loc("u_plane"), static_cast<float>(o.plane));
  glUniform1f(prog_.loc("u_side"), above ? 1.0f : -1.0f);
  glUniform3fv(prog_.loc("u_eye_v"), 1, glm::value_ptr(t.eye));
  glUniform3fv(prog_.loc("u_light"), 1, glm::value_ptr(light));
  glUniform1i(prog_.loc("u_kind"), o.kind);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(o.tri.size() / 3));
  return t;
}

// Fig. 3: the scale along the image of the object's main (vertical) axis, about a's image, that puts
// the object's deepest point b below a where the real refracted ray shows it:
// k = |uv(b) - uv(a)| / |uv(t_b) - uv(a)|; (uv(a), k, |E - a|) and the axis' image direction.
glm::vec4 VirtualEyeMaps::size_fix(const EyeObject& o, const glm::dvec3& eye, const glm::dvec3& a, Tile& t,
                                   double index) const {
  const glm::dvec3 ev(t.eye), b(a.x, a.y, o.lo.z);
  const glm::dvec2 uv_a = tile_uv(t.vp, ev, glm::normalize(a - ev));
  double k = 1.0;
  if (o.lo.z < o.plane - 1e-6) {
    const glm::dvec2 uv_b = tile_uv(t.vp, ev, glm::normalize(b - ev));
    const glm::dvec2 uv_t = tile_uv(t.vp, ev, refracted_ray_through(eye, b, o.plane, index));
    const double real = glm::length(uv_t - uv_a);
    if (real > 1e-9) k = glm::length(uv_b - uv_a) / real;
    if (glm::length(uv_b - uv_a) > 1e-9) t.axis = glm::vec2(glm::normalize(uv_b - uv_a));
  }
  return {static_cast<float>(uv_a.x), static_cast<float>(uv_a.y), static_cast<float>(k),
          static_cast<float>(glm::length(eye - a))};
}

void VirtualEyeMaps::build(std::span<const EyeObject> objects, const glm::dvec3& eye, const RenderSettings& s) {
  count_ = static_cast<int>(std::min<std::size_t>(objects.size(), kMaxObjects));
  GLfloat clear[4];
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
  fbo_.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glClearColor(clear[0], clear[1], clear[2], clear[3]);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CLIP_DISTANCE0);
  prog_.use();
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  const glm::dvec3 sun = glm::normalize(glm::dvec3(s.sun_dir));
  const glm::vec3 sun_w(-refract_dir(-sun, glm::dvec3(0.0, 0.0, 1.0), 1.0 / s.index));
  for (int i = 0; i < count_; ++i) {
    const EyeObject& o = objects[static_cast<std::size_t>(i)];
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(o.tri.size() * sizeof(float)), o.tri.data(), GL_STREAM_DRAW);
    const glm::dvec3 a = nearest_waterline_point(eye, o.lo, o.hi, o.plane);
    tiles_[2 * i] = draw_tile(o, refracted_eye(eye, a, s.index), false, 2 * i, sun_w);
    tiles_[2 * i + 1] = draw_tile(o, reflected_eye(eye, o.plane), true, 2 * i + 1, glm::vec3(sun));
    fix_[i] = size_fix(o, eye, a, tiles_[2 * i], s.index);
    const glm::dvec2 x = 0.5 * (glm::dvec2(o.lo) + glm::dvec2(o.hi)), to_eye = glm::dvec2(eye) - x;
    const double R = 0.5 * glm::length(glm::dvec2(o.hi) - glm::dvec2(o.lo));
    const glm::dvec2 r = glm::dot(to_eye, to_eye) > 0.0 ? glm::normalize(to_eye) : glm::dvec2(1.0, 0.0);
    trap_[i] = glm::vec4(glm::vec2(x - R * r), glm::vec2(r));
    radius_[i] = static_cast<float>(R);
  }
  glDisable(GL_CLIP_DISTANCE0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("VirtualEyeMaps::build");
}

void VirtualEyeMaps::set_uniforms(const gl::Program& p, int unit) const {
  atlas_.bind(unit);
  glUniform1i(p.loc("u_env"), unit);
  glUniform1i(p.loc("u_env_count"), count_);
  if (count_ == 0) return;
  std::array<glm::mat4, 2 * kMaxObjects> vp{};
  std::array<glm::vec3, 2 * kMaxObjects> ev{};
  std::array<glm::vec4, kMaxObjects> shape{};
  for (int i = 0; i < 2 * count_; ++i) vp[i] = tiles_[i].vp, ev[i] = tiles_[i].eye;
  for (int i = 0; i < count_; ++i) shape[i] = glm::vec4(tiles_[2 * i].axis, radius_[i], 0.0f);
  glUniform4fv(p.loc("u_env_shape"), count_, glm::value_ptr(shape[0]));
  glUniform4fv(p.loc("u_env_trap"), count_, glm::value_ptr(trap_[0]));
  glUniformMatrix4fv(p.loc("u_env_vp"), 2 * count_, GL_FALSE, glm::value_ptr(vp[0]));
  glUniform3fv(p.loc("u_env_eye"), 2 * count_, glm::value_ptr(ev[0]));
  glUniform4fv(p.loc("u_env_fix"), count_, glm::value_ptr(fix_[0]));
}

}  // namespace huygens
