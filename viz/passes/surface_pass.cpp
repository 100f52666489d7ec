#include "surface_pass.hpp"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

namespace huygens {

SurfacePass::SurfacePass(const GridPlacement& grid, double ground_z, int subsample)
    : grid_(grid),
      ground_z_(ground_z),
      factor_(static_cast<std::size_t>(std::max(1, subsample))),
      prog_(load_lit_program("surface.vert", "surface.frag", {"solid_colour.glsl", "solids_optics.glsl"})) {
  layout_ = make_mesh_layout(grid_.rows, grid_.cols, factor_);
  mesh_h_.assign(layout_.vertex_rows() * layout_.vertex_cols(), 0.0f);
  diffs_.assign(2 * grid_.rows * grid_.cols, 0.0f);
  const int cols = static_cast<int>(grid_.cols), rows = static_cast<int>(grid_.rows);
  diffs_tex_ = gl::Texture(cols, rows, GL_RG32F);
  diffs_tex_.set_filter(GL_LINEAR, GL_LINEAR);
  coef_tex_ = gl::Texture(cols, rows, GL_RGBA32F);
  coef_tex_.set_filter(GL_LINEAR, GL_LINEAR);
  build_mesh();
}

SurfacePass::~SurfacePass() {
  const GLuint bufs[] = {static_vbo_, h_vbo_, lin_vbo_, ibo_};
  glDeleteBuffers(4, bufs);
  glDeleteVertexArrays(1, &vao_);
}

// The mesh's buffers: static (x, y), dynamic heights, per-view coefficients, triangle indices.
void SurfacePass::build_mesh() {
  const std::size_t nv = layout_.vertex_rows() * layout_.vertex_cols();
  std::vector<float> xy;
  xy.reserve(2 * nv);
  for (std::size_t l = 0; l < layout_.vertex_rows(); ++l)
    for (std::size_t k = 0; k < layout_.vertex_cols(); ++k) {
      xy.push_back(static_cast<float>(grid_.x(layout_.col_idx[k])));
      xy.push_back(static_cast<float>(grid_.y(layout_.row_idx[l])));
    }
  const std::vector<std::uint32_t> idx = mesh_triangles(layout_);
  index_count_ = static_cast<GLsizei>(idx.size());
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  auto attribute = [](GLuint& vbo, GLuint slot, int size, GLsizeiptr bytes, const void* data, GLenum usage) {
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, bytes, data, usage);
    glEnableVertexAttribArray(slot);
    glVertexAttribPointer(slot, size, GL_FLOAT, GL_FALSE, 0, nullptr);
  };
  const auto bytes = [](std::size_t n) { return static_cast<GLsizeiptr>(n * sizeof(float)); };
  attribute(static_vbo_, 0, 2, bytes(xy.size()), xy.data(), GL_STATIC_DRAW);
  attribute(h_vbo_, 1, 1, bytes(nv), mesh_h_.data(), GL_STREAM_DRAW);
  attribute(lin_vbo_, 2, 4, bytes(4 * nv), nullptr, GL_DYNAMIC_DRAW);
  glGenBuffers(1, &ibo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(std::uint32_t)), idx.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
}

void SurfacePass::prepare(std::span<const float> eta) {
  subsample_heights(eta, grid_.rows, grid_.cols, factor_, layout_, mesh_h_);
  height_differences(eta, grid_.rows, grid_.cols, diffs_);
  heights_dirty_ = true;
}

bool SurfacePass::upload_grid_field(std::span<const float> values, gl::Texture& tex) const {
  if (values.size() != grid_.rows * grid_.cols) return false;
  if (tex.width() != static_cast<int>(grid_.cols)) {
    tex = gl::Texture(static_cast<int>(grid_.cols), static_cast<int>(grid_.rows), GL_R32F);
    tex.set_filter(GL_LINEAR, GL_LINEAR);
  }
  tex.upload(values.data(), GL_RED, GL_FLOAT);
  return true;
}

void SurfacePass::upload(const OrbitCamera& camera, float index) {
  const ViewRays v = camera.rays();
  const bool same_view = lin_valid_ && index == lin_index_ && v.ortho == lin_view_.ortho &&
                         (v.ortho ? v.dir == lin_view_.dir : v.eye == lin_view_.eye);
  if (!same_view) {
    RefractionParams rp;
    rp.index = index;
    rp.ground_z = ground_z_;
    const LinearRefraction lin = linearise_refraction(grid_, layout_, v, rp);
    glBindBuffer(GL_ARRAY_BUFFER, lin_vbo_);
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(lin.vertex.size() * sizeof(float)), lin.vertex.data());
    coef_tex_.upload(lin.grid.data(), GL_RGBA, GL_FLOAT);
    lin_valid_ = true;
    lin_view_ = v;
    lin_index_ = index;
  }
  if (!heights_dirty_) return;
  diffs_tex_.upload(diffs_.data(), GL_RG, GL_FLOAT);
  glBindBuffer(GL_ARRAY_BUFFER, h_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(mesh_h_.size() * sizeof(float)), mesh_h_.data());
  heights_dirty_ = false;
}

