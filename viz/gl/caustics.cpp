// Caustics texture of paper 004 section 5 on the GPU (see caustics.hpp).
#include "caustics.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

namespace huygens::viz {
namespace {

std::string with_define(const std::string& src, const char* define) {
  const auto nl = src.find('\n');  // after the #version line
  return src.substr(0, nl + 1) + "#define " + define + " 1\n" + src.substr(nl + 1);
}

constexpr const char* kShadowVs = R"(#version 330 core
layout(location = 0) in vec2 a_uv;
void main() { gl_Position = vec4(2.0 * a_uv - 1.0, 0.0, 1.0); }
)";
constexpr const char* kShadowFs = R"(#version 330 core
out vec4 o_color;
void main() { o_color = vec4(0.0); }
)";

float mip_level_value(const CausticsParams& p, int level) {
  const double v = std::pow(4.0, level - kMipFlatLevel) / (1.0 + 3.0 * p.mip_lod_offset);
  if (p.float_target) return float(v);
  return float(std::min(255.0, std::round(p.unit_level_u8 * v)) / 255.0);
}

}  // namespace

CausticsRenderer::CausticsRenderer(const CausticsParams& params)
    : params_(params),
      target_(params.texture_width, params.texture_height, params.float_target ? GL_R32F : GL_R8),
      fb_(target_) {
  caustics_mesh_init(params_, mesh_);
  const std::string vs = std::string(gl::shader_source("caustics.vert"));
  const std::string fs = std::string(gl::shader_source("caustics.frag"));
  mip_prog_ = gl::program_from_strings(vs, fs, "caustics (MIP)");
  // explicit mode: the per-triangle gain comes from a buffer texture indexed by gl_PrimitiveID,
  // computed on the CPU in render() (a geometry shader did it per triangle; the CPU loop takes
  // ~2 ms for the 346k triangles of a 416 x 416 mesh and llvmpipe's geometry stage is skipped)
  explicit_prog_ = gl::program_from_strings(vs, with_define(fs, "EXPLICIT"), "caustics (explicit)");
  shadow_prog_ = gl::program_from_strings(kShadowVs, kShadowFs, "caustics shadow");
  mip_prog_.set("u_mip", 0);
  explicit_prog_.set("u_mask", 0);
  explicit_prog_.set("u_gain", 1);
  glGenBuffers(1, &gain_buffer_);
  glGenTextures(1, &gain_texture_);

  // mesh buffers: ground positions (streamed), surface coordinates and indices (static)
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  glGenBuffers(1, &vbo_ground_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_ground_);
  // mesh vertices, then the skirt's (CausticsMesh)
  // mesh vertices, the skirt's, then skip_still's rest footprints' corners
  const auto vbo_bytes = GLsizeiptr((2 * mesh_.vertex_count() + mesh_.rest_uv.capacity()) * sizeof(float));
  glBufferData(GL_ARRAY_BUFFER, vbo_bytes, nullptr, GL_STREAM_DRAW);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(0);
  glGenBuffers(1, &vbo_surface_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_surface_);
  glBufferData(GL_ARRAY_BUFFER, vbo_bytes, nullptr, GL_STREAM_DRAW);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(1);
  glGenBuffers(1, &ebo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh_.indices.size() * sizeof(std::uint32_t)), mesh_.indices.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  // explicit mode's draw list (caustics_mesh_triangles): at most the mesh's own triangles
  glGenBuffers(1, &ebo_draw_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_draw_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh_.draw_indices.capacity() * sizeof(std::uint32_t)), nullptr,
               GL_STREAM_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  // shadow polygon buffer
  glGenVertexArrays(1, &vao_shadow_);
  glBindVertexArray(vao_shadow_);
  glGenBuffers(1, &vbo_shadow_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_shadow_);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glEnableVertexAttribArray(0);
  glBindVertexArray(0);
  gl::check("CausticsRenderer setup");
}

