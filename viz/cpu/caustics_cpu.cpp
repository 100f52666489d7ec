// CPU side of the caustics (paper 004 section 5) and the photon-histogram reference.
#include "caustics_cpu.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace huygens::viz {
namespace {

std::array<double, 3> unit_sun(const CausticsParams& p) {
  const double x = p.sun_dir[0], y = p.sun_dir[1], z = p.sun_dir[2];
  const double l = std::sqrt(x * x + y * y + z * z);
  if (!(z < 0.0) || !(l > 0.0)) throw std::invalid_argument("CausticsParams.sun_dir must point downwards (z < 0)");
  if (!(p.refractive_index >= 1.0f)) throw std::invalid_argument("CausticsParams.refractive_index must be >= 1");
  return {x / l, y / l, z / l};
}

// bilinear sample of a row-major grid at fractional index (fx along cols, fy along rows), clamped
inline float bilinear(const float* g, int rows, int cols, double fx, double fy) {
  fx = std::clamp(fx, 0.0, double(cols - 1));
  fy = std::clamp(fy, 0.0, double(rows - 1));
  const int j = std::min(int(fx), cols - 2), i = std::min(int(fy), rows - 2);
  const float u = float(fx - j), v = float(fy - i);
  const float* r0 = g + std::size_t(i) * cols + j;
  const float* r1 = r0 + cols;
  return (1 - v) * ((1 - u) * r0[0] + u * r0[1]) + v * ((1 - u) * r1[0] + u * r1[1]);
}

void check_field(const HeightfieldView& f) {
  if (f.rows < 2 || f.cols < 2 || f.eta.size() != std::size_t(f.rows) * f.cols || !(f.dx_m > 0) || !(f.depth_m > 0))
    throw std::invalid_argument("HeightfieldView: need rows, cols >= 2, eta.size() == rows*cols, dx > 0, depth > 0");
}

}  // namespace

std::array<double, 2> refract_displacement(const CausticsParams& p, double depth_m, double eta, double gx, double gy) {
  const auto s = unit_sun(p);
  const double nl = std::sqrt(gx * gx + gy * gy + 1.0);
  const double nx = -gx / nl, ny = -gy / nl, nz = 1.0 / nl;
  double cos_i = -(nx * s[0] + ny * s[1] + nz * s[2]);
  double Nx = nx, Ny = ny, Nz = nz;
  if (cos_i < 0) {  // sun below the local tangent plane: refract as seen from the other side
    cos_i = -cos_i;
    Nx = -nx, Ny = -ny, Nz = -nz;
  }
  const double r = 1.0 / p.refractive_index;
  const double k = 1.0 - r * r * (1.0 - cos_i * cos_i);  // > 0 always when entering the denser medium
  const double f = r * cos_i - std::sqrt(k);
  const double tx = r * s[0] + f * Nx, ty = r * s[1] + f * Ny, tz = r * s[2] + f * Nz;
  const double len = (eta + depth_m) / std::max(-tz, 1e-9);
  return {tx * len, ty * len};
}

LinearProjection linear_projection(const CausticsParams& p, double depth_m) {
  LinearProjection L;
  const auto d0 = refract_displacement(p, depth_m, 0.0, 0.0, 0.0);
  L.x0 = d0[0];
  L.y0 = d0[1];
  const double h = 1e-4;
  const auto px = refract_displacement(p, depth_m, 0.0, h, 0.0), mx = refract_displacement(p, depth_m, 0.0, -h, 0.0);
  const auto py = refract_displacement(p, depth_m, 0.0, 0.0, h), my = refract_displacement(p, depth_m, 0.0, 0.0, -h);
  L.a = (px[0] - mx[0]) / (2 * h);
  L.b = (py[0] - my[0]) / (2 * h);
  L.c = (px[1] - mx[1]) / (2 * h);
  L.d = (py[1] - my[1]) / (2 * h);
  return L;
}

GroundRect ground_rect(const CausticsParams& p, const HeightfieldView& field) {
  if (p.cover_domain) return {0.0, 0.0, double(field.cols - 1) * field.dx_m, double(field.rows - 1) * field.dx_m};
  const auto d0 = refract_displacement(p, field.depth_m, 0.0, 0.0, 0.0);
  return {d0[0], d0[1], double(field.cols - 1) * field.dx_m, double(field.rows - 1) * field.dx_m};
}

