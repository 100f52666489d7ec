#include "refraction.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace huygens {

glm::dvec3 refract_dir(const glm::dvec3& d, const glm::dvec3& n, double ratio) {
  // t = ratio d + (ratio cos_i - cos_t) n, with cos_i = -n.d (n faces the incoming ray)
  const double cos_i = -glm::dot(n, d);
  const double k = 1.0 - ratio * ratio * (1.0 - cos_i * cos_i);
  if (k < 0.0) return glm::dvec3(0.0);
  return ratio * d + (ratio * cos_i - std::sqrt(k)) * n;
}

glm::dvec3 normal_from_differences(double eta_u, double eta_v, double dx) {
  return glm::normalize(glm::dvec3(-eta_u / (2.0 * dx), -eta_v / (2.0 * dx), 1.0));
}

glm::dvec2 snell_ground_point(const ViewRays& view, const glm::dvec3& p, const glm::dvec3& n,
                              const RefractionParams& params) {
  const glm::dvec3 d = view.toward(p);
  // a normal facing away from the viewer (grazing waves) is flipped so Snell stays defined
  const glm::dvec3 nn = glm::dot(n, d) > 0.0 ? -n : n;
  glm::dvec3 t = refract_dir(d, nn, 1.0 / params.index);
  if (t.z > -1e-6) t.z = -1e-6;  // a ray that does not go down meets the ground far away
  const double s = (params.ground_z - p.z) / t.z;
  return {p.x + s * t.x, p.y + s * t.y};
}

void height_differences(std::span<const float> eta, std::size_t rows, std::size_t cols, std::span<float> out) {
  assert(eta.size() == rows * cols && out.size() == 2 * rows * cols);
  for (std::size_t i = 0; i < rows; ++i) {
    const std::size_t im = i > 0 ? i - 1 : 0, ip = i + 1 < rows ? i + 1 : rows - 1;
    const float sv = (ip - im) == 2 ? 1.0f : 2.0f;  // one-sided difference doubled at the border
    for (std::size_t j = 0; j < cols; ++j) {
      const std::size_t jm = j > 0 ? j - 1 : 0, jp = j + 1 < cols ? j + 1 : cols - 1;
      const float su = (jp - jm) == 2 ? 1.0f : 2.0f;
      out[2 * (i * cols + j)] = su * (eta[i * cols + jp] - eta[i * cols + jm]);
      out[2 * (i * cols + j) + 1] = sv * (eta[ip * cols + j] - eta[im * cols + j]);
    }
  }
}

namespace {
std::vector<std::size_t> axis_layout(std::size_t n, std::size_t f) {
  std::vector<std::size_t> idx;
  for (std::size_t k = 0; k < n; k += f) idx.push_back(k);
  if (idx.back() != n - 1) idx.push_back(n - 1);
  return idx;
}
}  // namespace

SurfaceMeshLayout make_mesh_layout(std::size_t rows, std::size_t cols, std::size_t factor) {
  factor = std::max<std::size_t>(factor, 1);
  return {axis_layout(cols, factor), axis_layout(rows, factor)};
}

std::vector<std::uint32_t> mesh_triangles(const SurfaceMeshLayout& layout) {
  std::vector<std::uint32_t> idx;
  const auto vc = static_cast<std::uint32_t>(layout.vertex_cols());
  for (std::uint32_t l = 0; l + 1 < layout.vertex_rows(); ++l)
    for (std::uint32_t k = 0; k + 1 < vc; ++k) {
      const std::uint32_t v00 = l * vc + k, v10 = v00 + 1, v01 = v00 + vc, v11 = v01 + 1;
      idx.insert(idx.end(), {v00, v10, v11, v00, v11, v01});
    }
  return idx;
}

void subsample_heights(std::span<const float> eta, std::size_t rows, std::size_t cols, std::size_t factor,
                       const SurfaceMeshLayout& layout, std::span<float> out) {
  const long f = static_cast<long>(std::max<std::size_t>(factor, 1));
  const std::size_t vc = layout.vertex_cols();
  for (std::size_t l = 0; l < layout.vertex_rows(); ++l) {
    const long ci = static_cast<long>(layout.row_idx[l]);
    for (std::size_t k = 0; k < vc; ++k) {
      const long cj = static_cast<long>(layout.col_idx[k]);
      double sum = 0.0, wsum = 0.0;
      for (long di = -f + 1; di < f; ++di) {
        const long i = ci + di;
        if (i < 0 || i >= static_cast<long>(rows)) continue;
        const double wi = static_cast<double>(f - std::labs(di));
        for (long dj = -f + 1; dj < f; ++dj) {
          const long j = cj + dj;
          if (j < 0 || j >= static_cast<long>(cols)) continue;
          const double w = wi * static_cast<double>(f - std::labs(dj));
          sum += w * eta[static_cast<std::size_t>(i) * cols + static_cast<std::size_t>(j)];
          wsum += w;
        }
      }
      out[l * vc + k] = static_cast<float>(sum / wsum);
    }
  }
}

