#include "renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <glm/gtc/type_ptr.hpp>

#include "caustics_stage.hpp"

namespace huygens {

// ---------------------------------------------------------------------------------
// RenderTarget

RenderTarget::RenderTarget(int width, int height) : color_(width, height, GL_RGBA8), w_(width), h_(height) {
  color_.set_filter(GL_LINEAR, GL_LINEAR);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_.id(), 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw gl::GlError("RenderTarget: incomplete framebuffer");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("RenderTarget");
}

RenderTarget::~RenderTarget() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
}

RenderTarget::RenderTarget(RenderTarget&& o) noexcept
    : color_(std::move(o.color_)), depth_(o.depth_), fbo_(o.fbo_), w_(o.w_), h_(o.h_) {
  o.depth_ = o.fbo_ = 0;
}

RenderTarget& RenderTarget::operator=(RenderTarget&& o) noexcept {
  if (this != &o) {
    if (fbo_) glDeleteFramebuffers(1, &fbo_);
    if (depth_) glDeleteRenderbuffers(1, &depth_);
    color_ = std::move(o.color_);
    depth_ = o.depth_;
    fbo_ = o.fbo_;
    w_ = o.w_;
    h_ = o.h_;
    o.depth_ = o.fbo_ = 0;
  }
  return *this;
}

void RenderTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, w_, h_);
}