void caustics_mesh_init(const CausticsParams& p, CausticsMesh& m) {
  if (p.mesh_cols < 2 || p.mesh_rows < 2) throw std::invalid_argument("CausticsParams: mesh needs >= 2x2 vertices");
  m.cols = p.mesh_cols;
  m.rows = p.mesh_rows;
  const std::size_t n = std::size_t(m.cols) * m.rows;
  m.height.assign(n, 0.0f);
  m.ground_uv.assign(2 * n, 0.0f);
  m.surface_uv.resize(2 * n);
  for (int i = 0; i < m.rows; ++i)
    for (int j = 0; j < m.cols; ++j) {
      m.surface_uv[2 * (std::size_t(i) * m.cols + j)] = float(j) / float(m.cols - 1);
      m.surface_uv[2 * (std::size_t(i) * m.cols + j) + 1] = float(i) / float(m.rows - 1);
    }
  m.indices.clear();
  m.indices.reserve(std::size_t(m.cols + 1) * (m.rows + 1) * 6);
  for (int i = 0; i + 1 < m.rows; ++i)
    for (int j = 0; j + 1 < m.cols; ++j) {
      const std::uint32_t v00 = std::uint32_t(i * m.cols + j), v01 = v00 + 1, v10 = v00 + std::uint32_t(m.cols),
                          v11 = v10 + 1;
      m.indices.insert(m.indices.end(), {v00, v01, v11, v00, v11, v10});
    }
  // skirt: the ring i in {-1, rows} or j in {-1, cols} of the extended lattice
  const int ec = m.cols + 2, er = m.rows + 2;
  std::vector<std::uint32_t> id(std::size_t(ec) * er);
  m.skirt_anchor.clear();
  m.skirt_dir.clear();
  for (int i = -1; i <= m.rows; ++i)
    for (int j = -1; j <= m.cols; ++j) {
      std::uint32_t& v = id[std::size_t(i + 1) * ec + (j + 1)];
      if (i >= 0 && i < m.rows && j >= 0 && j < m.cols) {
        v = std::uint32_t(i * m.cols + j);
        continue;
      }
      v = std::uint32_t(n + m.skirt_anchor.size());
      const int ai = std::clamp(i, 0, m.rows - 1), aj = std::clamp(j, 0, m.cols - 1);
      m.skirt_anchor.push_back(std::uint32_t(ai * m.cols + aj));
      m.skirt_dir.push_back(std::int8_t(j - aj));
      m.skirt_dir.push_back(std::int8_t(i - ai));
    }
  for (int i = -1; i < m.rows; ++i)
    for (int j = -1; j < m.cols; ++j) {
      if (i >= 0 && j >= 0 && i + 1 < m.rows && j + 1 < m.cols) continue;  // a mesh cell
      const std::uint32_t v00 = id[std::size_t(i + 1) * ec + (j + 1)], v01 = id[std::size_t(i + 1) * ec + (j + 2)],
                          v10 = id[std::size_t(i + 2) * ec + (j + 1)], v11 = id[std::size_t(i + 2) * ec + (j + 2)];
      m.indices.insert(m.indices.end(), {v00, v01, v11, v00, v11, v10});
    }
  m.skirt_ground_uv.assign(2 * m.skirt_anchor.size(), 0.0f);
  m.skirt_surface_uv.assign(2 * m.skirt_anchor.size(), 0.0f);
  m.draw_indices.clear();
  m.draw_indices.reserve(m.indices.size());
  m.gains.clear();
  m.gains.reserve(m.indices.size() / 3);
  m.cell_gain.assign(m.indices.size() / 3, 0.0f);
  // skip_still: at most one footprint per 4 x 4 cells, plus the two edge strips
  m.rest_uv.clear();
  m.rest_uv.reserve(8 * (std::size_t(m.cols / 4 + 1) * (m.rows / 4 + 1) + 2));
  m.block_still.reserve(std::size_t(m.cols / 4 + 1) * (m.rows / 4 + 1));
  m.draw_indices.reserve(m.indices.size() + m.rest_uv.capacity() / 8 * 6);
  m.gains.reserve(m.indices.size() / 3 + m.rest_uv.capacity() / 8 * 2);
}