bool snell_slope_derivatives(const ViewRays& view, const glm::dvec3& p, double dx, const RefractionParams& params,
                             glm::dvec2& d_eta_u, glm::dvec2& d_eta_v) {
  // snell_ground_point at rest (n = up) and its first-order change when the normal tilts by
  // dn = (-eta_u, -eta_v, 0) / (2 dx) (normal_from_differences to first order):
  //   t = r d + (r c - sqrt(k)) n,  c = -n.d,  k = 1 - r^2 (1 - c^2)
  //   dc = -dn.d,  dt = dc (r - r^2 c / sqrt(k)) n + (r c - sqrt(k)) dn
  //   G = P_xy + s t_xy,  s = (ground_z - P_z) / t_z  =>  dG = s (dt_xy - t_xy dt_z / t_z)
  const glm::dvec3 d = view.toward(p);
  const double sigma = d.z > 0.0 ? -1.0 : 1.0;  // the flip of snell_ground_point: n faces the ray
  const glm::dvec3 n(0.0, 0.0, sigma);
  const double r = 1.0 / params.index, c = -glm::dot(n, d);
  const double k = 1.0 - r * r * (1.0 - c * c);
  if (k <= 0.0) return false;
  const double sk = std::sqrt(k);
  const glm::dvec3 t = r * d + (r * c - sk) * n;
  if (t.z > -1e-6) return false;  // clamped in snell_ground_point: not differentiable this way
  const double s = (params.ground_z - p.z) / t.z;
  auto dG = [&](const glm::dvec3& dn_raw) {
    const glm::dvec3 dn = sigma * dn_raw;
    const double dc = -glm::dot(dn, d);
    const glm::dvec3 dt = dc * (r - r * r * c / sk) * n + (r * c - sk) * dn;
    return s * (glm::dvec2(dt.x, dt.y) - glm::dvec2(t.x, t.y) * (dt.z / t.z));
  };
  d_eta_u = dG(glm::dvec3(-1.0 / (2.0 * dx), 0.0, 0.0));
  d_eta_v = dG(glm::dvec3(0.0, -1.0 / (2.0 * dx), 0.0));
  return true;
}

namespace {
// (c, d, e, f) at one point by central differences of snell_ground_point (the reference path)
void numerical_slope_derivatives(const ViewRays& view, const glm::dvec3& p, double dx, const RefractionParams& params,
                                 glm::dvec2& du, glm::dvec2& dv) {
  const double hs = 1e-4 * dx;
  du = (snell_ground_point(view, p, normal_from_differences(hs, 0.0, dx), params) -
        snell_ground_point(view, p, normal_from_differences(-hs, 0.0, dx), params)) /
       (2.0 * hs);
  dv = (snell_ground_point(view, p, normal_from_differences(0.0, hs, dx), params) -
        snell_ground_point(view, p, normal_from_differences(0.0, -hs, dx), params)) /
       (2.0 * hs);
}

void slope_derivatives(const ViewRays& view, const glm::dvec3& p, double dx, const RefractionParams& params,
                       bool analytic, glm::dvec2& du, glm::dvec2& dv) {
  if (!analytic || !snell_slope_derivatives(view, p, dx, params, du, dv))
    numerical_slope_derivatives(view, p, dx, params, du, dv);
}

void store_cdef(float* o, const glm::dvec2& du, const glm::dvec2& dv) {
  o[0] = static_cast<float>(du.x);  // c
  o[1] = static_cast<float>(dv.x);  // d
  o[2] = static_cast<float>(du.y);  // e
  o[3] = static_cast<float>(dv.y);  // f
}

// Cell k of the mesh axis `idx` holding grid index g (the last cell for the last point), and
// the linear weight s in [0, 1] of its upper end.
void axis_cell(const std::vector<std::size_t>& idx, std::size_t g, std::size_t& k, double& s) {
  k = static_cast<std::size_t>(std::upper_bound(idx.begin(), idx.end(), g) - idx.begin());
  k = std::clamp<std::size_t>(k, 1, idx.size() - 1) - 1;
  s = static_cast<double>(g - idx[k]) / static_cast<double>(idx[k + 1] - idx[k]);
}
}  // namespace