CausticsRenderer::~CausticsRenderer() {
  glDeleteTextures(1, &gain_texture_);
  glDeleteBuffers(1, &gain_buffer_);
  glDeleteBuffers(1, &vbo_ground_);
  glDeleteBuffers(1, &vbo_surface_);
  glDeleteBuffers(1, &ebo_);
  glDeleteBuffers(1, &ebo_draw_);
  glDeleteBuffers(1, &vbo_shadow_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteVertexArrays(1, &vao_shadow_);
}

int CausticsRenderer::shadow_top_level() const {
  // every level still water reads from (the paper skips the higher ones)
  return kMipFlatLevel + (params_.mip_lod_offset > 0.0f ? 1 : 0);
}

void CausticsRenderer::ensure_mip() {
  if (mip_) return;
  const int w = params_.texture_width << kMipFlatLevel, h = params_.texture_height << kMipFlatLevel;
  int levels = 1;
  while ((std::max(w, h) >> (levels - 1)) > 1) ++levels;
  mip_.emplace(w, h, params_.float_target ? GL_R32F : GL_R8, levels);
  mip_->set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  // fill every level with its constant, each 4x brighter than the previous (until white)
  for (int l = 0; l < levels; ++l) {
    gl::Framebuffer fb(*mip_, l);
    fb.bind();
    const float v = mip_level_value(params_, l);
    glClearColor(v, v, v, v);
    glClear(GL_COLOR_BUFFER_BIT);
    if (l <= shadow_top_level()) mip_fb_.push_back(std::move(fb));
  }
  gl::check("CausticsRenderer MIP map");
}

void CausticsRenderer::ensure_mask() {
  if (mask_) return;
  mask_.emplace(params_.texture_width, params_.texture_height, GL_R8);
  mask_->set_filter(GL_LINEAR, GL_LINEAR);
  mask_fb_.emplace(*mask_);
}

void CausticsRenderer::draw_shadow_polygon(const std::vector<std::array<float, 2>>& poly,
                                           const HeightfieldView& field) {
  // outline (metres, surface frame) -> surface coordinates [0,1]^2; a convex fan
  const float W = float(field.cols - 1) * field.dx_m, H = float(field.rows - 1) * field.dx_m;
  std::vector<float> uv;
  uv.reserve(2 * poly.size());
  for (const auto& q : poly) uv.insert(uv.end(), {q[0] / W, q[1] / H});
  glBindVertexArray(vao_shadow_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_shadow_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(uv.size() * sizeof(float)), uv.data(), GL_STREAM_DRAW);
  shadow_prog_.use();
  glDrawArrays(GL_TRIANGLE_FAN, 0, GLsizei(poly.size()));
}

// The ship's shadow: black into the lower MIP levels, or into the explicit mode's mask.
void CausticsRenderer::draw_shadow(const std::vector<std::array<float, 2>>& shadow, bool has_ship,
                                   const HeightfieldView& field) {
  if (params_.area == CausticsArea::Explicit) {
    if (!has_ship) return;
    ensure_mask();
    mask_fb_->bind();
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    draw_shadow_polygon(shadow, field);
    return;
  }
  ensure_mip();
  if (!has_ship && !mip_dirty_) return;
  for (int l = 0; l < int(mip_fb_.size()); ++l) {
    mip_fb_[std::size_t(l)].bind();
    const float v = mip_level_value(params_, l);
    glClearColor(v, v, v, v);
    glClear(GL_COLOR_BUFFER_BIT);
    if (has_ship) draw_shadow_polygon(shadow, field);
  }
  mip_dirty_ = has_ship;
}

// The projected mesh into the vertex buffers (ground and surface positions, skirts, and the
// explicit mode's still-water positions).
void CausticsRenderer::upload_mesh() {
  const bool explicit_mode = params_.area == CausticsArea::Explicit;
  auto upload = [&](GLuint vbo, const std::vector<float>& mesh, const std::vector<float>& skirt) {
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(mesh.size() * sizeof(float)), mesh.data());
    glBufferSubData(GL_ARRAY_BUFFER, GLintptr(mesh.size() * sizeof(float)), GLsizeiptr(skirt.size() * sizeof(float)),
                    skirt.data());
    const std::vector<float>& rest = mesh_.rest_uv;
    if (explicit_mode && !rest.empty())
      glBufferSubData(GL_ARRAY_BUFFER, GLintptr((mesh.size() + skirt.size()) * sizeof(float)),
                      GLsizeiptr(rest.size() * sizeof(float)), rest.data());
  };
  upload(vbo_ground_, mesh_.ground_uv, mesh_.skirt_ground_uv);
  upload(vbo_surface_, mesh_.surface_uv, mesh_.skirt_surface_uv);
}