gl::Image8 RenderTarget::read() const {
  gl::Image8 img;
  img.width = w_;
  img.height = h_;
  img.channels = 4;
  img.pixels.resize(static_cast<std::size_t>(w_) * h_ * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w_, h_, GL_RGBA, GL_UNSIGNED_BYTE, img.pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  gl::check("RenderTarget::read");
  gl::flip_rows(img);
  return img;
}

// ---------------------------------------------------------------------------------
// WaterRenderer

namespace {

constexpr int kGroundTexSize = 512;

gl::Program load_program(const char* vs, const char* fs, bool with_ground_common) {
  std::string vsrc = std::string(gl::shader_source(vs));
  std::string fsrc = std::string(gl::shader_source(fs));
  if (with_ground_common)
    fsrc = "#version 330 core\n" + std::string(gl::shader_source("ground_common.glsl")) + "\n" + fsrc;
  return gl::program_from_strings(vsrc, fsrc, std::string(vs) + " + " + fs);
}

glm::mat4 mvp_of(const OrbitCamera& cam, double aspect) { return glm::mat4(cam.projection(aspect) * cam.view()); }

// Cheap deterministic hash noise in [0, 1) for the tile texture.
float hash01(std::uint32_t x, std::uint32_t y) {
  std::uint32_t h = x * 374761393u + y * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return static_cast<float>((h ^ (h >> 16)) & 0xffffu) / 65536.0f;
}

double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Wigley hull triangles (world coordinates) of one ship, appended to `out` (x, y, z triples).
void append_hull(const ShipPose& s, std::vector<float>& out) {
  constexpr int ns = 24, nz = 6;
  const double freeboard = std::max(0.6 * s.draft, 0.04 * s.length);
  const double ch = std::cos(s.heading), sh = std::sin(s.heading);
  auto world = [&](double lx, double ly, double z) {
    out.push_back(static_cast<float>(s.x + ch * lx - sh * ly));
    out.push_back(static_cast<float>(s.y + sh * lx + ch * ly));
    out.push_back(static_cast<float>(z));
  };
  // half-width at station x in [-L/2, L/2] and height z in [-T, F]
  auto half = [&](double lx, double z) {
    const double xi = 2.0 * lx / s.length;
    const double zz = z < 0.0 ? z / s.draft : 0.0;
    return 0.5 * s.beam * (1.0 - xi * xi) * (1.0 - zz * zz);
  };
  auto px = [&](int i) { return -0.5 * s.length + s.length * i / ns; };
  auto pz = [&](int k) { return -s.draft + (s.draft + freeboard) * k / nz; };
  for (int side = -1; side <= 1; side += 2) {
    for (int i = 0; i < ns; ++i) {
      for (int k = 0; k < nz; ++k) {
        const double x0 = px(i), x1 = px(i + 1), z0 = pz(k), z1 = pz(k + 1);
        const double a = side * half(x0, z0), b = side * half(x1, z0), c = side * half(x1, z1), d = side * half(x0, z1);
        world(x0, a, z0), world(x1, b, z0), world(x1, c, z1);
        world(x0, a, z0), world(x1, c, z1), world(x0, d, z1);
      }
    }
  }
  // deck at the freeboard height
  for (int i = 0; i < ns; ++i) {
    const double x0 = px(i), x1 = px(i + 1), f = freeboard;
    const double w0 = half(x0, f), w1 = half(x1, f);
    world(x0, -w0, f), world(x1, -w1, f), world(x1, w1, f);
    world(x0, -w0, f), world(x1, w1, f), world(x0, w0, f);
  }
}

}  // namespace

// Surface mesh buffers: static (x, y), dynamic heights, per-view coefficients, triangle indices.
void WaterRenderer::build_surface_mesh() {
  const std::size_t nv = layout_.vertex_rows() * layout_.vertex_cols();
  std::vector<float> xy;
  xy.reserve(2 * nv);
  for (std::size_t l = 0; l < layout_.vertex_rows(); ++l)
    for (std::size_t k = 0; k < layout_.vertex_cols(); ++k) {
      xy.push_back(static_cast<float>(grid_.x(layout_.col_idx[k])));
      xy.push_back(static_cast<float>(grid_.y(layout_.row_idx[l])));
    }
  std::vector<std::uint32_t> idx;
  const auto vc = static_cast<std::uint32_t>(layout_.vertex_cols());
  for (std::uint32_t l = 0; l + 1 < layout_.vertex_rows(); ++l)
    for (std::uint32_t k = 0; k + 1 < vc; ++k) {
      const std::uint32_t v00 = l * vc + k, v10 = v00 + 1, v01 = v00 + vc, v11 = v01 + 1;
      idx.insert(idx.end(), {v00, v10, v11, v00, v11, v01});  // same split as refraction.cpp
    }
  surface_index_count_ = static_cast<GLsizei>(idx.size());
  glGenVertexArrays(1, &surface_vao_);
  glBindVertexArray(surface_vao_);
  glGenBuffers(1, &surface_static_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, surface_static_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(xy.size() * sizeof(float)), xy.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenBuffers(1, &surface_h_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, surface_h_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(nv * sizeof(float)), mesh_h_.data(), GL_STREAM_DRAW);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenBuffers(1, &surface_lin_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, surface_lin_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(4 * nv * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenBuffers(1, &surface_ibo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, surface_ibo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(std::uint32_t)), idx.data(),
               GL_STATIC_DRAW);
}

WaterRenderer::WaterRenderer(const GridPlacement& grid, double ground_z, int subsample)
    : grid_(grid), ground_z_(ground_z), subsample_(std::max(1, subsample)) {
  gl::check("before WaterRenderer");
  layout_ = make_mesh_layout(grid_.rows, grid_.cols, static_cast<std::size_t>(subsample_));
  const std::size_t nv = layout_.vertex_rows() * layout_.vertex_cols();
  eta_.assign(grid_.rows * grid_.cols, 0.0f);
  mesh_h_.assign(nv, 0.0f);
  diffs_.assign(2 * grid_.rows * grid_.cols, 0.0f);

  surface_prog_ = load_program("surface.vert", "surface.frag", true);
  ground_prog_ = load_program("ground.vert", "ground.frag", true);
  ship_prog_ = gl::program_from_shaders("ship.vert", "ship.frag");

  const int cols = static_cast<int>(grid_.cols), rows = static_cast<int>(grid_.rows);
  diffs_tex_ = gl::Texture(cols, rows, GL_RG32F);
  diffs_tex_.set_filter(GL_LINEAR, GL_LINEAR);
  coef_tex_ = gl::Texture(cols, rows, GL_RGBA32F);
  coef_tex_.set_filter(GL_LINEAR, GL_LINEAR);
  flat_light_tex_ = gl::Texture(1, 1, GL_R8);
  const std::uint8_t one = 255;
  flat_light_tex_.upload(&one, GL_RED, GL_UNSIGNED_BYTE);

  build_surface_mesh();
  // ground: one large quad, 5 visible extents wide, centred on the visible region
  const double w = grid_.cols * grid_.dx, h = grid_.rows * grid_.dx;
  const float gx0 = static_cast<float>(grid_.x0 - 2.0 * w), gx1 = static_cast<float>(grid_.x0 + 3.0 * w);
  const float gy0 = static_cast<float>(grid_.y0 - 2.0 * h), gy1 = static_cast<float>(grid_.y0 + 3.0 * h);
  const float quad[] = {gx0, gy0, gx1, gy0, gx1, gy1, gx0, gy0, gx1, gy1, gx0, gy1};
  glGenVertexArrays(1, &ground_vao_);
  glBindVertexArray(ground_vao_);
  glGenBuffers(1, &ground_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, ground_vbo_);
  glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);

  glGenVertexArrays(1, &ship_vao_);
  glBindVertexArray(ship_vao_);
  glGenBuffers(1, &ship_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, ship_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindVertexArray(0);

  caustics_ = make_caustics_stage(grid_, ground_z_);
  gl::check("WaterRenderer");
}

WaterRenderer::~WaterRenderer() {
  glUseProgram(0);  // a deleted program must not stay current (others restore "the previous program")
  caustics_.reset();
  GLuint bufs[] = {surface_static_vbo_, surface_h_vbo_, surface_lin_vbo_, surface_ibo_, ground_vbo_, ship_vbo_};
  glDeleteBuffers(6, bufs);
  GLuint vaos[] = {surface_vao_, ground_vao_, ship_vao_};
  glDeleteVertexArrays(3, vaos);
  if (GLenum e = glGetError(); e != GL_NO_ERROR) std::fprintf(stderr, "~WaterRenderer: GL error 0x%04X\n", e);
}

double WaterRenderer::ground_texel() const { return grid_.cols * grid_.dx / kGroundTexSize; }

void WaterRenderer::set_heights(std::span<const float> eta) {
  const auto t0 = std::chrono::steady_clock::now();
  const float off = offset_;
  std::transform(eta.begin(), eta.end(), eta_.begin(), [off](float v) { return v - off; });
  subsample_heights(eta_, grid_.rows, grid_.cols, static_cast<std::size_t>(subsample_), layout_, mesh_h_);
  height_differences(eta_, grid_.rows, grid_.cols, diffs_);
  heights_dirty_ = true;
  times.prepare = elapsed_ms(t0);
}

void WaterRenderer::update_linearisation(const OrbitCamera& camera, float index) {
  const ViewRays v = camera.rays();
  if (lin_valid_ && index == lin_index_ && v.ortho == lin_view_.ortho &&
      (v.ortho ? v.dir == lin_view_.dir : v.eye == lin_view_.eye))
    return;
  RefractionParams rp;
  rp.index = index;
  rp.ground_z = ground_z_;
  const LinearRefraction lin = linearise_refraction(grid_, layout_, v, rp);
  glBindBuffer(GL_ARRAY_BUFFER, surface_lin_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(lin.vertex.size() * sizeof(float)), lin.vertex.data());
  coef_tex_.upload(lin.grid.data(), GL_RGBA, GL_FLOAT);
  lin_valid_ = true;
  lin_view_ = v;
  lin_index_ = index;
}

void WaterRenderer::build_ground_texture(const RenderSettings& s) {
  const glm::vec3 u = s.ground_uniform * 255.0f;
  const int key = static_cast<int>(s.ground) * 100000 + s.ground_squares * 1000 + static_cast<int>(u.r) * 7 +
                  static_cast<int>(u.g) * 131 + static_cast<int>(u.b) * 17;
  if (key == ground_key_) return;
  ground_key_ = key;
  const int n = kGroundTexSize, sq = std::max(1, s.ground_squares);
  std::vector<std::uint8_t> px(static_cast<std::size_t>(n) * n * 4);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      glm::vec3 c;
      const int cx = x * sq / n, cy = y * sq / n;  // square index (n divisible by sq for exact edges)
      if (s.ground == GroundPattern::checker) {
        c = ((cx + cy) % 2 == 0) ? glm::vec3(0.9f) : glm::vec3(0.1f);
      } else if (s.ground == GroundPattern::uniform) {
        c = s.ground_uniform;
      } else {
        // sandy tiles with darker grout lines and a little deterministic grain
        const float fx = static_cast<float>(x * sq % n) / n, fy = static_cast<float>(y * sq % n) / n;
        const bool grout = fx < 0.03f || fy < 0.03f;
        const float tone = 0.9f + 0.1f * hash01(static_cast<std::uint32_t>(cx), static_cast<std::uint32_t>(cy));
        const float grain = 0.94f + 0.06f * hash01(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y));
        c = grout ? glm::vec3(0.35f, 0.32f, 0.28f)
                  : tone * grain *
                        (((cx + cy) % 2 == 0) ? glm::vec3(0.86f, 0.78f, 0.60f) : glm::vec3(0.74f, 0.66f, 0.50f));
      }
      std::uint8_t* p = &px[4 * (static_cast<std::size_t>(y) * n + x)];
      for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
      p[3] = 255;
    }
  }
  ground_tex_ = gl::Texture(n, n, GL_RGBA8, 10);
  ground_tex_.upload(px.data(), GL_RGBA, GL_UNSIGNED_BYTE, 0);
  glBindTexture(GL_TEXTURE_2D, ground_tex_.id());
  glGenerateMipmap(GL_TEXTURE_2D);
  ground_tex_.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  ground_tex_.set_wrap(GL_REPEAT);
}

