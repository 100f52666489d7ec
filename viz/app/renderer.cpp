#include "renderer.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <numbers>
#include <string>

#include "caustics_stage.hpp"
#include "plot.hpp"

namespace huygens {

// ---------------------------------------------------------------------------------
// RenderTarget

RenderTarget::RenderTarget(int width, int height, int samples)
    : color_(width, height, GL_RGBA8), hdr_(width, height, GL_RGBA16F), w_(width), h_(height) {
  color_.set_filter(GL_LINEAR, GL_LINEAR);
  hdr_.set_filter(GL_NEAREST, GL_NEAREST);
  GLint most = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &most);
  samples_ = std::clamp(samples, 1, static_cast<int>(most));
  const GLsizei n = samples_;
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_ > 1 ? n : 0, GL_DEPTH_COMPONENT24, width, height);
  glGenFramebuffers(1, &hdr_fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, hdr_fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, hdr_.id(), 0);
  if (samples_ == 1) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw gl::GlError("RenderTarget: incomplete half-float framebuffer");
  if (samples_ > 1) {
    glGenRenderbuffers(1, &ms_color_);
    glBindRenderbuffer(GL_RENDERBUFFER, ms_color_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_RGBA16F, width, height);
    glGenFramebuffers(1, &ms_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ms_color_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw gl::GlError("RenderTarget: incomplete multisampled framebuffer");
  }
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_.id(), 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw gl::GlError("RenderTarget: incomplete framebuffer");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("RenderTarget");
}

void RenderTarget::release() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (hdr_fbo_) glDeleteFramebuffers(1, &hdr_fbo_);
  if (ms_fbo_) glDeleteFramebuffers(1, &ms_fbo_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  if (ms_color_) glDeleteRenderbuffers(1, &ms_color_);
  depth_ = fbo_ = hdr_fbo_ = ms_fbo_ = ms_color_ = 0;
}

RenderTarget::~RenderTarget() { release(); }

RenderTarget::RenderTarget(RenderTarget&& o) noexcept
    : color_(std::move(o.color_)),
      hdr_(std::move(o.hdr_)),
      depth_(o.depth_),
      fbo_(o.fbo_),
      hdr_fbo_(o.hdr_fbo_),
      ms_fbo_(o.ms_fbo_),
      ms_color_(o.ms_color_),
      w_(o.w_),
      h_(o.h_),
      samples_(o.samples_) {
  o.depth_ = o.fbo_ = o.hdr_fbo_ = o.ms_fbo_ = o.ms_color_ = 0;
}

RenderTarget& RenderTarget::operator=(RenderTarget&& o) noexcept {
  if (this != &o) {
    release();
    color_ = std::move(o.color_);
    hdr_ = std::move(o.hdr_);
    depth_ = o.depth_;
    fbo_ = o.fbo_;
    hdr_fbo_ = o.hdr_fbo_;
    ms_fbo_ = o.ms_fbo_;
    ms_color_ = o.ms_color_;
    w_ = o.w_;
    h_ = o.h_;
    samples_ = o.samples_;
    o.depth_ = o.fbo_ = o.hdr_fbo_ = o.ms_fbo_ = o.ms_color_ = 0;
  }
  return *this;
}

void RenderTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo_ ? ms_fbo_ : hdr_fbo_);
  glViewport(0, 0, w_, h_);
}