// The program that lights the texture and its inputs; returns the indices to draw.
GLsizei CausticsRenderer::bind_light_program(bool has_ship) {
  if (params_.area != CausticsArea::Explicit) {
    mip_prog_.use();
    mip_prog_.set("u_lod_bias", params_.mip_lod_offset);
    mip_prog_.set("u_isotropic", params_.mip_isotropic_lod ? 1 : 0);
    mip_->bind(0);
    return GLsizei(mesh_.indices.size());
  }
  explicit_prog_.use();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_draw_);
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, GLsizeiptr(mesh_.draw_indices.size() * sizeof(std::uint32_t)),
                  mesh_.draw_indices.data());
  glBindBuffer(GL_TEXTURE_BUFFER, gain_buffer_);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(mesh_.gains.size() * sizeof(float)), mesh_.gains.data(), GL_STREAM_DRAW);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, gain_texture_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, gain_buffer_);
  glActiveTexture(GL_TEXTURE0);
  explicit_prog_.set("u_use_mask", has_ship ? 1 : 0);
  if (has_ship) mask_->bind(0);
  return GLsizei(mesh_.draw_indices.size());
}

void CausticsRenderer::render(const HeightfieldView& field, const ShipShadow* ship) {
  // CPU: subsample, refract and project the mesh vertices
  const auto t0 = std::chrono::steady_clock::now();
  caustics_mesh_update(params_, field, mesh_);
  cpu_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  const bool explicit_mode = params_.area == CausticsArea::Explicit;
  const bool has_ship = ship && ship->outline.size() >= 3;
  std::vector<std::array<float, 2>> shadow;
  if (has_ship) shadow = shadow_on_surface(params_, *ship);
  draw_shadow(shadow, has_ship, field);

  // GPU: all projected triangles, additive
  glBindVertexArray(vao_);
  if (explicit_mode) {
    // per triangle: unit * (surface area) / (ground area), both in texels of the caustics
    // texture (the still-water projection maps one onto the other; surface = the beam
    // cross-section, CausticsParams::flux_by_beam_area); uniform blocks merged into fans, still
    // ones skipped (skip_still) unless under the ship's shadow
    std::array<float, 4> box{1.0f, 1.0f, 0.0f, 0.0f};
    if (has_ship) {
      const float W = float(field.cols - 1) * field.dx_m, H = float(field.rows - 1) * field.dx_m;
      box = {3.4e38f, 3.4e38f, -3.4e38f, -3.4e38f};
      for (const auto& q : shadow)
        box = {std::min(box[0], q[0] / W), std::min(box[1], q[1] / H), std::max(box[2], q[0] / W),
               std::max(box[3], q[1] / H)};
    }
    caustics_mesh_triangles(params_, mesh_, box);
  }
  upload_mesh();
  fb_.bind();
  // skip_still: still-water light 1 to start with, the still blocks are not drawn
  const float start = explicit_mode && mesh_.start_still ? 1.0f : 0.0f;
  glClearColor(start, start, start, start);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  glDrawElements(GL_TRIANGLES, bind_light_program(has_ship), GL_UNSIGNED_INT, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);  // the vertex array's own element buffer again
  glDisable(GL_BLEND);
  glBindVertexArray(0);
  gl::check("CausticsRenderer::render");
}

}  // namespace huygens::viz