void WaterRenderer::set_common_uniforms(const gl::Program& p, const RenderSettings& s, const OrbitCamera&) const {
  p.use();
  glUniform1i(p.loc("u_ground"), 0);
  glUniform1i(p.loc("u_caustics"), 1);
  glUniform2f(p.loc("u_ground_origin"), static_cast<float>(grid_.x0), static_cast<float>(grid_.y0));
  glUniform2f(p.loc("u_ground_extent"), static_cast<float>(grid_.cols * grid_.dx),
              static_cast<float>(grid_.rows * grid_.dx));
  glUniform1f(p.loc("u_ambient"), s.ambient);
  glUniform1f(p.loc("u_sun_light"), s.sun_light);
  const bool use_caustics = s.caustics && caustics_ && caustics_->available();
  glUniform1i(p.loc("u_use_caustics"), use_caustics ? 1 : 0);
  if (use_caustics) {
    const glm::vec2 o(caustics_->origin()), e(caustics_->extent());
    glUniform2f(p.loc("u_caustics_origin"), o.x, o.y);
    glUniform2f(p.loc("u_caustics_extent"), e.x, e.y);
    glUniform1f(p.loc("u_caustics_scale"), caustics_->scale());
  }
  glUniform1f(p.loc("u_ground_z"), static_cast<float>(ground_z_));
}