namespace {

// The skirt (see CausticsMesh): the map continued linearly outwards from each border vertex,
// P_ring = P_a + r (P_a - P_inner) per outward axis, in ground and surface coordinates alike,
// with one reach r (in cells, >= 1) for the whole ring: the smallest that takes every ring
// vertex at least one texel beyond the texture's edge. Where that cannot work (a fold at the
// border, or r capped) the ground position is pushed out to that margin instead, so the ring
// always encloses the whole texture.
void update_skirt(const CausticsParams& p, CausticsMesh& m) {
  const float mu = 1.0f / float(p.texture_width), mv = 1.0f / float(p.texture_height);  // one texel
  auto inner = [&](std::size_t k, int c) {  // the vertex one cell inwards along axis c
    const int a = int(m.skirt_anchor[k]), d = m.skirt_dir[2 * k + c];
    return std::uint32_t(c == 0 ? a - d : a - d * m.cols);
  };
  float r = 1.0f;
  for (std::size_t k = 0; k < m.skirt_anchor.size(); ++k) {
    const std::uint32_t a = m.skirt_anchor[k];
    for (int c = 0; c < 2; ++c) {
      const int d = m.skirt_dir[2 * k + c];
      if (d == 0) continue;
      const float beyond = d > 0 ? m.ground_uv[2 * a + c] - 1.0f : -m.ground_uv[2 * a + c];
      const float grow = float(d) * (m.ground_uv[2 * a + c] - m.ground_uv[2 * inner(k, c) + c]);
      const float margin = c == 0 ? mu : mv;
      if (grow > 0.0f) r = std::max(r, (margin - beyond) / grow);
    }
  }
  r = std::min(r, 16.0f);
  for (std::size_t k = 0; k < m.skirt_anchor.size(); ++k) {
    const std::uint32_t a = m.skirt_anchor[k];
    for (int c = 0; c < 2; ++c) {
      float gr = m.ground_uv[2 * a + c], sr = m.surface_uv[2 * a + c];
      for (int axis = 0; axis < 2; ++axis) {
        if (m.skirt_dir[2 * k + axis] == 0) continue;
        const std::uint32_t in = inner(k, axis);
        gr += r * (m.ground_uv[2 * a + c] - m.ground_uv[2 * in + c]);
        sr += r * (m.surface_uv[2 * a + c] - m.surface_uv[2 * in + c]);
      }
      const int d = m.skirt_dir[2 * k + c];
      const float margin = c == 0 ? mu : mv;
      if (d > 0) gr = std::max(gr, 1.0f + margin);
      if (d < 0) gr = std::min(gr, -margin);
      m.skirt_ground_uv[2 * k + c] = gr;
      m.skirt_surface_uv[2 * k + c] = sr;
    }
  }
  m.skirt_reach = r;
}

}  // namespace

void caustics_mesh_update(const CausticsParams& p, const HeightfieldView& f, CausticsMesh& m) {
  check_field(f);
  if (m.cols != p.mesh_cols || m.rows != p.mesh_rows) caustics_mesh_init(p, m);
  const GroundRect g = ground_rect(p, f);
  const double W = g.width, H = g.height;
  const double hx = W / (m.cols - 1), hy = H / (m.rows - 1);
  const LinearProjection L = linear_projection(p, f.depth_m);
  // rest positions: the domain's lattice, or (cover_domain) shifted back along the sun by the
  // still-water displacement so that the flat surface lights exactly [0, W] x [0, H]
  const double ox = p.cover_domain ? -L.x0 : 0.0, oy = p.cover_domain ? -L.y0 : 0.0;
  // heights at the mesh vertices, bilinear from the full field (clamped: the edge value outside)
  for (int i = 0; i < m.rows; ++i)
    for (int j = 0; j < m.cols; ++j)
      m.height[std::size_t(i) * m.cols + j] =
          bilinear(f.eta.data(), f.rows, f.cols, (j * hx + ox) / f.dx_m, (i * hy + oy) / f.dx_m);
  // ray crossing of z = 0: rest position + eta s_xy / (-s_z)
  const auto sun = unit_sun(p);
  const double bx = p.flux_by_beam_area ? sun[0] / -sun[2] : 0.0, by = p.flux_by_beam_area ? sun[1] / -sun[2] : 0.0;
  const bool exact = p.projection == CausticsProjection::Exact;
  for (int i = 0; i < m.rows; ++i) {
    const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, m.rows - 1);
    for (int j = 0; j < m.cols; ++j) {
      const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, m.cols - 1);
      const float* h = m.height.data();
      // slopes by central differences on the mesh (one-sided at the border)
      const double gx = (h[std::size_t(i) * m.cols + j1] - h[std::size_t(i) * m.cols + j0]) / ((j1 - j0) * hx);
      const double gy = (h[std::size_t(i1) * m.cols + j] - h[std::size_t(i0) * m.cols + j]) / ((i1 - i0) * hy);
      const double X0 = j * hx + ox, Y0 = i * hy + oy;
      double X = X0, Y = Y0;
      if (exact) {
        const auto d = refract_displacement(p, f.depth_m, h[std::size_t(i) * m.cols + j], gx, gy);
        X += d[0];
        Y += d[1];
      } else {
        X += L.x0 + L.a * gx + L.b * gy;
        Y += L.y0 + L.c * gx + L.d * gy;
      }
      const double e = h[std::size_t(i) * m.cols + j];
      m.surface_uv[2 * (std::size_t(i) * m.cols + j)] = float((X0 + e * bx) / W);
      m.surface_uv[2 * (std::size_t(i) * m.cols + j) + 1] = float((Y0 + e * by) / H);
      m.ground_uv[2 * (std::size_t(i) * m.cols + j)] = float((X - g.x0) / W);
      m.ground_uv[2 * (std::size_t(i) * m.cols + j) + 1] = float((Y - g.y0) / H);
    }
  }
  update_skirt(p, m);
}

