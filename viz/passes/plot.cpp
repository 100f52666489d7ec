#include "plot.hpp"

#include <stb_easy_font.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>

namespace huygens {

// Piecewise-linear colour maps through a few control colours (t in [0, 1]): a diverging
// blue-white-red for heights about rest (ColorBrewer RdBu), viridis for depths.
glm::vec3 plan_colour(double t, bool diverging) {
  static const glm::vec3 rdbu[] = {{0.02f, 0.19f, 0.38f},
                                   {0.26f, 0.58f, 0.76f},
                                   {0.97f, 0.97f, 0.97f},
                                   {0.84f, 0.38f, 0.30f},
                                   {0.40f, 0.00f, 0.12f}};
  static const glm::vec3 viridis[] = {{0.267f, 0.005f, 0.329f},
                                      {0.229f, 0.322f, 0.546f},
                                      {0.128f, 0.567f, 0.551f},
                                      {0.369f, 0.789f, 0.383f},
                                      {0.993f, 0.906f, 0.144f}};
  const glm::vec3* c = diverging ? rdbu : viridis;
  const double x = std::clamp(t, 0.0, 1.0) * 4.0;
  const int k = std::min(static_cast<int>(x), 3);
  return glm::mix(c[k], c[k + 1], static_cast<float>(x - k));
}

glm::vec3 plan_colour(double t, const PlotSpec& spec) {
  if (!spec.hue) return plan_colour(t, spec.diverging);
  return glm::mix(glm::vec3(1.0f), *spec.hue, static_cast<float>(std::clamp(t, 0.0, 1.0)));
}

double nice_step(double range, int n) {
  if (!(range > 0.0)) return 1.0;
  const double raw = range / n, p = std::pow(10.0, std::floor(std::log10(raw))), f = raw / p;
  return (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * p;
}

namespace {

std::string tick_label(double v, double step) {
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v) < 0.5 * step ? 0.0 : v);
  return buf;
}

// Filled rectangles (pixels, y down from the top) drawn by scissored clears into the bound
// framebuffer of height `fb_h`.
struct Painter {
  int fb_h = 0;
  void rect(double x, double y, double w, double h, glm::vec3 c) const {
    const int x0 = static_cast<int>(std::floor(x)), x1 = static_cast<int>(std::floor(x + w));
    const int y0 = static_cast<int>(std::floor(y)), y1 = static_cast<int>(std::floor(y + h));
    if (x1 <= x0 || y1 <= y0) return;
    glScissor(x0, fb_h - y1, x1 - x0, y1 - y0);
    glClearColor(c.r, c.g, c.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  // stb_easy_font's glyph quads scaled by `s`; (x, y) = the text's top-left corner
  void text(double x, double y, const std::string& str, double s, glm::vec3 c = glm::vec3(0.0f)) const {
    static char buf[64 * 1024];
    unsigned char col[4] = {0, 0, 0, 255};
    const int quads = stb_easy_font_print(0, 0, const_cast<char*>(str.c_str()), col, buf, sizeof buf);
    for (int q = 0; q < quads; ++q) {
      const float* v0 = reinterpret_cast<const float*>(buf + 64 * q);
      const float* v2 = reinterpret_cast<const float*>(buf + 64 * q + 32);
      rect(x + s * v0[0], y + s * v0[1], s * (v2[0] - v0[0]), s * (v2[1] - v0[1]), c);
    }
  }
  static double text_width(const std::string& str, double s) {
    return s * stb_easy_font_width(const_cast<char*>(str.c_str()));
  }
};

}  // namespace

double caption_width(const std::string& text, int height) {
  const double s = std::max(1.0, std::round(height / 300.0));
  return Painter::text_width(text, s) + 8 * s;
}

double draw_caption(const std::string& text, const RenderTarget& target) {
  const int H = target.height();
  const double s = std::max(1.0, std::round(H / 300.0)), w = caption_width(text, H);
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo());
  glViewport(0, 0, target.width(), H);
  glEnable(GL_SCISSOR_TEST);
  const Painter p{H};
  p.rect(0, 0, w, 13 * s, glm::vec3(0.12f, 0.14f, 0.17f));
  p.text(4 * s, 3 * s, text, s, glm::vec3(1.0f));
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return w;
}

PlanPlot plot_layout(int W, int H, const PlotSpec& spec, double reserve_right) {
  // pixels, y down: title on top, the plot keeping the aspect, the colour bar on the right,
  // axis labels left and below
  const double s = std::max(1.0, std::round(H / 300.0));  // text scale (glyphs ~7 px high at 1)
  const double left = 40 * s, right = 84 * s + reserve_right, top = 30 * s, bottom = 26 * s;
  const double avail_w = std::max(1.0, W - left - right), avail_h = std::max(1.0, H - top - bottom);
  const double ppm = std::min(avail_w / spec.width_m, avail_h / spec.height_m);  // pixels per metre
  PlanPlot r;
  r.width = spec.width_m * ppm, r.height = spec.height_m * ppm;
  r.x0 = left + 0.5 * (avail_w - r.width), r.y0 = top + 0.5 * (avail_h - r.height);
  r.lo = spec.lo, r.hi = spec.hi;
  return r;
}

ColourBar colour_bar_layout(const PlanPlot& r, const PlotSpec& spec, int H) {
  const double s = std::max(1.0, std::round(H / 300.0));  // text scale, as plot_layout
  const double top = 30 * s, bottom = 26 * s;             // plot_layout's margins
  ColourBar b;
  b.x = r.x0 + r.width + 12 * s, b.width = 12 * s;
  const double intervals = std::max(1.0, std::round((spec.hi - spec.lo) / spec.step));
  b.height = std::min(std::max(r.height, intervals * kTickPitch * s), std::max(r.height, H - top - bottom));
  b.y = std::clamp(r.y0 + 0.5 * (r.height - b.height), std::min(top, r.y0), std::max(r.y0, H - bottom - b.height));
  return b;
}

void plot_range(double lo, double hi, bool diverging, PlotSpec& spec) {
  if (lo > hi) lo = hi = 0.0;
  if (diverging) hi = std::max(std::abs(lo), std::abs(hi)), lo = -hi;
  if (hi - lo < 1e-12) hi = lo + 1.0;
  spec.step = nice_step(hi - lo, 6);
  spec.lo = std::floor(lo / spec.step + 1e-9) * spec.step;  // a value on a tick stays the end
  spec.hi = std::ceil(hi / spec.step - 1e-9) * spec.step;
  spec.diverging = diverging;
}

namespace {

// Frame, ticks and labels of both axes (the image's corner at spec.x0_m, spec.y0_m).
void draw_axes(const Painter& p, const PlanPlot& r, const PlotSpec& spec, double s) {
  const glm::vec3 ink(0.0f);
  const double lw = std::max(1.0, s * 0.5), ppm = r.width / spec.width_m;
  p.rect(r.x0 - lw, r.y0 - lw, r.width + 2 * lw, lw, ink);
  p.rect(r.x0 - lw, r.y0 + r.height, r.width + 2 * lw, lw, ink);
  p.rect(r.x0 - lw, r.y0, lw, r.height, ink);
  p.rect(r.x0 + r.width, r.y0, lw, r.height, ink);
  const double mstep = nice_step(std::max(spec.width_m, spec.height_m), 6);
  for (double v = std::ceil(spec.x0_m / mstep) * mstep; v <= spec.x0_m + spec.width_m + 1e-9; v += mstep) {
    const double x = r.x0 + (v - spec.x0_m) * ppm;
    p.rect(x - 0.5 * lw, r.y0 + r.height, lw, 4 * s, ink);
    const std::string l = tick_label(v, mstep);
    p.text(x - 0.5 * Painter::text_width(l, s), r.y0 + r.height + 6 * s, l, s);
  }
  for (double v = std::ceil(spec.y0_m / mstep) * mstep; v <= spec.y0_m + spec.height_m + 1e-9; v += mstep) {
    const double y = r.y0 + r.height - (v - spec.y0_m) * ppm;
    p.rect(r.x0 - 4 * s, y - 0.5 * lw, 4 * s, lw, ink);
    const std::string l = tick_label(v, mstep);
    p.text(r.x0 - 6 * s - Painter::text_width(l, s), y - 3 * s, l, s);
  }
  p.text(r.x0 + 0.5 * r.width - Painter::text_width(spec.x_label, s) / 2, r.y0 + r.height + 16 * s, spec.x_label, s);
  p.text(r.x0 - 0.5 * Painter::text_width(spec.y_label, s), r.y0 - 16 * s, spec.y_label, s);  // above the axis
}

// The colour bar right of the plot (colour_bar_layout): one row per pixel through the map,
// ticks at spec.step. The ticks point into the bar from its right edge: a tick outside it, just
// left of its label, read as a minus sign (+5 as "-5", -1 as "--1").
void draw_colour_bar(const Painter& p, const PlanPlot& r, const PlotSpec& spec, double s, int H) {
  const ColourBar b = colour_bar_layout(r, spec, H);
  const double lw = std::max(1.0, s * 0.5);
  for (int row = 0; row < static_cast<int>(b.height); ++row)
    p.rect(b.x, b.y + b.height - row - 1, b.width, 1, plan_colour((row + 0.5) / b.height, spec));
  for (double v = spec.lo; v <= spec.hi + 1e-9 * spec.step; v += spec.step) {
    const double y = b.y + b.height - (v - spec.lo) / (spec.hi - spec.lo) * b.height;
    p.rect(b.x + b.width - 3 * s, y - 0.5 * lw, 3 * s, lw, glm::vec3(0.0f));
    p.text(b.x + b.width + 3 * s, y - 3 * s, tick_label(v, spec.step), s);
  }
  p.text(b.x, b.y - 12 * s, spec.quantity + " (" + spec.unit + ")", s);
}

}  // namespace

void draw_plot(const PlanPlot& r, const PlotSpec& spec, const std::vector<std::uint8_t>& rgba, int iw, int ih,
               const RenderTarget& target) {
  gl::Texture tex(iw, ih, GL_RGBA8);
  tex.upload(rgba.data(), GL_RGBA, GL_UNSIGNED_BYTE);
  const gl::Framebuffer src(tex);
  const int W = target.width(), H = target.height();
  const double s = std::max(1.0, std::round(H / 300.0));
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo());
  glViewport(0, 0, W, H);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(1.0f, 1.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, src.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.fbo());
  glBlitFramebuffer(0, 0, iw, ih, static_cast<GLint>(std::lround(r.x0)),
                    static_cast<GLint>(std::lround(H - r.y0 - r.height)),
                    static_cast<GLint>(std::lround(r.x0 + r.width)), static_cast<GLint>(std::lround(H - r.y0)),
                    GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, target.fbo());
  glEnable(GL_SCISSOR_TEST);
  const Painter p{H};
  draw_axes(p, r, spec, s);
  draw_colour_bar(p, r, spec, s, H);
  p.text(r.x0, 5 * s, spec.title, s);
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("draw_plot");
}