LinearRefraction linearise_refraction(const GridPlacement& grid, const SurfaceMeshLayout& layout, const ViewRays& view,
                                      const RefractionParams& params, const LinearisationMethod& method) {
  LinearRefraction lin;
  const glm::dvec3 up(0.0, 0.0, 1.0);
  // step of the numerical derivative in height: small against the depth, large against rounding
  const double he = 1e-4 * std::max(1.0, -params.ground_z);
  const std::size_t vr = layout.vertex_rows(), vc = layout.vertex_cols();
  lin.vertex.resize(4 * vr * vc);
  // (c, d, e, f) at the mesh vertices too when the grid values are interpolated from them
  std::vector<float> coarse(method.coarse ? 4 * vr * vc : 0);
  for (std::size_t l = 0; l < vr; ++l) {
    for (std::size_t k = 0; k < vc; ++k) {
      const double x = grid.x(layout.col_idx[k]), y = grid.y(layout.row_idx[l]);
      const glm::dvec2 g0 = snell_ground_point(view, {x, y, 0.0}, up, params);
      const glm::dvec2 gp = snell_ground_point(view, {x, y, he}, up, params);
      const glm::dvec2 gm = snell_ground_point(view, {x, y, -he}, up, params);
      const glm::dvec2 ab = (gp - gm) / (2.0 * he);
      float* o = &lin.vertex[4 * (l * vc + k)];
      o[0] = static_cast<float>(g0.x);
      o[1] = static_cast<float>(g0.y);
      o[2] = static_cast<float>(ab.x);
      o[3] = static_cast<float>(ab.y);
      if (method.coarse) {
        glm::dvec2 du, dv;
        slope_derivatives(view, {x, y, 0.0}, grid.dx, params, method.analytic, du, dv);
        store_cdef(&coarse[4 * (l * vc + k)], du, dv);
      }
    }
  }
  lin.grid.resize(4 * grid.rows * grid.cols);
  if (!method.coarse) {
    for (std::size_t i = 0; i < grid.rows; ++i)
      for (std::size_t j = 0; j < grid.cols; ++j) {
        glm::dvec2 du, dv;
        slope_derivatives(view, {grid.x(j), grid.y(i), 0.0}, grid.dx, params, method.analytic, du, dv);
        store_cdef(&lin.grid[4 * (i * grid.cols + j)], du, dv);
      }
    return lin;
  }
  // bilinear over the mesh cells: the coefficients vary on the scale of the view distance, the
  // cells are `factor` grid points wide
  std::vector<std::size_t> kc(grid.cols);
  std::vector<float> sc(grid.cols);
  for (std::size_t j = 0; j < grid.cols; ++j) {
    double s;
    axis_cell(layout.col_idx, j, kc[j], s);
    sc[j] = static_cast<float>(s);
  }
  for (std::size_t i = 0; i < grid.rows; ++i) {
    std::size_t l;
    double t;
    axis_cell(layout.row_idx, i, l, t);
    const float tf = static_cast<float>(t);
    const float* r0 = &coarse[4 * l * vc];
    const float* r1 = &coarse[4 * (l + 1) * vc];
    float* out = &lin.grid[4 * i * grid.cols];
    for (std::size_t j = 0; j < grid.cols; ++j) {
      const std::size_t k = kc[j];
      const float s = sc[j];
      const float w00 = (1 - s) * (1 - tf), w01 = s * (1 - tf), w10 = (1 - s) * tf, w11 = s * tf;
      for (int q = 0; q < 4; ++q)
        out[4 * j + q] =
            w00 * r0[4 * k + q] + w01 * r0[4 * (k + 1) + q] + w10 * r1[4 * k + q] + w11 * r1[4 * (k + 1) + q];
    }
  }
  return lin;
}