namespace {

// Draw list of caustics_mesh_triangles: vertex positions in texels, the gain of a triangle, the
// flatness test of a block and its fan.
class TriangleList {
 public:
  TriangleList(const CausticsParams& p, CausticsMesh& m)
      : m_(m),
        tw_(float(p.texture_width)),
        th_(float(p.texture_height)),
        unit_(p.float_target ? 1.0f : p.unit_level_u8 / 255.0f),
        dg_(p.merge_gain_tolerance),
        dp_(p.merge_position_tolerance),
        nv_(std::size_t(m.cols) * m.rows) {}

  // unit * (surface area) / (ground area) of triangle (a, b, c), areas in texels
  float gain(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    const float ground = area(m_.ground_uv, m_.skirt_ground_uv, a, b, c);
    const float surface = area(m_.surface_uv, m_.skirt_surface_uv, a, b, c);
    return unit_ * surface / std::max(ground, 1e-6f * surface);
  }
  void emit(std::uint32_t a, std::uint32_t b, std::uint32_t c, float g) {
    m_.draw_indices.insert(m_.draw_indices.end(), {a, b, c});
    m_.gains.push_back(g);
  }
  // the block of `size` cells at cell (i0, j0): one fan if uniform, else its quarters, else cells
  void block(int i0, int j0, int size) {
    if (size >= 4 && uniform(i0, j0, size)) return fan(i0, j0, size);
    if (size > 4) {
      const int h = size / 2;
      for (const auto& [di, dj] : {std::pair{0, 0}, {0, h}, {h, 0}, {h, h}}) block(i0 + di, j0 + dj, h);
      return;
    }
    for (int i = i0; i < i0 + size; ++i)
      for (int j = j0; j < j0 + size; ++j) cell(i, j);
  }
  // still water: gains within dg_ of 1, every vertex within dp_ texels of its rest position,
  // its surface outside the box `shadow`
  bool still(int i0, int j0, int size, const std::array<float, 4>& shadow) const {
    float u0 = 3.4e38f, v0 = 3.4e38f, u1 = -3.4e38f, v1 = -3.4e38f;
    for (int i = i0; i <= i0 + size; ++i)
      for (int j = j0; j <= j0 + size; ++j) {
        const std::size_t v = vid(i, j);
        const float ru = float(j) / float(m_.cols - 1), rv = float(i) / float(m_.rows - 1);
        if (tw_ * std::abs(m_.ground_uv[2 * v] - ru) > dp_ || th_ * std::abs(m_.ground_uv[2 * v + 1] - rv) > dp_)
          return false;
        u0 = std::min(u0, m_.surface_uv[2 * v]), u1 = std::max(u1, m_.surface_uv[2 * v]);
        v0 = std::min(v0, m_.surface_uv[2 * v + 1]), v1 = std::max(v1, m_.surface_uv[2 * v + 1]);
      }
    if (u1 >= shadow[0] && u0 <= shadow[2] && v1 >= shadow[1] && v0 <= shadow[3]) return false;
    for (int i = i0; i < i0 + size; ++i) {
      const std::size_t t = 2 * (std::size_t(i) * (m_.cols - 1) + j0);
      for (std::size_t k = t; k < t + 2 * std::size_t(size); ++k)
        if (std::abs(m_.cell_gain[k] - unit_) > dg_ * unit_) return false;
    }
    return true;
  }
  // light -1 over the rest footprint of cells [i0, i1) x [j0, j1): two triangles on new vertices
  void remove_rest_light(int i0, int j0, int i1, int j1) {
    if (i1 <= i0 || j1 <= j0) return;
    const auto base = std::uint32_t(m_.vertex_count() + m_.rest_uv.size() / 2);
    const float u0 = float(j0) / float(m_.cols - 1), u1 = float(j1) / float(m_.cols - 1);
    const float v0 = float(i0) / float(m_.rows - 1), v1 = float(i1) / float(m_.rows - 1);
    m_.rest_uv.insert(m_.rest_uv.end(), {u0, v0, u1, v0, u1, v1, u0, v1});
    emit(base, base + 1, base + 2, -unit_);
    emit(base, base + 2, base + 3, -unit_);
  }
  void cell(int i, int j) {
    const std::size_t t = 2 * (std::size_t(i) * (m_.cols - 1) + j);
    for (std::size_t k = t; k < t + 2; ++k)
      emit(m_.indices[3 * k], m_.indices[3 * k + 1], m_.indices[3 * k + 2], m_.cell_gain[k]);
  }

