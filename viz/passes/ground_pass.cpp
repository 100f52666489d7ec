#include "ground_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>

namespace huygens {

namespace {

constexpr int kPatternTexSize = 512;

// Cheap deterministic hash noise in [0, 1) for the tile texture.
float hash01(std::uint32_t x, std::uint32_t y) {
  std::uint32_t h = x * 374761393u + y * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return static_cast<float>((h ^ (h >> 16)) & 0xffffu) / 65536.0f;
}

// The pattern's colour at texel (x, y) of an n x n texture holding `sq` squares across.
glm::vec3 pattern_colour(const RenderSettings& s, int x, int y, int n, int sq) {
  const int cx = x * sq / n, cy = y * sq / n;  // square index (n divisible by sq for exact edges)
  if (s.ground == GroundPattern::checker) return ((cx + cy) % 2 == 0) ? glm::vec3(0.9f) : glm::vec3(0.1f);
  if (s.ground == GroundPattern::uniform) return s.ground_uniform;
  // sandy tiles with darker grout lines, a tone per tile (no per-texel grain: it made every
  // picture incompressible and hid the caustics' fine detail)
  const float fx = static_cast<float>(x * sq % n) / n, fy = static_cast<float>(y * sq % n) / n;
  const bool grout = fx < 0.03f || fy < 0.03f;
  const float tone = 0.9f + 0.1f * hash01(static_cast<std::uint32_t>(cx), static_cast<std::uint32_t>(cy));
  return grout ? glm::vec3(0.35f, 0.32f, 0.28f)
               : tone * (((cx + cy) % 2 == 0) ? glm::vec3(0.86f, 0.78f, 0.60f) : glm::vec3(0.74f, 0.66f, 0.50f));
}

}  // namespace

GroundPass::GroundPass(const GridPlacement& grid, double ground_z, const SurfaceMeshLayout& layout)
    : grid_(grid), ground_z_(ground_z), layout_(layout), prog_(load_lit_program("ground.vert", "ground.frag")) {
  build_quads();
}

GroundPass::~GroundPass() {
  const GLuint bufs[] = {quads_vbo_, terrain_vbo_, terrain_ibo_};
  glDeleteBuffers(3, bufs);
  const GLuint vaos[] = {quads_vao_, terrain_vao_};
  glDeleteVertexArrays(2, vaos);
}

// One large floor quad, 5 times the region's longer side, centred on the visible region (vertices
// 0-5); the floor under the region (6-11); a deck at the rest level around it, 2 extents wide,
// reaching 1.5 cells under the water's outline so that no gap opens between its edge and a wave
// trough there (12-35); over terrain the deck ends at the outline (36-59): there the water and the
// bed may lie below the rest level near the edge.
void GroundPass::build_quads() {
  const double w = grid_.cols * grid_.dx, h = grid_.rows * grid_.dx;
  const float gz = static_cast<float>(ground_z_);
  // the floor rect and the deck's inner edge: the surface mesh's outline (first to last point)
  const float ax = static_cast<float>(grid_.x(0)), bx = static_cast<float>(grid_.x(grid_.cols - 1));
  const float ay = static_cast<float>(grid_.y(0)), by = static_cast<float>(grid_.y(grid_.rows - 1));
  const float gx0 = static_cast<float>(grid_.x0 - 2.0 * w), gx1 = static_cast<float>(grid_.x0 + 3.0 * w);
  const float gy0 = static_cast<float>(grid_.y0 - 2.0 * h), gy1 = static_cast<float>(grid_.y0 + 3.0 * h);
  std::vector<float> quads;
  auto quad = [&](float x0, float y0, float x1, float y1, float z) {
    quads.insert(quads.end(), {x0, y0, z, x1, y0, z, x1, y1, z, x0, y0, z, x1, y1, z, x0, y1, z});
  };
  // the large floor (seen without a deck: a quasi-2D slab from the side) reaches 2.5 times the
  // region's longer side from its middle both ways, so a slab's floor is not a narrow strip
  const double far = 2.5 * std::max(w, h), mx = grid_.x0 + 0.5 * w, my = grid_.y0 + 0.5 * h;
  quad(static_cast<float>(mx - far), static_cast<float>(my - far), static_cast<float>(mx + far),
       static_cast<float>(my + far), gz);
  quad(ax, ay, bx, by, gz);
  for (const float o : {static_cast<float>(1.5 * grid_.dx), 0.0f}) {  // south, north, west, east
    quad(gx0, gy0, gx1, ay + o, 0.0f);
    quad(gx0, by - o, gx1, gy1, 0.0f);
    quad(gx0, ay + o, ax + o, by - o, 0.0f);
    quad(bx - o, ay + o, gx1, by - o, 0.0f);
  }
  glGenVertexArrays(1, &quads_vao_);
  glBindVertexArray(quads_vao_);
  glGenBuffers(1, &quads_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, quads_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(quads.size() * sizeof(float)), quads.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);
}

double GroundPass::tile_m() const {
  const double want = static_cast<double>(std::max(grid_.cols, grid_.rows)) * grid_.dx / 8.0;
  const double decade = std::pow(10.0, std::floor(std::log10(want)));
  double best = decade;
  for (const double m : {2.0, 5.0, 10.0})
    if (std::abs(std::log(m * decade / want)) < std::abs(std::log(best / want))) best = m * decade;
  return best;
}

void GroundPass::set_bed(std::span<const float> z) {
  has_bed_ = z.size() == grid_.rows * grid_.cols;
  if (!has_bed_) return;
  bed_tex_ = gl::Texture(static_cast<int>(grid_.cols), static_cast<int>(grid_.rows), GL_R32F);
  bed_tex_.set_filter(GL_LINEAR, GL_LINEAR);
  bed_tex_.upload(z.data(), GL_RED, GL_FLOAT);
  std::vector<float> xyz;
  for (std::size_t l = 0; l < layout_.vertex_rows(); ++l)
    for (std::size_t k = 0; k < layout_.vertex_cols(); ++k)
      xyz.insert(xyz.end(),
                 {static_cast<float>(grid_.x(layout_.col_idx[k])), static_cast<float>(grid_.y(layout_.row_idx[l])),
                  z[layout_.row_idx[l] * grid_.cols + layout_.col_idx[k]]});
  if (terrain_vao_ == 0) {
    glGenVertexArrays(1, &terrain_vao_);
    glGenBuffers(1, &terrain_vbo_);
    glGenBuffers(1, &terrain_ibo_);
  }
  glBindVertexArray(terrain_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, terrain_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(xyz.size() * sizeof(float)), xyz.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  const std::vector<std::uint32_t> idx = mesh_triangles(layout_);
  terrain_index_count_ = static_cast<GLsizei>(idx.size());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, terrain_ibo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(std::uint32_t)), idx.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  gl::check("GroundPass::set_bed");
}

void GroundPass::update_pattern(const RenderSettings& s) {
  const glm::vec3 u = s.ground_uniform * 255.0f;
  const int key = static_cast<int>(s.ground) * 100000 + s.ground_squares * 1000 + static_cast<int>(u.r) * 7 +
                  static_cast<int>(u.g) * 131 + static_cast<int>(u.b) * 17;
  if (key == pattern_key_) return;
  pattern_key_ = key;
  const int n = kPatternTexSize, sq = std::max(1, s.ground_squares);
  std::vector<std::uint8_t> px(static_cast<std::size_t>(n) * n * 4);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const glm::vec3 c = pattern_colour(s, x, y, n, sq);
      std::uint8_t* p = &px[4 * (static_cast<std::size_t>(y) * n + x)];
      for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
      p[3] = 255;
    }
  pattern_tex_ = gl::Texture(n, n, GL_SRGB8_ALPHA8, 10);  // sRGB texels, sampled as linear
  pattern_tex_.upload(px.data(), GL_RGBA, GL_UNSIGNED_BYTE, 0);
  glBindTexture(GL_TEXTURE_2D, pattern_tex_.id());
  glGenerateMipmap(GL_TEXTURE_2D);
  pattern_tex_.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  pattern_tex_.set_wrap(GL_REPEAT);
}