namespace {

// The side view's pixel image (w x h, row 0 at the bottom): background, then obstacles and
// particles through a depth buffer of y (smaller y = nearer the eye at -y).
struct SideImage {
  int w, h;
  double ppm;  // pixels per metre
  std::vector<std::uint8_t> rgba;
  std::vector<float> depth;
  std::vector<std::uint8_t> covered;  // pixels a mesh obstacle covers, whatever is in front
  SideImage(int w_, int h_, double ppm_)
      : w(w_),
        h(h_),
        ppm(ppm_),
        rgba(4 * std::size_t(w_) * h_, 255),
        depth(std::size_t(w_) * h_, 1e30f),
        covered(std::size_t(w_) * h_, 0) {
    for (std::size_t k = 0; k < depth.size(); ++k)  // a pale blue-grey tank
      rgba[4 * k] = 236, rgba[4 * k + 1] = 240, rgba[4 * k + 2] = 244;
  }
  void put(int i, int j, float y, glm::vec3 c) {
    if (i < 0 || j < 0 || i >= w || j >= h) return;
    const std::size_t k = std::size_t(j) * w + i;
    if (y >= depth[k]) return;
    depth[k] = y;
    for (int ch = 0; ch < 3; ++ch) rgba[4 * k + ch] = static_cast<std::uint8_t>(std::lround(255.0f * c[ch]));
  }
  // a filled x-z rectangle (m) at depth y
  void box(double x0, double z0, double x1, double z1, float y, glm::vec3 c) {
    for (int j = int(std::floor(z0 * ppm)); j < int(std::ceil(z1 * ppm)); ++j)
      for (int i = int(std::floor(x0 * ppm)); i < int(std::ceil(x1 * ppm)); ++i) put(i, j, y, c);
  }
  // a triangle of corners (x, y, z) (m) projected on x-z, its depth y interpolated across it,
  // lit by a light from the viewer's side and above: c (0.35 + 0.65 max(n.l, 0)), n the face
  // normal turned to the viewer (-y)
  void triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, glm::vec3 colour) {
    glm::dvec3 n = glm::cross(b - a, c - a);
    if (glm::length(n) == 0.0) return;
    n = glm::normalize(n);
    if (n.y > 0.0) n = -n;
    const double lambert = std::max(0.0, glm::dot(n, glm::normalize(glm::dvec3(-0.3, -1.0, 0.8))));
    const glm::vec3 lit = colour * static_cast<float>(0.35 + 0.65 * lambert);
    const glm::dvec2 pa(a.x * ppm, a.z * ppm), pb(b.x * ppm, b.z * ppm), pc(c.x * ppm, c.z * ppm);
    const double det = (pb.x - pa.x) * (pc.y - pa.y) - (pc.x - pa.x) * (pb.y - pa.y);
    if (std::abs(det) < 1e-9) return;  // seen edge-on
    const int i0 = int(std::floor(std::min({pa.x, pb.x, pc.x}))), i1 = int(std::ceil(std::max({pa.x, pb.x, pc.x})));
    const int j0 = int(std::floor(std::min({pa.y, pb.y, pc.y}))), j1 = int(std::ceil(std::max({pa.y, pb.y, pc.y})));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double x = i + 0.5, z = j + 0.5;
        const double wb = ((x - pa.x) * (pc.y - pa.y) - (pc.x - pa.x) * (z - pa.y)) / det;
        const double wc = ((pb.x - pa.x) * (z - pa.y) - (x - pa.x) * (pb.y - pa.y)) / det;
        if (wb < 0.0 || wc < 0.0 || wb + wc > 1.0) continue;
        put(i, j, static_cast<float>(a.y + wb * (b.y - a.y) + wc * (c.y - a.y)), lit);
        if (i >= 0 && j >= 0 && i < w && j < h) covered[std::size_t(j) * w + i] = 1;
      }
  }
  // the outline of the meshes' projection (covered pixels next to uncovered ones), drawn over
  // everything: where water stands in front of a mesh, its place still reads
  void outline(glm::vec3 c) {
    auto cov = [&](int i, int j) { return i >= 0 && j >= 0 && i < w && j < h && covered[std::size_t(j) * w + i]; };
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i)
        if (cov(i, j) && !(cov(i - 1, j) && cov(i + 1, j) && cov(i, j - 1) && cov(i, j + 1))) {
          depth[std::size_t(j) * w + i] = 1e30f;
          put(i, j, -1e30f, c);
        }
  }
  // a disc of radius r (px) centred at (x, z) (m)
  void disc(double x, double z, double r, float y, glm::vec3 c) {
    const double cx = x * ppm, cz = z * ppm;
    for (int j = int(std::floor(cz - r)); j <= int(std::ceil(cz + r)); ++j)
      for (int i = int(std::floor(cx - r)); i <= int(std::ceil(cx + r)); ++i) {
        const double dx = i + 0.5 - cx, dz = j + 0.5 - cz;
        if (dx * dx + dz * dz <= r * r) put(i, j, y, c);
      }
  }
};

}  // namespace