 private:
  float coord(const std::vector<float>& main, const std::vector<float>& skirt, std::uint32_t v, int c) const {
    const float s = c == 0 ? tw_ : th_;
    return s * (v < nv_ ? main[2 * std::size_t(v) + c] : skirt[2 * (std::size_t(v) - nv_) + c]);
  }
  float area(const std::vector<float>& m, const std::vector<float>& sk, std::uint32_t a, std::uint32_t b,
             std::uint32_t c) const {
    const float ax = coord(m, sk, a, 0), ay = coord(m, sk, a, 1);
    const float e1x = coord(m, sk, b, 0) - ax, e1y = coord(m, sk, b, 1) - ay;
    const float e2x = coord(m, sk, c, 0) - ax, e2y = coord(m, sk, c, 1) - ay;
    return 0.5f * std::abs(e1x * e2y - e1y * e2x);
  }
  std::uint32_t vid(int i, int j) const { return std::uint32_t(i * m_.cols + j); }
  // every vertex of the block within dp_ texels of the bilinear map through its corners
  bool near_bilinear(const std::vector<float>& uv, int i0, int j0, int size) const {
    const std::uint32_t c00 = vid(i0, j0), c01 = vid(i0, j0 + size), c10 = vid(i0 + size, j0),
                        c11 = vid(i0 + size, j0 + size);
    const float inv = 1.0f / float(size);
    for (int c = 0; c < 2; ++c) {
      const float s = c == 0 ? tw_ : th_;
      const float p00 = uv[2 * c00 + c], p01 = uv[2 * c01 + c], p10 = uv[2 * c10 + c], p11 = uv[2 * c11 + c];
      for (int i = 0; i <= size; ++i) {
        const float v = float(i) * inv;
        const float a = p00 + v * (p10 - p00), b = p01 + v * (p11 - p01);
        for (int j = 0; j <= size; ++j) {
          const float want = a + float(j) * inv * (b - a);
          if (s * std::abs(uv[2 * std::size_t(vid(i0 + i, j0 + j)) + c] - want) > dp_) return false;
        }
      }
    }
    return true;
  }
  bool uniform(int i0, int j0, int size) const {
    float lo = 3.4e38f, hi = 0.0f;
    for (int i = i0; i < i0 + size; ++i) {
      const std::size_t t = 2 * (std::size_t(i) * (m_.cols - 1) + j0);
      for (std::size_t k = t; k < t + 2 * std::size_t(size); ++k) {
        lo = std::min(lo, m_.cell_gain[k]);
        hi = std::max(hi, m_.cell_gain[k]);
      }
    }
    return hi <= lo * (1.0f + dg_) && near_bilinear(m_.ground_uv, i0, j0, size) &&
           near_bilinear(m_.surface_uv, i0, j0, size);
  }
  // fan from the centre vertex to the 4 size boundary vertices, counter-clockwise
  void fan(int i0, int j0, int size) {
    const std::uint32_t centre = vid(i0 + size / 2, j0 + size / 2);
    auto boundary = [&](int k) {  // k-th boundary vertex from the corner (i0, j0)
      const int side = k / size, o = k % size;
      return side == 0   ? vid(i0, j0 + o)
             : side == 1 ? vid(i0 + o, j0 + size)
             : side == 2 ? vid(i0 + size, j0 + size - o)
                         : vid(i0 + size - o, j0);
    };
    std::uint32_t prev = boundary(0);
    for (int k = 1; k <= 4 * size; ++k) {
      const std::uint32_t next = boundary(k % (4 * size));
      emit(centre, prev, next, gain(centre, prev, next));
      prev = next;
    }
  }

  CausticsMesh& m_;
  float tw_, th_, unit_, dg_, dp_;
  std::size_t nv_;
};

}  // namespace

void caustics_mesh_triangles(const CausticsParams& p, CausticsMesh& m, std::array<float, 4> shadow_uv) {
  TriangleList list(p, m);
  const std::size_t n_tri = m.indices.size() / 3;
  m.cell_gain.resize(n_tri);
  for (std::size_t t = 0; t < n_tri; ++t)
    m.cell_gain[t] = list.gain(m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]);
  m.draw_indices.clear();
  m.gains.clear();
  m.rest_uv.clear();
  const int cells_x = m.cols - 1, cells_y = m.rows - 1;
  const int b = p.merge_block >= 4 ? p.merge_block : 0;
  const int bx = b ? cells_x / b : 0, by = b ? cells_y / b : 0;
  // skip_still pays a footprint's fill for every block it draws: worth it only when at least
  // half the blocks are still
  bool skip = b && p.skip_still && p.float_target && p.area == CausticsArea::Explicit;
  m.block_still.assign(std::size_t(bx) * by, 0);
  if (skip) {
    std::size_t n_still = 0;
    for (int bi = 0; bi < by; ++bi)
      for (int bj = 0; bj < bx; ++bj)
        n_still += m.block_still[std::size_t(bi) * bx + bj] = list.still(bi * b, bj * b, b, shadow_uv) ? 1 : 0;
    skip = 2 * n_still >= m.block_still.size();
  }
  m.start_still = skip;
  // whole blocks, then the cells of the partial blocks along the top and right edges
  for (int bi = 0; bi < by; ++bi)
    for (int bj = 0; bj < bx; ++bj) {
      if (skip && m.block_still[std::size_t(bi) * bx + bj]) continue;
      if (skip) list.remove_rest_light(bi * b, bj * b, (bi + 1) * b, (bj + 1) * b);
      list.block(bi * b, bj * b, b);
    }
  for (int i = 0; i < cells_y; ++i)
    for (int j = (i < by * b ? bx * b : 0); j < cells_x; ++j) list.cell(i, j);
  if (skip) {  // the edge strips' footprints
    list.remove_rest_light(0, bx * b, by * b, cells_x);
    list.remove_rest_light(by * b, 0, cells_y, cells_x);
  }
  // the skirt's triangles follow the mesh cells' in `indices`
  for (std::size_t t = 2 * std::size_t(cells_x) * cells_y; t < n_tri; ++t)
    list.emit(m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2], m.cell_gain[t]);
}