void GroundPass::draw(const FrameContext& f, const ShadingScene& scene) const {
  if (has_bed_)
    draw_terrain(f, scene);
  else if (!f.s.deep_water || f.s.pool_deck)
    draw_floor(f, scene);
}

// The bed as terrain, lit with its slope, and the deck around it ending at the outline.
void GroundPass::draw_terrain(const FrameContext& f, const ShadingScene& scene) const {
  set_shading_uniforms(prog_, f, scene);
  glUniformMatrix4fv(prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(f.mvp));
  glUniform1i(prog_.loc("u_terrain"), 1);
  glBindVertexArray(terrain_vao_);
  glDrawElements(GL_TRIANGLES, terrain_index_count_, GL_UNSIGNED_INT, nullptr);
  glUniform1i(prog_.loc("u_terrain"), 0);
  if (f.s.pool_deck) {
    glBindVertexArray(quads_vao_);
    glDrawArrays(GL_TRIANGLES, 36, 24);
  }
}

// The floor seen directly and the deck around the region.
void GroundPass::draw_floor(const FrameContext& f, const ShadingScene& scene) const {
  set_shading_uniforms(prog_, f, scene);
  glUniformMatrix4fv(prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(f.mvp));
  glUniform1i(prog_.loc("u_terrain"), 0);
  glBindVertexArray(quads_vao_);
  // the deck lies at the rest level and reaches under the water's outline: pushed back in depth
  // so that the water there wins the depth test instead of alternating with it (z-fighting)
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 2.0f);
  if (f.s.pool_deck)
    glDrawArrays(GL_TRIANGLES, f.s.deep_water ? 12 : 6, f.s.deep_water ? 24 : 30);
  else
    glDrawArrays(GL_TRIANGLES, 0, 6);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

}  // namespace huygens