// The water surface: the subsampled mesh with per-pixel normals, refraction, Fresnel, glint.
void WaterRenderer::draw_surface(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) const {
  const gl::Program& p = surface_prog_;
  set_common_uniforms(p, s, camera);
  glUniformMatrix4fv(p.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
  diffs_tex_.bind(2);
  coef_tex_.bind(3);
  glUniform1i(p.loc("u_diffs"), 2);
  glUniform1i(p.loc("u_coef"), 3);
  glUniform2f(p.loc("u_grid_origin"), static_cast<float>(grid_.x0), static_cast<float>(grid_.y0));
  glUniform2f(p.loc("u_grid_size"), static_cast<float>(grid_.cols), static_cast<float>(grid_.rows));
  glUniform1f(p.loc("u_dx"), static_cast<float>(grid_.dx));
  const ViewRays v = camera.rays();
  glUniform3f(p.loc("u_eye"), static_cast<float>(v.eye.x), static_cast<float>(v.eye.y), static_cast<float>(v.eye.z));
  glUniform1i(p.loc("u_ortho"), v.ortho ? 1 : 0);
  glUniform3f(p.loc("u_view_dir"), static_cast<float>(v.dir.x), static_cast<float>(v.dir.y),
              static_cast<float>(v.dir.z));
  glUniform1f(p.loc("u_index"), s.index);
  glUniform1i(p.loc("u_exact"), s.exact_refraction ? 1 : 0);
  glUniform1i(p.loc("u_fresnel"), static_cast<int>(s.fresnel));
  glUniform1i(p.loc("u_glint"), s.sun_glint ? 1 : 0);
  glUniform1i(p.loc("u_absorption"), s.absorption ? 1 : 0);
  glUniform3fv(p.loc("u_absorb"), 1, glm::value_ptr(s.absorb_rgb));
  glUniform3fv(p.loc("u_water_colour"), 1, glm::value_ptr(s.water_colour));
  glUniform3fv(p.loc("u_sky"), 1, glm::value_ptr(s.sky_colour));
  glUniform3fv(p.loc("u_sun_dir"), 1, glm::value_ptr(s.sun_dir));
  glUniform3fv(p.loc("u_sun_colour"), 1, glm::value_ptr(s.sun_colour));
  glBindVertexArray(surface_vao_);
  glDrawElements(GL_TRIANGLES, surface_index_count_, GL_UNSIGNED_INT, nullptr);
}

// The hulls at their poses (Wigley hulls below the waterline).
void WaterRenderer::draw_ships(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) {
  std::vector<float> tri;
  for (const ShipPose& sp : ships_) append_hull(sp, tri);
  ship_vertex_count_ = static_cast<GLsizei>(tri.size() / 3);
  glBindVertexArray(ship_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, ship_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(tri.size() * sizeof(float)), tri.data(), GL_STREAM_DRAW);
  ship_prog_.use();
  glUniformMatrix4fv(ship_prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
  glUniform3fv(ship_prog_.loc("u_sun_dir"), 1, glm::value_ptr(s.sun_dir));
  const glm::vec3 eye(camera.eye());
  glUniform3fv(ship_prog_.loc("u_eye"), 1, glm::value_ptr(eye));
  glDrawArrays(GL_TRIANGLES, 0, ship_vertex_count_);
}

void WaterRenderer::render(const OrbitCamera& camera, const RenderSettings& s, const RenderTarget& target) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  auto lap = [&](double& slot) {
    if (!times.enabled) return;
    glFinish();
    slot = elapsed_ms(t0);
    t0 = clock::now();
  };
  if (times.enabled) glFinish(), t0 = clock::now();

  // upload: view-dependent coefficients, ground texture, the frame's heights
  update_linearisation(camera, s.index);
  build_ground_texture(s);
  if (heights_dirty_) {
    diffs_tex_.upload(diffs_.data(), GL_RG, GL_FLOAT);
    glBindBuffer(GL_ARRAY_BUFFER, surface_h_vbo_);
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(mesh_h_.size() * sizeof(float)), mesh_h_.data());
    heights_dirty_ = false;
  }
  lap(times.upload);

  // caustics into their texture (lights the ground; flat light when off)
  const bool use_caustics = s.caustics && caustics_ && caustics_->available();
  if (use_caustics) caustics_->run(eta_, ships_, s);
  lap(times.caustics);

  const double aspect = static_cast<double>(target.width()) / target.height();
  const glm::mat4 mvp = mvp_of(camera, aspect);
  target.bind();
  // state other passes may have changed (the caustics pass blends, masks and uses its own viewport)
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glClearColor(s.clear_colour.r, s.clear_colour.g, s.clear_colour.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  ground_tex_.bind(0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, use_caustics ? caustics_->texture() : flat_light_tex_.id());

  if (s.draw_water) draw_surface(camera, s, mvp);
  lap(times.surface);

  if (s.draw_ship && !ships_.empty()) draw_ships(camera, s, mvp);
  lap(times.ship);
  // ground seen directly, drawn last so the depth test skips what the water and ships cover
  set_common_uniforms(ground_prog_, s, camera);
  glUniformMatrix4fv(ground_prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
  glBindVertexArray(ground_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 6);
  lap(times.ground);

  glBindVertexArray(0);
  glUseProgram(0);
  glActiveTexture(GL_TEXTURE0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("WaterRenderer::render");
}

}  // namespace huygens