int mesh_size_for_field(const HeightfieldView& f, double per_wavelength, int min_n) {
  check_field(f);
  // lambda = 2 pi rms(grad eta) / rms(laplacian eta): for one sine 2 pi / k; for a spectrum the
  // k^4-weighted mean wavelength, i.e. the curvature that focuses light into caustics (a long
  // swell with short rings on it is resolved for the rings)
  double g2 = 0, l2 = 0;
  const double inv = 1.0 / (double(f.dx_m) * f.dx_m);
  for (int i = 1; i + 1 < f.rows; ++i)
    for (int j = 1; j + 1 < f.cols; ++j) {
      const float* r = f.eta.data() + std::size_t(i) * f.cols + j;
      const double gx = (r[1] - r[-1]) / (2.0 * f.dx_m), gy = (r[f.cols] - r[-f.cols]) / (2.0 * f.dx_m);
      const double lap = (r[1] + r[-1] + r[f.cols] + r[-f.cols] - 4.0 * r[0]) * inv;
      g2 += gx * gx + gy * gy;
      l2 += lap * lap;
    }
  const int n_max = std::max(f.rows, f.cols);
  if (!(g2 > 0) || !(l2 > 0)) return std::min(min_n, n_max);
  const double lambda = 2 * std::numbers::pi * std::sqrt(g2 / l2);
  const double extent = double(n_max - 1) * f.dx_m;
  const double want = std::ceil(per_wavelength * extent / lambda) + 1;
  return int(std::clamp(want, double(std::min(min_n, n_max)), double(n_max)));
}

ShipShadow make_ellipse_hull(float cx, float cy, float heading, float length, float beam, int segments) {
  ShipShadow s;
  const float c = std::cos(heading), sn = std::sin(heading);
  for (int k = 0; k < segments; ++k) {
    const float t = 2.0f * std::numbers::pi_v<float> * float(k) / float(segments);
    const float u = 0.5f * length * std::cos(t), v = 0.5f * beam * std::sin(t);
    s.outline.push_back({cx + c * u - sn * v, cy + sn * u + c * v});
  }
  return s;
}

std::vector<std::array<float, 2>> shadow_on_surface(const CausticsParams& p, const ShipShadow& ship) {
  const auto s = unit_sun(p);
  const float ox = float(ship.height_m * s[0] / -s[2]), oy = float(ship.height_m * s[1] / -s[2]);
  std::vector<std::array<float, 2>> out = ship.outline;
  for (auto& q : out) q = {q[0] + ox, q[1] + oy};
  return out;
}

bool inside_convex(const std::vector<std::array<float, 2>>& poly, float x, float y) {
  const std::size_t n = poly.size();
  if (n < 3) return false;
  int sign = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto& a = poly[k];
    const auto& b = poly[(k + 1) % n];
    const float cr = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
    const int sg = (cr > 0) - (cr < 0);
    if (sg == 0) continue;
    if (sign == 0)
      sign = sg;
    else if (sg != sign)
      return false;
  }
  return true;
}