PlanPlot render_particles(std::span<const float> particles, const std::array<double, 3>& box_m, double radius_m,
                          std::span<const RenderObstacle> obstacles, const std::string& title, double reserve_right,
                          const RenderTarget& target) {
  const std::size_t n = particles.size() / 4;
  double vmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) vmax = std::max(vmax, static_cast<double>(particles[4 * i + 3]));
  const double scale = vmax < 2.0 ? 100.0 : 1.0;  // cm/s below 2 m/s
  PlotSpec spec;
  spec.width_m = box_m[0], spec.height_m = box_m[2];
  spec.y_label = "z (m)";
  spec.quantity = "speed", spec.unit = scale == 100.0 ? "cm/s" : "m/s";
  spec.title = title;
  plot_range(0.0, scale * vmax, false, spec);
  PlanPlot rect = plot_layout(target.width(), target.height(), spec, reserve_right);
  const int w = std::max(1, int(std::lround(rect.width))), h = std::max(1, int(std::lround(rect.height)));
  SideImage img(w, h, w / box_m[0]);
  for (const RenderObstacle& o : obstacles) {
    if (o.kind == RenderObstacle::Kind::mesh) {
      const std::vector<float>& t = o.triangles_m;
      for (std::size_t k = 0; k + 9 <= t.size(); k += 9)
        img.triangle({t[k], t[k + 1], t[k + 2]}, {t[k + 3], t[k + 4], t[k + 5]}, {t[k + 6], t[k + 7], t[k + 8]},
                     glm::vec3(0.62f, 0.60f, 0.57f));
      continue;
    }
    const bool cyl = o.kind == RenderObstacle::Kind::cylinder;
    const double x0 = cyl ? o.centre_m[0] - o.radius_m : o.min_m[0], x1 = cyl ? o.centre_m[0] + o.radius_m : o.max_m[0];
    const double z0 = std::max(0.0, cyl ? o.z0_m : o.min_m[2]), z1 = std::min(box_m[2], cyl ? o.z1_m : o.max_m[2]);
    const double y = cyl ? o.centre_m[1] - o.radius_m : o.min_m[1];
    img.box(x0, z0, x1, z1, static_cast<float>(y), glm::vec3(0.55f));
  }
  const double r_px = std::max(1.0, radius_m * img.ppm);
  for (std::size_t i = 0; i < n; ++i) {
    const float* q = &particles[4 * i];
    const double t = (scale * q[3] - spec.lo) / (spec.hi - spec.lo);
    const double shade = 1.0 - 0.45 * std::clamp(q[1] / box_m[1], 0.0, 1.0);  // farther = darker
    img.disc(q[0], q[2], r_px, q[1], plan_colour(t, false) * static_cast<float>(shade));
  }
  img.outline(glm::vec3(0.2f));
  draw_plot(rect, spec, img.rgba, w, h, target);
  return rect;
}

}  // namespace huygens