void SurfacePass::draw(const FrameContext& f, const ShadingScene& scene, const gl::Texture* bed) const {
  const RenderSettings& s = f.s;
  set_shading_uniforms(prog_, f, scene);
  glUniformMatrix4fv(prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(f.mvp));
  diffs_tex_.bind(2);
  const bool dye = s.dye && has_dye_;
  glUniform1i(prog_.loc("u_use_dye"), dye ? 1 : 0);
  glUniform1i(prog_.loc("u_dye"), 4);
  set_colour(prog_, "u_dye_colour", s.dye_colour);
  if (dye) dye_tex_.bind(4);
  const bool foam = s.foam && has_foam_;
  glUniform1i(prog_.loc("u_use_foam"), foam ? 1 : 0);
  glUniform1i(prog_.loc("u_foam"), 6);
  set_colour(prog_, "u_foam_colour", s.foam_colour);
  if (foam) foam_tex_.bind(6);
  coef_tex_.bind(3);
  glUniform1i(prog_.loc("u_use_bed"), bed ? 1 : 0);
  glUniform1i(prog_.loc("u_bed"), 5);
  glUniform1f(prog_.loc("u_dry_depth"), kDryDepth);
  glUniform1i(prog_.loc("u_hide_dry"), s.hide_dry ? 1 : 0);
  if (bed) bed->bind(5);
  glUniform1i(prog_.loc("u_diffs"), 2);
  glUniform1i(prog_.loc("u_coef"), 3);
  glUniform2f(prog_.loc("u_grid_origin"), static_cast<float>(grid_.x0), static_cast<float>(grid_.y0));
  glUniform2f(prog_.loc("u_grid_size"), static_cast<float>(grid_.cols), static_cast<float>(grid_.rows));
  glUniform1f(prog_.loc("u_dx"), static_cast<float>(grid_.dx));
  glUniform1i(prog_.loc("u_exact"), s.exact_refraction ? 1 : 0);
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

void SurfacePass::draw_sides(const FrameContext& f, const FlatDrawer& flat) const {
  const std::size_t vr = layout_.vertex_rows(), vc = layout_.vertex_cols();
  std::vector<float> tri;
  auto edge = [&](std::size_t a, std::size_t b, double xa, double ya, double xb, double yb) {
    const float ha = mesh_h_[a], hb = mesh_h_[b], z0 = static_cast<float>(ground_z_);
    // a film's side was a dark line along the floor past the surge's toe
    if (f.s.hide_dry && ha - z0 < kDryDepth && hb - z0 < kDryDepth) return;
    const float p[4][3] = {{static_cast<float>(xa), static_cast<float>(ya), z0},
                           {static_cast<float>(xb), static_cast<float>(yb), z0},
                           {static_cast<float>(xb), static_cast<float>(yb), hb},
                           {static_cast<float>(xa), static_cast<float>(ya), ha}};
    for (int k : {0, 1, 2, 0, 2, 3}) tri.insert(tri.end(), p[k], p[k] + 3);
  };
  const auto X = [&](std::size_t k) { return grid_.x(layout_.col_idx[k]); };
  const auto Y = [&](std::size_t l) { return grid_.y(layout_.row_idx[l]); };
  for (std::size_t k = 0; k + 1 < vc; ++k) {
    edge(k, k + 1, X(k), Y(0), X(k + 1), Y(0));
    const std::size_t top = (vr - 1) * vc;
    edge(top + k, top + k + 1, X(k), Y(vr - 1), X(k + 1), Y(vr - 1));
  }
  for (std::size_t l = 0; l + 1 < vr; ++l) {
    edge(l * vc, (l + 1) * vc, X(0), Y(l), X(0), Y(l + 1));
    edge(l * vc + vc - 1, (l + 1) * vc + vc - 1, X(vc - 1), Y(l), X(vc - 1), Y(l + 1));
  }
  flat.draw(tri, FlatKind::water_side, f);
}

}  // namespace huygens