std::vector<float> photon_caustics(const CausticsParams& p, const HeightfieldView& f, int per_cell, std::uint64_t seed,
                                   const ShipShadow* ship) {
  check_field(f);
  if (per_cell < 1) throw std::invalid_argument("photon_caustics: per_cell >= 1");
  const auto s = unit_sun(p);
  const int R = f.rows, C = f.cols;
  // slopes of the full-resolution surface: central differences, one-sided at the border
  std::vector<float> gx(std::size_t(R) * C), gy(std::size_t(R) * C);
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) {
      const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, C - 1);
      const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, R - 1);
      gx[std::size_t(i) * C + j] =
          (f.eta[std::size_t(i) * C + j1] - f.eta[std::size_t(i) * C + j0]) / ((j1 - j0) * f.dx_m);
      gy[std::size_t(i) * C + j] =
          (f.eta[std::size_t(i1) * C + j] - f.eta[std::size_t(i0) * C + j]) / ((i1 - i0) * f.dx_m);
    }
  const GroundRect g = ground_rect(p, f);
  const int TW = p.texture_width, TH = p.texture_height;
  std::vector<double> acc(std::size_t(TW) * TH, 0.0);
  // each photon carries (surface area per photon) * (flux factor), in units of texel area
  const double texel_area = (g.width / TW) * (g.height / TH);
  const double cell = f.dx_m / per_cell;
  const double w0 = cell * cell / texel_area;
  std::vector<std::array<float, 2>> shadow;
  if (ship) shadow = shadow_on_surface(p, *ship);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double inv_dx = 1.0 / f.dx_m;
  for (int i = 0; i + 1 < R; ++i)
    for (int j = 0; j + 1 < C; ++j)
      for (int a = 0; a < per_cell; ++a)
        for (int b = 0; b < per_cell; ++b) {
          const double x = (j + (b + U(rng)) / per_cell) * f.dx_m;
          const double y = (i + (a + U(rng)) / per_cell) * f.dx_m;
          const double fx = x * inv_dx, fy = y * inv_dx;
          const double eta = bilinear(f.eta.data(), R, C, fx, fy);
          // the shadow polygon lies on z = 0: test where the photon's ray crosses it
          if (!shadow.empty() && inside_convex(shadow, float(x + eta * s[0] / -s[2]), float(y + eta * s[1] / -s[2])))
            continue;
          const double sx = bilinear(gx.data(), R, C, fx, fy), sy = bilinear(gy.data(), R, C, fx, fy);
          // flux through the surface element per horizontal area, relative to still water
          const double flux = std::abs(s[2] - s[0] * sx - s[1] * sy) / -s[2];
          const auto d = refract_displacement(p, f.depth_m, eta, sx, sy);
          const double u = (x + d[0] - g.x0) / g.width * TW, v = (y + d[1] - g.y0) / g.height * TH;
          if (u < 0 || v < 0 || u >= TW || v >= TH) continue;
          acc[std::size_t(v) * TW + std::size_t(u)] += w0 * flux;
        }
  return std::vector<float>(acc.begin(), acc.end());
}

std::vector<float> blur121_f32(std::span<const float> img, int w, int h) {
  std::vector<float> out(std::size_t(w) * h);
  static constexpr float k[3] = {1.0f, 2.0f, 1.0f};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double s = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
          s += k[dx + 1] * k[dy + 1] * img[std::size_t(yy) * w + xx];
        }
      out[std::size_t(y) * w + x] = float(s / 16.0);
    }
  return out;
}

CausticsDiff compare_caustics(std::span<const float> a, std::span<const float> b, int w, int h, int border) {
  if (a.size() != std::size_t(w) * h || b.size() != a.size() || 2 * border >= std::min(w, h))
    throw std::invalid_argument("compare_caustics: size mismatch or border too wide");
  CausticsDiff r;
  double n = 0;
  for (int y = border; y < h - border; ++y)
    for (int x = border; x < w - border; ++x) {
      r.mean_a += a[std::size_t(y) * w + x];
      r.mean_b += b[std::size_t(y) * w + x];
      n += 1;
    }
  r.mean_a /= n;
  r.mean_b /= n;
  double d2 = 0, b2 = 0, c2 = 0;
  for (int y = border; y < h - border; ++y)
    for (int x = border; x < w - border; ++x) {
      const double va = a[std::size_t(y) * w + x] / r.mean_a, vb = b[std::size_t(y) * w + x] / r.mean_b;
      d2 += (va - vb) * (va - vb);
      b2 += vb * vb;
      c2 += (vb - 1) * (vb - 1);
      r.max_abs = std::max(r.max_abs, std::abs(va - vb));
    }
  r.rel_l2 = std::sqrt(d2 / b2);
  r.rel_l2_contrast = std::sqrt(d2 / std::max(c2, 1e-300));
  return r;
}

double focus_factor(double depth_m, double n) { return depth_m * (1.0 - 1.0 / n); }

// 0 on [0, 0.1] and [0.9, 1], 1 on [0.3, 0.7], smoothstep between
static double edge_window(double t) {
  const double u = std::clamp((std::min(t, 1 - t) - 0.1) / 0.2, 0.0, 1.0);
  return u * u * (3 - 2 * u);
}