void RenderTarget::resolve_scene() const {
  if (!ms_fbo_) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, ms_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, hdr_fbo_);
  glBlitFramebuffer(0, 0, w_, h_, 0, 0, w_, h_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
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

// CPU time of this process, all its threads (llvmpipe's rasteriser threads included) (unit: ms).
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Wigley hull triangles (world coordinates) of one ship, appended to `out` (x, y, z triples).
void append_hull(const ShipPose& s, std::vector<float>& out) {
  constexpr int ns = 24, nz = 6;
  const double freeboard = hull_freeboard(s);
  const double ch = std::cos(s.heading), sh = std::sin(s.heading);
  auto world = [&](double lx, double ly, double z) {  // afloat: sheared onto the plane of float_ship
    out.push_back(static_cast<float>(s.x + ch * lx - sh * ly));
    out.push_back(static_cast<float>(s.y + sh * lx + ch * ly));
    out.push_back(static_cast<float>(z + s.heave + s.slope_along * lx + s.slope_across * ly));
  };
  // half-width at station x in [-L/2, L/2] and height z in [-T, F]: the Wigley hull below the
  // waterline, topsides flaring out by 12 % to the deck (so that they show from above)
  auto half = [&](double lx, double z) {
    const double xi = 2.0 * lx / s.length;
    const double zz = z < 0.0 ? z / s.draft : 0.0, flare = z > 0.0 ? 1.0 + 0.12 * z / freeboard : 1.0;
    return 0.5 * s.beam * (1.0 - xi * xi) * (1.0 - zz * zz) * flare;
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
  // deck at the freeboard height, crowned: its centre line 8 % of the beam higher (two faces
  // across, lit differently)
  const double crown = 0.08 * s.beam;
  for (int i = 0; i < ns; ++i) {
    const double x0 = px(i), x1 = px(i + 1), f = freeboard;
    const double w0 = half(x0, f), w1 = half(x1, f);
    const double c0 = f + crown * (1.0 - std::pow(2.0 * x0 / s.length, 2)),
                 c1 = f + crown * (1.0 - std::pow(2.0 * x1 / s.length, 2));
    for (int side = -1; side <= 1; side += 2) {
      world(x0, side * w0, f), world(x1, side * w1, f), world(x1, 0.0, c1);
      world(x0, side * w0, f), world(x1, 0.0, c1), world(x0, 0.0, c0);
    }
  }
}

// The grid points under the ships' waterlines (1 there, else 0): in the ship's frame (lx along
// the heading) a Wigley hull's waterline is |ly| <= B/2 (1 - (2 lx / L)^2), |lx| <= L/2.
void mark_hulls(const GridPlacement& g, std::span<const ShipPose> ships, std::vector<std::uint8_t>& out) {
  out.assign(g.rows * g.cols, 0);
  for (const ShipPose& s : ships) {
    const double ch = std::cos(s.heading), sh = std::sin(s.heading), reach = 0.5 * std::max(s.length, s.beam);
    const auto lo = [&](double v, double v0) { return static_cast<long>(std::floor((v - reach - v0) / g.dx)); };
    const auto hi = [&](double v, double v0) { return static_cast<long>(std::ceil((v + reach - v0) / g.dx)); };
    for (long i = std::max(0L, lo(s.y, g.y0)); i <= std::min(static_cast<long>(g.rows) - 1, hi(s.y, g.y0)); ++i)
      for (long j = std::max(0L, lo(s.x, g.x0)); j <= std::min(static_cast<long>(g.cols) - 1, hi(s.x, g.x0)); ++j) {
        const double dx = g.x(static_cast<std::size_t>(j)) - s.x, dy = g.y(static_cast<std::size_t>(i)) - s.y;
        const double lx = ch * dx + sh * dy, ly = -sh * dx + ch * dy, xi = 2.0 * lx / s.length;
        if (std::abs(xi) <= 1.0 && std::abs(ly) <= 0.5 * s.beam * (1.0 - xi * xi))
          out[static_cast<std::size_t>(i) * g.cols + static_cast<std::size_t>(j)] = 1;
      }
  }
}

}  // namespace

void float_ship(const GridPlacement& g, std::span<const float> eta, ShipPose& s) {
  // eta at (x, y), bilinear; false outside the grid's points
  const auto at = [&](double x, double y, double& v) {
    const double fx = (x - g.x0) / g.dx, fy = (y - g.y0) / g.dx;
    if (!(fx >= 0.0 && fy >= 0.0 && fx <= g.cols - 1.0 && fy <= g.rows - 1.0)) return false;
    const std::size_t c = std::min(static_cast<std::size_t>(fx), g.cols - 2),
                      r = std::min(static_cast<std::size_t>(fy), g.rows - 2);
    const double tx = fx - c, ty = fy - r;
    const auto e = [&](std::size_t i, std::size_t j) { return static_cast<double>(eta[i * g.cols + j]); };
    v = (1 - ty) * ((1 - tx) * e(r, c) + tx * e(r, c + 1)) + ty * ((1 - tx) * e(r + 1, c) + tx * e(r + 1, c + 1));
    return true;
  };
  // eta = a + b u + c w in the ship's frame (u along the heading, w across), normal equations
  double n = 0, su = 0, sw = 0, se = 0, suu = 0, sww = 0, suw = 0, sue = 0, swe = 0;
  const double ch = std::cos(s.heading), sh = std::sin(s.heading);
  for (const double rho : {0.6, 0.7, 0.8})
    for (int k = 0; k < 48; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / 48, u = rho * s.length * std::cos(phi),
                   w = rho * s.length * std::sin(phi);
      double v = 0.0;
      if (!at(s.x + ch * u - sh * w, s.y + sh * u + ch * w, v)) continue;
      n += 1, su += u, sw += w, se += v, suu += u * u, sww += w * w, suw += u * w, sue += u * v, swe += w * v;
    }
  s.heave = s.slope_along = s.slope_across = 0.0;
  if (n < 3) return;
  const glm::dmat3 m(n, su, sw, su, suu, suw, sw, suw, sww);  // symmetric
  if (std::abs(glm::determinant(m)) < 1e-12 * n * n * n * std::pow(s.length, 4)) return;
  const glm::dvec3 abc = glm::inverse(m) * glm::dvec3(se, sue, swe);
  s.slope_along = std::clamp(abc.y, -0.3, 0.3);
  s.slope_across = std::clamp(abc.z, -0.3, 0.3);
  s.heave = abc.x;
}

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
  background_prog_ = load_program("background.vert", "background.frag", true);
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
  // ground: one large floor quad, 5 times the region's longer side, centred on the visible region
  // (vertices 0-5); then the floor under the region and a deck at the rest level around it,
  // 2 extents wide (vertices 6-35, RenderSettings::pool_deck)
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
  // deck: south, north, west, east, reaching 1.5 cells under the water's outline so that no
  // gap opens between its edge and a wave trough there (vertices 12-35); over terrain the deck
  // ends at the outline (vertices 36-59): there the water and the bed may lie below the rest
  // level near the edge, and a deck reaching in hid them (a strip of deck inside the flood's
  // near edge until 2026-12-04)
  for (const float o : {static_cast<float>(1.5 * grid_.dx), 0.0f}) {
    quad(gx0, gy0, gx1, ay + o, 0.0f);
    quad(gx0, by - o, gx1, gy1, 0.0f);
    quad(gx0, ay + o, ax + o, by - o, 0.0f);
    quad(bx - o, ay + o, gx1, by - o, 0.0f);
  }
  glGenVertexArrays(1, &ground_vao_);
  glBindVertexArray(ground_vao_);
  glGenBuffers(1, &ground_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, ground_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(quads.size() * sizeof(float)), quads.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glGenVertexArrays(1, &empty_vao_);
  tone_prog_ = gl::program_from_strings(gl::fullscreen_vertex_shader(), gl::shader_source("tonemap.frag"), "tonemap");

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
  GLuint bufs[] = {surface_static_vbo_, surface_h_vbo_, surface_lin_vbo_, surface_ibo_,
                   ground_vbo_,         ship_vbo_,      terrain_vbo_};
  glDeleteBuffers(7, bufs);
  if (sea_sampler_ != 0) glDeleteSamplers(1, &sea_sampler_);
  GLuint vaos[] = {surface_vao_, ground_vao_, ship_vao_, empty_vao_, terrain_vao_};
  glDeleteVertexArrays(5, vaos);
  if (GLenum e = glGetError(); e != GL_NO_ERROR) std::fprintf(stderr, "~WaterRenderer: GL error 0x%04X\n", e);
}

double WaterRenderer::tile_m() const {
  const double want = static_cast<double>(std::max(grid_.cols, grid_.rows)) * grid_.dx / 8.0;
  const double decade = std::pow(10.0, std::floor(std::log10(want)));
  double best = decade;
  for (const double m : {2.0, 5.0, 10.0})
    if (std::abs(std::log(m * decade / want)) < std::abs(std::log(best / want))) best = m * decade;
  return best;
}

void WaterRenderer::set_heights(std::span<const float> eta) {
  const auto t0 = std::chrono::steady_clock::now();
  const float off = offset_;
  std::transform(eta.begin(), eta.end(), eta_.begin(), [off](float v) { return v - off; });
  // inside an obstacle the solver's height is meaningless (dry cells, an empty column): the
  // nearest water point's height closes the surface around the solid drawn there
  if (!fill_from_.empty())
    for (std::size_t k = 0; k < eta_.size(); ++k)
      if (fill_from_[k] != k) eta_[k] = eta_[fill_from_[k]];
  // over a mesh obstacle the surface is not below the solid's top (a dry column there, which an
  // SPH solver reports as height 0, lies just inside the solid and is hidden by it), unless the
  // water at the nearest point outside its footprint is lower: a solid standing in shallower
  // water or on a dry floor keeps its footprint's own height (until 2026-12-04 a dry wedge got a
  // one-cell ring of water round its foot, the surface sloping down from its top)
  if (!mesh_top_.empty() && !mesh_from_.empty()) {
    const float inset = static_cast<float>(0.25 * grid_.dx);
    for (std::size_t k = 0; k < eta_.size(); ++k)
      eta_[k] = std::max(eta_[k], std::min(mesh_top_[k] - inset, eta_[mesh_from_[k]]));
  }
  subsample_heights(eta_, grid_.rows, grid_.cols, static_cast<std::size_t>(subsample_), layout_, mesh_h_);
  height_differences(eta_, grid_.rows, grid_.cols, diffs_);
  heights_dirty_ = true;
  times.prepare = elapsed_ms(t0);
}

bool WaterRenderer::upload_grid_field(std::span<const float> values, gl::Texture& tex) const {
  if (values.size() != grid_.rows * grid_.cols) return false;
  if (tex.width() != static_cast<int>(grid_.cols)) {
    tex = gl::Texture(static_cast<int>(grid_.cols), static_cast<int>(grid_.rows), GL_R32F);
    tex.set_filter(GL_LINEAR, GL_LINEAR);
  }
  tex.upload(values.data(), GL_RED, GL_FLOAT);
  return true;
}

void WaterRenderer::set_dye(std::span<const float> dye) { has_dye_ = upload_grid_field(dye, dye_tex_); }

void WaterRenderer::set_foam(std::span<const float> foam) { has_foam_ = upload_grid_field(foam, foam_tex_); }

void WaterRenderer::set_bed(std::span<const float> bed) {
  has_bed_ = bed.size() == grid_.rows * grid_.cols;
  if (!has_bed_) return;
  std::vector<float> z(bed.begin(), bed.end());
  for (float& b : z) b -= offset_;
  bed_tex_ = gl::Texture(static_cast<int>(grid_.cols), static_cast<int>(grid_.rows), GL_R32F);
  bed_tex_.set_filter(GL_LINEAR, GL_LINEAR);
  bed_tex_.upload(z.data(), GL_RED, GL_FLOAT);
  // the terrain: the surface mesh's points at the bed's height, the surface's triangles
  std::vector<float> xyz;
  for (std::size_t l = 0; l < layout_.vertex_rows(); ++l)
    for (std::size_t k = 0; k < layout_.vertex_cols(); ++k)
      xyz.insert(xyz.end(),
                 {static_cast<float>(grid_.x(layout_.col_idx[k])), static_cast<float>(grid_.y(layout_.row_idx[l])),
                  z[layout_.row_idx[l] * grid_.cols + layout_.col_idx[k]]});
  if (terrain_vao_ == 0) glGenVertexArrays(1, &terrain_vao_), glGenBuffers(1, &terrain_vbo_);
  glBindVertexArray(terrain_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, terrain_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(xyz.size() * sizeof(float)), xyz.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, surface_ibo_);
  glBindVertexArray(0);
  gl::check("WaterRenderer::set_bed");
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
        // sandy tiles with darker grout lines, a tone per tile (no per-texel grain: it made
        // every picture incompressible and hid the caustics' fine detail)
        const float fx = static_cast<float>(x * sq % n) / n, fy = static_cast<float>(y * sq % n) / n;
        const bool grout = fx < 0.03f || fy < 0.03f;
        const float tone = 0.9f + 0.1f * hash01(static_cast<std::uint32_t>(cx), static_cast<std::uint32_t>(cy));
        c = grout ? glm::vec3(0.35f, 0.32f, 0.28f)
                  : tone * (((cx + cy) % 2 == 0) ? glm::vec3(0.86f, 0.78f, 0.60f) : glm::vec3(0.74f, 0.66f, 0.50f));
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

void WaterRenderer::set_ambient_sea(const RenderAmbientSea& sea) {
  sea_ = sea.slopes;
  const int n = sea_->n();
  sea_time_ = std::numeric_limits<double>::quiet_NaN();
  // every level down to 1 x 1: far away a texel averages the slopes (the sea flattens to its mean
  // colour instead of aliasing); anisotropic where the driver offers it (grazing views)
  sea_tex_ = gl::Texture(n, n, GL_RGBA32F, static_cast<int>(std::bit_width(static_cast<unsigned>(n))));
  sea_texels_.assign(4 * static_cast<std::size_t>(n) * n, 0.0f);
  // Cox & Munk's mean square slope less what the texture's slopes resolve (spectral) and what
  // the region's normals resolve (central differences of the heights on the same grid); both
  // are constant in time (each mode's amplitude is)
  const double cox_munk = 0.003 + 5.12e-3 * sea.wind_speed_mps;
  sea_unresolved_var_ = std::max(cox_munk - sea_->mean_square_slope(false), 0.0);
  region_unresolved_var_ = std::max(cox_munk - sea_->mean_square_slope(true), 0.0);
  sea_tex_.set_filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  sea_tex_.set_wrap(GL_REPEAT);
  if (epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic")) {
    GLfloat most = 1.0f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &most);
    glBindTexture(GL_TEXTURE_2D, sea_tex_.id());
    glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY_EXT, std::min(most, 16.0f));
  }
  // the sea out to the horizon (background.frag) samples the slopes without anisotropic
  // filtering: at its footprints llvmpipe's took 1.4 s for a 1280x720 frame
  if (sea_sampler_ == 0) glGenSamplers(1, &sea_sampler_);
  glSamplerParameteri(sea_sampler_, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glSamplerParameteri(sea_sampler_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(sea_sampler_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glSamplerParameteri(sea_sampler_, GL_TEXTURE_WRAP_T, GL_REPEAT);
  set_sea_time(0.0);
}

// The ambient sea's slopes at the requested time, when this picture draws them and they are not
// already there.
void WaterRenderer::update_sea_slopes(const RenderSettings& s) {
  const double t = sea_request_;
  if (!sea_ || !s.deep_water || !s.ambient_sea || t == sea_time_ || !std::isfinite(t)) return;
  // the squares' sum too: the mipmap's averages of it give the slopes' variance in a texel
  const std::span<const float> slopes = sea_->compute(t);
  for (std::size_t i = 0; i < slopes.size() / 2; ++i) {
    const float sx = slopes[2 * i], sy = slopes[2 * i + 1];
    sea_texels_[4 * i] = sx, sea_texels_[4 * i + 1] = sy, sea_texels_[4 * i + 2] = sx * sx + sy * sy;
  }
  sea_tex_.upload(sea_texels_.data(), GL_RGBA, GL_FLOAT, 0);
  glBindTexture(GL_TEXTURE_2D, sea_tex_.id());
  glGenerateMipmap(GL_TEXTURE_2D);
  sea_time_ = t;
}

namespace {

// Per grid point (R x C, row-major) the nearest point outside `solid` (itself when outside):
// multi-source breadth-first search over the 4-neighbourhood. Empty when every point is solid.
std::vector<std::uint32_t> nearest_outside(std::vector<std::uint8_t> solid, std::size_t R, std::size_t C) {
  std::vector<std::uint32_t> from(R * C);
  std::vector<std::size_t> queue;
  for (std::size_t k = 0; k < R * C; ++k) {
    from[k] = static_cast<std::uint32_t>(k);
    if (!solid[k]) queue.push_back(k);
  }
  if (queue.empty()) return {};
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t k = queue[head], i = k / C, j = k % C;
    const std::size_t nb[4] = {i > 0 ? k - C : k, i + 1 < R ? k + C : k, j > 0 ? k - 1 : k, j + 1 < C ? k + 1 : k};
    for (std::size_t m : nb)
      if (solid[m]) {
        solid[m] = 0;
        from[m] = from[k];
        queue.push_back(m);
      }
  }
  return from;
}

}  // namespace

// A mesh obstacle (RenderObstacle::Kind::mesh): its triangles among the solids, and per grid
// point the highest z of the mesh above it (mesh_top_; the water surface is kept at least that
// high, set_heights) and the outline of its footprint (mesh_outline_, grey in the plan view).
void WaterRenderer::add_mesh_solids(std::span<const RenderObstacle> obstacles) {
  const std::size_t R = grid_.rows, C = grid_.cols;
  for (const RenderObstacle& o : obstacles) {
    if (o.kind != RenderObstacle::Kind::mesh) continue;
    if (mesh_top_.empty()) mesh_top_.assign(R * C, -std::numeric_limits<float>::infinity());
    const std::vector<float>& t = o.triangles_m;
    for (std::size_t k = 0; k + 9 <= t.size(); k += 9) {
      for (int c = 0; c < 3; ++c)
        solids_.insert(solids_.end(), {t[k + 3 * c], t[k + 3 * c + 1], t[k + 3 * c + 2] - offset_});
      // the triangle's plane over the grid points its xy projection covers (barycentric weights)
      const glm::dvec3 a(t[k], t[k + 1], t[k + 2]), b(t[k + 3], t[k + 4], t[k + 5]), c(t[k + 6], t[k + 7], t[k + 8]);
      const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      if (std::abs(det) < 1e-12) continue;  // a vertical face covers no area seen from above
      for (std::size_t i = 0; i < R; ++i)
        for (std::size_t j = 0; j < C; ++j) {
          const double x = grid_.x(j), y = grid_.y(i);
          const double wb = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
          const double wc = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
          if (wb < 0.0 || wc < 0.0 || wb + wc > 1.0) continue;
          const double z = a.z + wb * (b.z - a.z) + wc * (c.z - a.z) - offset_;
          mesh_top_[i * C + j] = std::max(mesh_top_[i * C + j], static_cast<float>(z));
        }
    }
  }
  if (mesh_top_.empty()) return;
  std::vector<std::uint8_t> footprint(R * C);
  for (std::size_t k = 0; k < R * C; ++k) footprint[k] = std::isfinite(mesh_top_[k]);
  mesh_from_ = nearest_outside(footprint, R, C);
  mesh_outline_.assign(R * C, 0);
  auto in = [&](std::size_t i, std::size_t j) { return std::isfinite(mesh_top_[i * C + j]); };
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t j = 0; j < C; ++j)
      mesh_outline_[i * C + j] = in(i, j) && (i == 0 || j == 0 || i + 1 == R || j + 1 == C || !in(i - 1, j) ||
                                              !in(i + 1, j) || !in(i, j - 1) || !in(i, j + 1));
}

void WaterRenderer::set_obstacles(std::span<const RenderObstacle> obstacles) {
  solids_.clear();
  fill_from_.clear();
  mesh_top_.clear();
  mesh_from_.clear();
  mesh_outline_.clear();
  add_mesh_solids(obstacles);
  if (std::none_of(obstacles.begin(), obstacles.end(),
                   [](const RenderObstacle& o) { return o.kind != RenderObstacle::Kind::mesh; }))
    return;
  add_prism_solids(obstacles);
  fill_footprints(obstacles);
}

// Boxes and cylinders as solids (triangles in solids_).
void WaterRenderer::add_prism_solids(std::span<const RenderObstacle> obstacles) {
  // solids: from the floor (or the obstacle's bottom) to its top, or for a 2D solver's
  // obstacle (infinite z) to a quarter of the depth above the water at rest; over terrain
  // (set_bed first), where water runs deeper than the rest level, at least 3 % of the region's
  // size (houses in a flood)
  const double extent = std::max(grid_.cols, grid_.rows) * grid_.dx;
  const double floor_z = ground_z_, rise = std::max(0.25 * std::abs(ground_z_), has_bed_ ? 0.03 * extent : 0.0);
  auto zr = [&](double z, double fallback) { return std::isfinite(z) ? z - offset_ : fallback; };
  auto tri = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    for (const glm::dvec3& p : {a, b, c})
      solids_.insert(solids_.end(), {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  };
  auto wall = [&](glm::dvec2 p, glm::dvec2 q, double z0, double z1) {
    tri({p, z0}, {q, z0}, {q, z1});
    tri({p, z0}, {q, z1}, {p, z1});
  };
  const double gx1 = grid_.x0 + (grid_.cols - 1) * grid_.dx, gy1 = grid_.y0 + (grid_.rows - 1) * grid_.dx;
  for (const RenderObstacle& o : obstacles) {
    if (o.kind == RenderObstacle::Kind::mesh) continue;  // add_mesh_solids
    const double z0 = std::max(zr(o.z0_m, floor_z), floor_z), z1 = zr(o.z1_m, rise);
    if (o.kind == RenderObstacle::Kind::box) {
      // clipped to the visible region (a wall along the domain's edge stays inside it)
      const double x0 = std::max(o.min_m[0], grid_.x0 - 0.5 * grid_.dx),
                   x1 = std::min(o.max_m[0], gx1 + 0.5 * grid_.dx);
      const double y0 = std::max(o.min_m[1], grid_.y0 - 0.5 * grid_.dx),
                   y1 = std::min(o.max_m[1], gy1 + 0.5 * grid_.dx);
      const double b0 = std::max(zr(o.min_m[2], floor_z), floor_z), b1 = zr(o.max_m[2], rise);
      if (x1 <= x0 || y1 <= y0) continue;
      const glm::dvec2 c[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
      for (int k = 0; k < 4; ++k) wall(c[k], c[(k + 1) % 4], b0, b1);
      tri({c[0], b1}, {c[1], b1}, {c[2], b1});
      tri({c[0], b1}, {c[2], b1}, {c[3], b1});
    } else {
      constexpr int n = 48;
      const glm::dvec2 ctr(o.centre_m[0], o.centre_m[1]);
      for (int k = 0; k < n; ++k) {
        const double a0 = 2.0 * std::numbers::pi * k / n, a1 = 2.0 * std::numbers::pi * (k + 1) / n;
        const glm::dvec2 p = ctr + o.radius_m * glm::dvec2(std::cos(a0), std::sin(a0));
        const glm::dvec2 q = ctr + o.radius_m * glm::dvec2(std::cos(a1), std::sin(a1));
        wall(p, q, z0, z1);
        tri({ctr, z1}, {p, z1}, {q, z1});
      }
    }
  }
}

// The grid points under a box or cylinder take a height from outside (fill_from_).
void WaterRenderer::fill_footprints(std::span<const RenderObstacle> obstacles) {
  // the grid points inside an obstacle's footprint take the height of the nearest point
  // outside all of them (multi-source breadth-first search over the 4-neighbourhood)
  const std::size_t R = grid_.rows, C = grid_.cols;
  std::vector<std::uint8_t> solid(R * C, 0);
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t j = 0; j < C; ++j) {
      const double x = grid_.x(j), y = grid_.y(i);
      for (const RenderObstacle& o : obstacles) {
        if (o.kind == RenderObstacle::Kind::mesh) continue;  // the surface runs over it (mesh_top_)
        const bool in = o.kind == RenderObstacle::Kind::box
                            ? x >= o.min_m[0] && x <= o.max_m[0] && y >= o.min_m[1] && y <= o.max_m[1]
                            : std::hypot(x - o.centre_m[0], y - o.centre_m[1]) <= o.radius_m + 0.5 * grid_.dx;
        if (in) solid[i * C + j] = 1;
      }
    }
  fill_from_ = nearest_outside(solid, R, C);
}

// The water's sides: the mesh's outline down to the floor (seen where no deck hides them: a
// quasi-2D slab from the side shows its profile), flat-shaded in the water's colour.
void WaterRenderer::draw_water_sides(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) {
  const std::size_t vr = layout_.vertex_rows(), vc = layout_.vertex_cols();
  std::vector<float> tri;
  auto edge = [&](std::size_t a, std::size_t b, double xa, double ya, double xb, double yb) {
    const float ha = mesh_h_[a], hb = mesh_h_[b], z0 = static_cast<float>(ground_z_);
    // where the surface is left out as dry (thinner than kDryDepth), so is its side: a film's side
    // was a dark line along the floor past the surge's toe
    if (s.hide_dry && ha - z0 < kDryDepth && hb - z0 < kDryDepth) return;
    const float p[4][3] = {{static_cast<float>(xa), static_cast<float>(ya), z0},
                           {static_cast<float>(xb), static_cast<float>(yb), z0},
                           {static_cast<float>(xb), static_cast<float>(yb), hb},
                           {static_cast<float>(xa), static_cast<float>(ya), ha}};
    for (int k : {0, 1, 2, 0, 2, 3}) tri.insert(tri.end(), p[k], p[k] + 3);
  };
  for (std::size_t k = 0; k + 1 < vc; ++k) {
    const double x0 = grid_.x(layout_.col_idx[k]), x1 = grid_.x(layout_.col_idx[k + 1]);
    edge(k, k + 1, x0, grid_.y(layout_.row_idx[0]), x1, grid_.y(layout_.row_idx[0]));
    const std::size_t top = (vr - 1) * vc;
    edge(top + k, top + k + 1, x0, grid_.y(layout_.row_idx[vr - 1]), x1, grid_.y(layout_.row_idx[vr - 1]));
  }
  for (std::size_t l = 0; l + 1 < vr; ++l) {
    const double y0 = grid_.y(layout_.row_idx[l]), y1 = grid_.y(layout_.row_idx[l + 1]);
    edge(l * vc, (l + 1) * vc, grid_.x(layout_.col_idx[0]), y0, grid_.x(layout_.col_idx[0]), y1);
    edge(l * vc + vc - 1, (l + 1) * vc + vc - 1, grid_.x(layout_.col_idx[vc - 1]), y0, grid_.x(layout_.col_idx[vc - 1]),
         y1);
  }
  draw_flat(tri, FlatKind::water_side, camera, s, mvp);
}

// Triangles (x, y, z per vertex) in the ship program, flat-shaded in the colour of `kind`.
void WaterRenderer::draw_flat(const std::vector<float>& tri, FlatKind kind, const OrbitCamera& camera,
                              const RenderSettings& s, const glm::mat4& mvp) {
  glBindVertexArray(ship_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, ship_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(tri.size() * sizeof(float)), tri.data(), GL_STREAM_DRAW);
  ship_prog_.use();
  glUniformMatrix4fv(ship_prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
  glUniform3fv(ship_prog_.loc("u_sun_dir"), 1, glm::value_ptr(s.sun_dir));
  const glm::vec3 eye(camera.eye());
  glUniform3fv(ship_prog_.loc("u_eye"), 1, glm::value_ptr(eye));
  glUniform1i(ship_prog_.loc("u_solid"), static_cast<int>(kind));
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(tri.size() / 3));
  glUniform1i(ship_prog_.loc("u_solid"), 0);
}

void WaterRenderer::set_tank(const std::array<double, 3>& box_m) { tank_ = box_m; }

// The tank's side walls (set_tank) the eye is inside of, from the floor to the lid.
void WaterRenderer::draw_tank(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) {
  if (tank_[0] <= 0.0) return;
  const glm::dvec3 eye = camera.eye();
  const float X = static_cast<float>(tank_[0]), Y = static_cast<float>(tank_[1]);
  const float z0 = static_cast<float>(ground_z_), z1 = static_cast<float>(tank_[2]) - offset_;
  std::vector<float> tri;
  auto wall = [&](float ax, float ay, float bx, float by) {
    const float p[4][3] = {{ax, ay, z0}, {bx, by, z0}, {bx, by, z1}, {ax, ay, z1}};
    for (int k : {0, 1, 2, 0, 2, 3}) tri.insert(tri.end(), p[k], p[k] + 3);
  };
  if (eye.y > 0.0) wall(0, 0, X, 0);
  if (eye.y < Y) wall(0, Y, X, Y);
  if (eye.x > 0.0) wall(0, 0, 0, Y);
  if (eye.x < X) wall(X, 0, X, Y);
  draw_flat(tri, FlatKind::tank_wall, camera, s, mvp);
}

// Obstacles as solids (flat-shaded, the ship program's solid colour).
void WaterRenderer::draw_solids(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) {
  if (solids_.empty() || !s.draw_solids) return;
  draw_flat(solids_, FlatKind::obstacle, camera, s, mvp);
}

// The half-float scene into the 8-bit image, tone-mapped once (renderer.hpp).
void WaterRenderer::tone_map(const RenderSettings& s, const RenderTarget& target) {
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo());
  glViewport(0, 0, target.width(), target.height());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  tone_prog_.use();
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, target.hdr().id());
  glUniform1i(tone_prog_.loc("u_hdr"), 0);
  glUniform1i(tone_prog_.loc("u_on"), s.tone_map ? 1 : 0);
  glUniform1f(tone_prog_.loc("u_knee"), s.tone_knee);
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void WaterRenderer::set_common_uniforms(const gl::Program& p, const RenderSettings& s,
                                        const OrbitCamera& camera) const {
  p.use();
  const ViewRays v = camera.rays();
  glUniform3f(p.loc("u_eye"), static_cast<float>(v.eye.x), static_cast<float>(v.eye.y), static_cast<float>(v.eye.z));
  glUniform1i(p.loc("u_ortho"), v.ortho ? 1 : 0);
  glUniform3f(p.loc("u_view_dir"), static_cast<float>(v.dir.x), static_cast<float>(v.dir.y),
              static_cast<float>(v.dir.z));
  glUniform1f(p.loc("u_index"), s.index);
  glUniform3fv(p.loc("u_water_colour"), 1, glm::value_ptr(s.water_colour));
  glUniform3fv(p.loc("u_sky"), 1, glm::value_ptr(s.sky_colour));
  glUniform1i(p.loc("u_sky_gradient"), s.sky_gradient ? 1 : 0);
  glUniform3fv(p.loc("u_sky_zenith"), 1, glm::value_ptr(s.sky_zenith));
  glUniform3fv(p.loc("u_sun_dir"), 1, glm::value_ptr(s.sun_dir));
  glUniform1i(p.loc("u_deep"), s.deep_water ? 1 : 0);
  glUniform1i(p.loc("u_ground"), 0);
  glUniform1i(p.loc("u_caustics"), 1);
  if (s.ground == GroundPattern::tiles) {  // square tiles of tile_m() from the frame's origin
    const float e = static_cast<float>(std::max(1, s.ground_squares) * tile_m());
    glUniform2f(p.loc("u_ground_origin"), 0.0f, 0.0f);
    glUniform2f(p.loc("u_ground_extent"), e, e);
  } else {  // the pattern spans the visible region
    glUniform2f(p.loc("u_ground_origin"), static_cast<float>(grid_.x0), static_cast<float>(grid_.y0));
    glUniform2f(p.loc("u_ground_extent"), static_cast<float>(grid_.cols * grid_.dx),
                static_cast<float>(grid_.rows * grid_.dx));
  }
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
  // the floor under the visible region (walls beyond it when there is a deck)
  glUniform4f(p.loc("u_floor_rect"), static_cast<float>(grid_.x(0)), static_cast<float>(grid_.y(0)),
              static_cast<float>(grid_.x(grid_.cols - 1)), static_cast<float>(grid_.y(grid_.rows - 1)));
  glUniform1i(p.loc("u_deck"), s.pool_deck ? 1 : 0);
  glUniform1i(p.loc("u_fresnel"), static_cast<int>(s.fresnel));
  glUniform1i(p.loc("u_glint"), !s.sun_glint ? 0 : s.paper_glint ? 1 : 2);
  glUniform1f(p.loc("u_sun_radius"), s.sun_radius_rad);
  glUniform1f(p.loc("u_sun_irradiance"), s.sun_irradiance);
  // the wind's short waves: beyond the region those its texture does not resolve, in it
  // (u_region_var more) those its central differences do not
  const bool wind = sea_ && s.deep_water && s.ambient_sea;
  glUniform1f(p.loc("u_slope_var"), static_cast<float>(s.slope_var + (wind ? sea_unresolved_var_ : 0.0)));
  glUniform1f(p.loc("u_region_var"), static_cast<float>(wind ? region_unresolved_var_ - sea_unresolved_var_ : 0.0));
  glUniform3fv(p.loc("u_sun_colour"), 1, glm::value_ptr(s.sun_colour));
  // the sea beyond the region: the ambient sea's slopes, repeated every length_m from the full
  // grid's origin (texel centres at the grid points)
  const bool far = sea_ && s.deep_water && s.ambient_sea;
  glUniform1i(p.loc("u_far"), far ? 1 : 0);
  glUniform1i(p.loc("u_far_slopes"), 7);
  if (far) {
    sea_tex_.bind(7);
    const float L = static_cast<float>(sea_->length_m()), h = 0.5f * L / static_cast<float>(sea_->n());
    glUniform2f(p.loc("u_far_origin"), -h, -h);
    glUniform1f(p.loc("u_far_length"), L);
  }
}

// The water surface: the subsampled mesh with per-pixel normals, refraction, Fresnel, glint.
void WaterRenderer::draw_surface(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) const {
  const gl::Program& p = surface_prog_;
  set_common_uniforms(p, s, camera);
  glUniformMatrix4fv(p.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
  diffs_tex_.bind(2);
  const bool dye = s.dye && has_dye_;
  glUniform1i(p.loc("u_use_dye"), dye ? 1 : 0);
  glUniform1i(p.loc("u_dye"), 4);
  glUniform3fv(p.loc("u_dye_colour"), 1, glm::value_ptr(s.dye_colour));
  if (dye) dye_tex_.bind(4);
  const bool foam = s.foam && has_foam_;
  glUniform1i(p.loc("u_use_foam"), foam ? 1 : 0);
  glUniform1i(p.loc("u_foam"), 6);
  glUniform3fv(p.loc("u_foam_colour"), 1, glm::value_ptr(s.foam_colour));
  if (foam) foam_tex_.bind(6);
  coef_tex_.bind(3);
  glUniform1i(p.loc("u_use_bed"), has_bed_ ? 1 : 0);
  glUniform1i(p.loc("u_bed"), 5);
  glUniform1f(p.loc("u_dry_depth"), kDryDepth);
  glUniform1i(p.loc("u_hide_dry"), s.hide_dry ? 1 : 0);
  if (has_bed_) bed_tex_.bind(5);
  glUniform1i(p.loc("u_diffs"), 2);
  glUniform1i(p.loc("u_coef"), 3);
  glUniform2f(p.loc("u_grid_origin"), static_cast<float>(grid_.x0), static_cast<float>(grid_.y0));
  glUniform2f(p.loc("u_grid_size"), static_cast<float>(grid_.cols), static_cast<float>(grid_.rows));
  glUniform1f(p.loc("u_dx"), static_cast<float>(grid_.dx));
  glUniform1i(p.loc("u_exact"), s.exact_refraction ? 1 : 0);
  glUniform1i(p.loc("u_absorption"), s.absorption ? 1 : 0);
  glUniform3fv(p.loc("u_absorb"), 1, glm::value_ptr(s.absorb_rgb));
  glBindVertexArray(surface_vao_);
  glDrawElements(GL_TRIANGLES, surface_index_count_, GL_UNSIGNED_INT, nullptr);
}

// The bed as terrain (set_bed), lit with its slope, and the deck around it (no flat floor).
void WaterRenderer::draw_terrain(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) {
  set_common_uniforms(ground_prog_, s, camera);
  glUniformMatrix4fv(ground_prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
  glUniform1i(ground_prog_.loc("u_terrain"), 1);
  glBindVertexArray(terrain_vao_);
  glDrawElements(GL_TRIANGLES, surface_index_count_, GL_UNSIGNED_INT, nullptr);
  glUniform1i(ground_prog_.loc("u_terrain"), 0);
  if (s.pool_deck) {
    glBindVertexArray(ground_vao_);
    glDrawArrays(GL_TRIANGLES, 36, 24);  // the deck that ends at the outline
  }
}

// What no geometry covered (drawn last, at the far plane): the sky, or below the horizon the open
// sea or the pool's deck going on to it (shaders/background.frag).
void WaterRenderer::draw_background(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) const {
  const gl::Program& p = background_prog_;
  set_common_uniforms(p, s, camera);
  glUniformMatrix4fv(p.loc("u_inv_vp"), 1, GL_FALSE, glm::value_ptr(glm::inverse(mvp)));
  glBindSampler(7, sea_sampler_);  // 0 (the texture's own) without an ambient sea
  glDepthFunc(GL_LEQUAL);
  glBindVertexArray(empty_vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_LESS);
  glBindSampler(7, 0);
}

// The hulls at their poses (Wigley hulls below the waterline).
void WaterRenderer::draw_ships(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) {
  std::vector<float> tri;
  for (ShipPose sp : ships_) {
    float_ship(grid_, eta_, sp);
    append_hull(sp, tri);
  }
  draw_flat(tri, FlatKind::hull, camera, s, mvp);
}

// The frame's uploads: view-dependent coefficients, ground texture, the sea's slopes, the heights.
void WaterRenderer::upload_frame(const OrbitCamera& camera, const RenderSettings& s) {
  update_linearisation(camera, s.index);
  build_ground_texture(s);
  update_sea_slopes(s);
  if (!heights_dirty_) return;
  diffs_tex_.upload(diffs_.data(), GL_RG, GL_FLOAT);
  glBindBuffer(GL_ARRAY_BUFFER, surface_h_vbo_);
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(mesh_h_.size() * sizeof(float)), mesh_h_.data());
  heights_dirty_ = false;
}

// The state other passes may have changed (the caustics pass blends, masks and uses its own
// viewport), and a cleared target.
void WaterRenderer::reset_scene_state() {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

// The floor seen directly and the deck around the region (vertices 0-5 the large floor, 6-11 the
// region's floor, 12-35 the deck; deep water has no floor).
void WaterRenderer::draw_ground(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) {
  set_common_uniforms(ground_prog_, s, camera);
  glUniformMatrix4fv(ground_prog_.loc("u_mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
  glUniform1i(ground_prog_.loc("u_terrain"), 0);
  glBindVertexArray(ground_vao_);
  // the deck lies at the rest level and reaches under the water's outline: pushed back in depth
  // so that the water there wins the depth test instead of alternating with it (z-fighting)
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 2.0f);
  if (s.pool_deck)
    glDrawArrays(GL_TRIANGLES, s.deep_water ? 12 : 6, s.deep_water ? 24 : 30);
  else
    glDrawArrays(GL_TRIANGLES, 0, 6);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

void WaterRenderer::render(const OrbitCamera& camera, const RenderSettings& s, const RenderTarget& target) {
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  double c0 = process_cpu_ms();
  auto lap = [&](double& slot, double& cpu_slot) {
    if (!times.enabled) return;
    glFinish();
    slot = elapsed_ms(t0);
    cpu_slot = process_cpu_ms() - c0;
    t0 = clock::now();
    c0 = process_cpu_ms();
  };
  if (times.enabled) glFinish(), t0 = clock::now(), c0 = process_cpu_ms();

  upload_frame(camera, s);
  lap(times.upload, times.cpu.upload);

  // caustics into their texture (lights the ground; flat light when off)
  const bool use_caustics = s.caustics && caustics_ && caustics_->available();
  if (use_caustics) caustics_->run(eta_, ships_, s);
  lap(times.caustics, times.cpu.caustics);

  const double aspect = static_cast<double>(target.width()) / target.height();
  const glm::mat4 mvp = mvp_of(camera, aspect);
  target.bind();
  // state other passes may have changed (the caustics pass blends, masks and uses its own viewport)
  reset_scene_state();
  ground_tex_.bind(0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, use_caustics ? caustics_->texture() : flat_light_tex_.id());

  if (s.draw_water) draw_surface(camera, s, mvp);
  if (s.draw_water && !s.deep_water) draw_water_sides(camera, s, mvp);
  lap(times.surface, times.cpu.surface);

  if (s.draw_ship && !ships_.empty()) draw_ships(camera, s, mvp);
  draw_solids(camera, s, mvp);
  draw_tank(camera, s, mvp);
  lap(times.ship, times.cpu.ship);
  // ground seen directly, drawn after the water and ships so the depth test skips what they
  // cover; deep water has no floor, only the sea (the deck) around the region
  if (has_bed_) {
    draw_terrain(camera, s, mvp);
  } else if (!s.deep_water || s.pool_deck) {
    draw_ground(camera, s, mvp);
  }
  draw_background(camera, s, mvp);
  lap(times.ground, times.cpu.ground);
  target.resolve_scene();
  tone_map(s, target);
  lap(times.tonemap, times.cpu.tonemap);

  glBindVertexArray(0);
  glUseProgram(0);
  glActiveTexture(GL_TEXTURE0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("WaterRenderer::render");
}

void WaterRenderer::render_plan(std::span<const float> values, const std::string& quantity, double unit_scale,
                                const std::string& unit, bool diverging, const std::string& title,
                                const RenderTarget& target, std::optional<glm::vec3> hue) {
  const std::size_t R = grid_.rows, C = grid_.cols;
  // the colour range: symmetric about 0 (heights) or from the minimum (depths), rounded out to
  // the colour bar's ticks; obstacles (fill_from_) and the ships' waterlines are grey (the dent
  // under a hull sets no range), NaN values (dry land) sand
  std::vector<std::uint8_t> hull;
  mark_hulls(grid_, ships_, hull);
  double lo = 1e300, hi = -1e300;
  for (std::size_t k = 0; k < R * C; ++k) {
    if ((!fill_from_.empty() && fill_from_[k] != k) || !std::isfinite(values[k]) || hull[k]) continue;
    if (!mesh_outline_.empty() && mesh_outline_[k]) continue;
    lo = std::min(lo, unit_scale * values[k]);
    hi = std::max(hi, unit_scale * values[k]);
  }
  PlotSpec spec;
  spec.x0_m = grid_.x0 - 0.5 * grid_.dx, spec.y0_m = grid_.y0 - 0.5 * grid_.dx;  // the corner of cell (0, 0)
  spec.width_m = C * grid_.dx, spec.height_m = R * grid_.dx;
  spec.quantity = quantity, spec.unit = unit, spec.title = title;
  plot_range(lo, hi, diverging, spec);
  spec.hue = hue;
  std::vector<std::uint8_t> px(R * C * 4);
  for (std::size_t k = 0; k < R * C; ++k) {
    const bool solid =
        (!fill_from_.empty() && fill_from_[k] != k) || (!mesh_outline_.empty() && mesh_outline_[k]) || hull[k];
    const bool dry = !std::isfinite(values[k]);
    const glm::vec3 c = solid ? glm::vec3(0.55f)
                        : dry ? kPlanDryLand
                              : plan_colour((unit_scale * values[k] - spec.lo) / (spec.hi - spec.lo), spec);
    for (int ch = 0; ch < 3; ++ch) px[4 * k + ch] = static_cast<std::uint8_t>(std::lround(255.0f * c[ch]));
    px[4 * k + 3] = 255;
  }
  plan = plot_layout(target.width(), target.height(), spec, plan_reserve_right);
  draw_plot(plan, spec, px, static_cast<int>(C), static_cast<int>(R), target);
}

}  // namespace huygens