namespace {
// Cell of the mesh containing grid index g along one axis, and the local coordinate in [0, 1].
void locate(const std::vector<std::size_t>& idx, std::size_t g, std::size_t& cell, double& s) {
  const auto it = std::upper_bound(idx.begin(), idx.end(), g);
  std::size_t k = static_cast<std::size_t>(it - idx.begin());
  k = std::clamp<std::size_t>(k, 1, idx.size() - 1) - 1;
  cell = k;
  s = static_cast<double>(g - idx[k]) / static_cast<double>(idx[k + 1] - idx[k]);
}

// Barycentric weights (w00, w10, w01, w11) of the triangles (00, 10, 11) and (00, 11, 01).
void tri_weights(double s, double t, double w[4]) {
  if (s >= t) {
    w[0] = 1.0 - s;
    w[1] = s - t;
    w[2] = 0.0;
    w[3] = t;
  } else {
    w[0] = 1.0 - t;
    w[1] = 0.0;
    w[2] = t - s;
    w[3] = s;
  }
}

struct Corner {
  std::size_t v[4];  // vertex indices 00, 10, 01, 11
  double w[4];
};

Corner corner(const SurfaceMeshLayout& layout, std::size_t i, std::size_t j) {
  std::size_t k, l;
  double s, t;
  locate(layout.col_idx, j, k, s);
  locate(layout.row_idx, i, l, t);
  Corner c;
  const std::size_t vc = layout.vertex_cols();
  c.v[0] = l * vc + k;
  c.v[1] = l * vc + k + 1;
  c.v[2] = (l + 1) * vc + k;
  c.v[3] = (l + 1) * vc + k + 1;
  tri_weights(s, t, c.w);
  return c;
}
}  // namespace

glm::dvec2 linear_ground_point(const GridPlacement& grid, const SurfaceMeshLayout& layout, const LinearRefraction& lin,
                               std::span<const float> mesh_heights, std::span<const float> diffs, std::size_t i,
                               std::size_t j) {
  const Corner c = corner(layout, i, j);
  glm::dvec2 g(0.0);
  for (int q = 0; q < 4; ++q) {
    const float* o = &lin.vertex[4 * c.v[q]];
    const double h = mesh_heights[c.v[q]];
    g += c.w[q] * glm::dvec2(o[0] + h * o[2], o[1] + h * o[3]);
  }
  const std::size_t p = i * grid.cols + j;
  const float* cf = &lin.grid[4 * p];
  const double eu = diffs[2 * p], ev = diffs[2 * p + 1];
  g.x += cf[0] * eu + cf[1] * ev;
  g.y += cf[2] * eu + cf[3] * ev;
  return g;
}

glm::dvec2 exact_ground_point(const GridPlacement& grid, const SurfaceMeshLayout& layout,
                              std::span<const float> mesh_heights, std::span<const float> diffs, const ViewRays& view,
                              const RefractionParams& params, std::size_t i, std::size_t j) {
  const Corner c = corner(layout, i, j);
  double h = 0.0;
  for (int q = 0; q < 4; ++q) h += c.w[q] * mesh_heights[c.v[q]];
  const std::size_t p = i * grid.cols + j;
  const glm::dvec3 n = normal_from_differences(diffs[2 * p], diffs[2 * p + 1], grid.dx);
  return snell_ground_point(view, {grid.x(j), grid.y(i), h}, n, params);
}

RefractionError compare_refraction(const GridPlacement& grid, std::size_t factor, std::span<const float> eta,
                                   const ViewRays& view, const RefractionParams& params, double texel_m) {
  const SurfaceMeshLayout layout = make_mesh_layout(grid.rows, grid.cols, factor);
  std::vector<float> mesh(layout.vertex_rows() * layout.vertex_cols());
  subsample_heights(eta, grid.rows, grid.cols, factor, layout, mesh);
  std::vector<float> diffs(2 * grid.rows * grid.cols);
  height_differences(eta, grid.rows, grid.cols, diffs);
  const LinearRefraction lin = linearise_refraction(grid, layout, view, params);
  RefractionError err;
  double sum = 0.0;
  for (std::size_t i = 0; i < grid.rows; ++i) {
    for (std::size_t j = 0; j < grid.cols; ++j) {
      const glm::dvec2 a = linear_ground_point(grid, layout, lin, mesh, diffs, i, j);
      const glm::dvec2 b = exact_ground_point(grid, layout, mesh, diffs, view, params, i, j);
      const double e = glm::length(a - b) / texel_m;
      err.max_texels = std::max(err.max_texels, e);
      sum += e;
    }
  }
  err.mean_texels = sum / static_cast<double>(grid.rows * grid.cols);
  return err;
}

}  // namespace huygens