// An n x n field over [0, L]^2 (spacing L / (n - 1)) with the elevation eta(x, y) (m) at its points.
template <class Eta>
SyntheticField sample_field(int n, double L, double depth, Eta eta) {
  SyntheticField f;
  f.n = n;
  f.dx = float(L / (n - 1));
  f.depth = float(depth);
  f.eta.resize(std::size_t(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) f.eta[std::size_t(i) * n + j] = float(eta(j * L / (n - 1), i * L / (n - 1)));
  return f;
}

// wind-like sea: a sum of sines with wave vectors on the periodic lattice of the domain,
// amplitudes scaled so that sum (1 - 1/n) D A_k k^2 = strength (the largest possible local
// compression of the ground map); `window` multiplies by a smooth window that is zero in the
// outer tenth of the domain, so the border stays still (all projected triangles stay on the ground)
SyntheticField synthetic_wind_sea(int n, double L, double depth, double strength, bool window) {
  struct C {
    int ix, iy;
    double a, phase;
  };
  const C comps[] = {{5, 2, 1.0, 0.3}, {-3, 6, 0.8, 1.1}, {7, -4, 0.5, 2.0}, {2, 9, 0.35, 4.2}, {11, 3, 0.2, 0.7}};
  double sum = 0;
  for (const auto& c : comps)
    sum += c.a * (2 * std::numbers::pi / L) * (2 * std::numbers::pi / L) * (c.ix * c.ix + c.iy * c.iy);
  const double scale = strength / (focus_factor(depth, 1.333) * sum);
  return sample_field(n, L, depth, [&](double x, double y) {
    double e = 0;
    for (const auto& c : comps) e += scale * c.a * std::sin(2 * std::numbers::pi / L * (c.ix * x + c.iy * y) + c.phase);
    return window ? e * edge_window(x / L) * edge_window(y / L) : e;
  });
}

// ring wave: A J0(k r) exp(-r^2 / (2 s^2)) about the centre; at the centre the Hessian is
// -A k^2 / 2 I, so `strength` = (1 - 1/n) D A k^2 / 2 is the central compression
SyntheticField synthetic_ring_wave(int n, double L, double depth, double strength) {
  const double k = 2 * std::numbers::pi / (0.15 * L), s = 0.2 * L;
  const double A = strength / (focus_factor(depth, 1.333) * k * k / 2);
  return sample_field(n, L, depth, [&](double x, double y) {
    const double r = std::hypot(x - L / 2, y - L / 2);
    return A * std::cyl_bessel_j(0.0, k * r) * std::exp(-r * r / (2 * s * s));
  });
}

}  // namespace huygens::viz

namespace huygens::viz {

namespace {

// Bilinear height of the field at (x, y) (m, field coordinates; clamped to the grid).
float field_height(const HeightfieldView& f, float x, float y) {
  const float fx = std::clamp(x / f.dx_m, 0.0f, static_cast<float>(f.cols - 1)),
              fy = std::clamp(y / f.dx_m, 0.0f, static_cast<float>(f.rows - 1));
  const int c = std::min(static_cast<int>(fx), f.cols - 2), r = std::min(static_cast<int>(fy), f.rows - 2);
  const float tx = fx - c, ty = fy - r;
  const auto e = [&](int i, int j) { return f.eta[static_cast<std::size_t>(i) * f.cols + j]; };
  return (1 - ty) * ((1 - tx) * e(r, c) + tx * e(r, c + 1)) + ty * ((1 - tx) * e(r + 1, c) + tx * e(r + 1, c + 1));
}

}  // namespace

std::vector<float> simple_caustics(const CausticsParams& p, const HeightfieldView& field,
                                   const SimpleCausticsWeights& w) {
  const int W = p.texture_width, H = p.texture_height;
  const GroundRect g = ground_rect(p, field);
  // the sun's ray refracted at the still surface: a texel's light left the surface this far back
  const glm::dvec3 s = glm::normalize(glm::dvec3(p.sun_dir[0], p.sun_dir[1], p.sun_dir[2]));
  const double r = 1.0 / p.refractive_index, ci = s.z < 0 ? -s.z : s.z;
  const glm::dvec3 t = r * s + (r * ci - std::sqrt(1.0 - r * r * (1.0 - ci * ci))) * glm::dvec3(0.0, 0.0, 1.0);
  const float back_x = static_cast<float>(t.x / -t.z * field.depth_m),
              back_y = static_cast<float>(t.y / -t.z * field.depth_m);
  const auto [lo, hi] = std::minmax_element(field.eta.begin(), field.eta.end());
  const float z0 = *lo, span = *hi - *lo, e = field.dx_m;
  std::vector<float> out(static_cast<std::size_t>(W) * H);
  double sum = 0.0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float gx = static_cast<float>(g.x0 + (x + 0.5) * g.width / W) - back_x,
                  gy = static_cast<float>(g.y0 + (y + 0.5) * g.height / H) - back_y;
      const float sx = (field_height(field, gx + e, gy) - field_height(field, gx - e, gy)) / (2 * e),
                  sy = (field_height(field, gx, gy + e) - field_height(field, gx, gy - e)) / (2 * e);
      const float n = 1.0f / std::sqrt(1.0f + sx * sx + sy * sy);
      const float zn = span > 0.0f ? (field_height(field, gx, gy) - z0) / span : 0.0f;
      const float v = w.a * zn + w.b * std::abs(-sx * n - sy * n);
      out[static_cast<std::size_t>(y) * W + x] = v;
      sum += v;
    }
  const float c = static_cast<float>(1.0 - sum / (static_cast<double>(W) * H));
  for (float& v : out) v += c;
  return out;
}

}  // namespace huygens::viz
