// Heightfield extraction of paper 000, eq. 5-6: see huygens/sph/surface.hpp.
#include "huygens/sph/surface.hpp"

#include <algorithm>
#include <cmath>

namespace huygens {

float sph_flat_iso(float radius, float spacing) {
  const int m = static_cast<int>(std::ceil(radius / spacing)) + 1;
  const double R2 = double(radius) * radius;
  double acc = 0;
  int samples = 0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const double ox = 0.25 * a * spacing, oy = 0.25 * b * spacing, oz = 0.5 * spacing;
      double phi = 0;
      for (int k = 0; k <= m; ++k)
        for (int j = -m; j <= m + 1; ++j)
          for (int i = -m; i <= m + 1; ++i) {
            const double dx = ox - i * spacing, dy = oy - j * spacing, dz = oz + k * spacing;
            const double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 < R2) phi += std::sqrt(1.0 - r2 / R2);
          }
      acc += phi;
      ++samples;
    }
  return static_cast<float>(acc / samples);
}

float sph_phi(const SphGrid& grid, const float* x, const float* y, const float* z, float radius, float px, float py,
              float pz) {
  const int cx = grid.ix(px), cy = grid.iy(py), cz = grid.iz(pz);
  const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, grid.nx() - 1);
  const float inv_r2 = 1.f / (radius * radius);
  float phi = 0.f;
  for (int kz = std::max(cz - 1, 0); kz <= std::min(cz + 1, grid.nz() - 1); ++kz)
    for (int ky = std::max(cy - 1, 0); ky <= std::min(cy + 1, grid.ny() - 1); ++ky) {
      std::uint32_t b, e;
      grid.row_range(x0, x1, ky, kz, b, e);
#pragma omp simd reduction(+ : phi)
      for (std::uint32_t j = b; j < e; ++j) {
        const float dx = px - x[j], dy = py - y[j], dz = pz - z[j];
        const float q = std::max(1.f - (dx * dx + dy * dy + dz * dz) * inv_r2, 0.f);
        phi += std::sqrt(q);
      }
    }
  return phi;
}

void sph_heightfield_init(const SphSurfaceParams& p, float lx, float ly, SphHeightfield& out) {
  out.cols = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(lx / p.cell_m - 1e-4f)));
  out.rows = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(ly / p.cell_m - 1e-4f)));
  out.cell_m = p.cell_m;
  out.lx_m = lx;
  out.ly_m = ly;
  out.height.assign(out.rows * out.cols, 0.f);
  out.normal.assign(out.rows * out.cols * 3, 0.f);
}

namespace {

// The evaluation points whose phi adds up to the phi of the particles AND their mirror images across
// the container walls x = 0, x = lx, y = 0, y = ly and the floor z = 0 within R (phi of an image
// at p equals phi of the particle at the mirrored point): for the surface only (the solver samples
// the walls with boundary particles, which the heightfield does not see), so a
// column next to a wall sees the fluid continue instead of dipping. Returns the count (<= 12).
int mirror_points(float xc, float yc, float R, float lx, float ly, float* mx, float* my) {
  float xs[3] = {xc, 0.f, 0.f}, ys[3] = {yc, 0.f, 0.f};
  int nx = 1, ny = 1;
  if (lx > 0.f) {
    if (xc < R) xs[nx++] = -xc;
    if (lx - xc < R) xs[nx++] = 2.f * lx - xc;
  }
  if (ly > 0.f) {
    if (yc < R) ys[ny++] = -yc;
    if (ly - yc < R) ys[ny++] = 2.f * ly - yc;
  }
  int n = 0;
  for (int b = 0; b < ny; ++b)
    for (int a = 0; a < nx; ++a) {
      mx[n] = xs[a];
      my[n] = ys[b];
      ++n;
    }
  return n;
}

float phi_mirrored(const SphGrid& grid, const float* x, const float* y, const float* z, float R, int np,
                   const float* mx, const float* my, float pz, bool floor) {
  float phi = 0.f;
  for (int k = 0; k < np; ++k) {
    phi += sph_phi(grid, x, y, z, R, mx[k], my[k], pz);
    if (floor && pz < R) phi += sph_phi(grid, x, y, z, R, mx[k], my[k], -pz);
  }
  return phi;
}

}  // namespace

void sph_extract_heightfield(const SphSurfaceParams& p, const SphGrid& grid, const float* x, const float* y,
                             const float* z, SphHeightfield& out) {
  const std::size_t rows = out.rows, cols = out.cols;
  const float R = p.radius_m, R2 = R * R, cell = out.cell_m;
  const std::size_t total = rows * cols;
  const bool floor = out.lx_m > 0.f;
#pragma omp parallel for schedule(static) if (total > 1024)
  for (std::size_t idx = 0; idx < total; ++idx) {
    const std::size_t r = idx / cols, c = idx % cols;
    const float xc = (static_cast<float>(c) + 0.5f) * cell, yc = (static_cast<float>(r) + 0.5f) * cell;
    float mx[9], my[9];
    const int np = mirror_points(xc, yc, R, out.lx_m, out.ly_m, mx, my);
    // highest point where phi becomes non-zero: top of the highest sphere of radius R over the column
    // (or over one of its mirrored columns)
    float ztop = -1.f;
    for (int k = 0; k < np; ++k) {
      const int cx = grid.ix(mx[k]), cy = grid.iy(my[k]);
      const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, grid.nx() - 1);
      const int y0 = std::max(cy - 1, 0), y1 = std::min(cy + 1, grid.ny() - 1);
      int found_layer = -1;
      for (int kz = grid.nz() - 1; kz >= 0 && kz >= found_layer - 1; --kz) {
        for (int ky = y0; ky <= y1; ++ky) {
          std::uint32_t b, e;
          grid.row_range(x0, x1, ky, kz, b, e);
          for (std::uint32_t j = b; j < e; ++j) {
            const float dx = mx[k] - x[j], dy = my[k] - y[j];
            const float q = R2 - dx * dx - dy * dy;
            if (q > 0.f) {
              ztop = std::max(ztop, z[j] + std::sqrt(q));
              if (found_layer < 0) found_layer = kz;
            }
          }
        }
      }
    }
    float height = 0.f;
    if (ztop > 0.f) {
      // march down in steps of R/4 until phi >= iso, then bisect
      const float step = 0.25f * R;
      float zhi = ztop, zlo = -1.f;
      for (float zz = ztop - step; zz > -step; zz -= step) {
        const float zq = std::max(zz, 0.f);
        if (phi_mirrored(grid, x, y, z, R, np, mx, my, zq, floor) >= p.iso) {
          zlo = zq;
          break;
        }
        zhi = zq;
      }
      if (zlo >= 0.f) {
        for (int it = 0; it < p.bisections; ++it) {
          const float zm = 0.5f * (zlo + zhi);
          if (phi_mirrored(grid, x, y, z, R, np, mx, my, zm, floor) >= p.iso)
            zlo = zm;
          else
            zhi = zm;
        }
        height = 0.5f * (zlo + zhi);
      }
    }
    out.height[idx] = height;
  }
  // normals from central differences (one-sided at the border)
#pragma omp parallel for schedule(static) if (total > 1024)
  for (std::size_t idx = 0; idx < total; ++idx) {
    const std::size_t r = idx / cols, c = idx % cols;
    const std::size_t cl = c > 0 ? c - 1 : c, cr = c + 1 < cols ? c + 1 : c;
    const std::size_t rl = r > 0 ? r - 1 : r, rr = r + 1 < rows ? r + 1 : r;
    const float hx =
        (cr > cl) ? (out.height[r * cols + cr] - out.height[r * cols + cl]) / (float(cr - cl) * cell) : 0.f;
    const float hy =
        (rr > rl) ? (out.height[rr * cols + c] - out.height[rl * cols + c]) / (float(rr - rl) * cell) : 0.f;
    const float inv = 1.f / std::sqrt(hx * hx + hy * hy + 1.f);
    out.normal[3 * idx] = -hx * inv;
    out.normal[3 * idx + 1] = -hy * inv;
    out.normal[3 * idx + 2] = inv;
  }
}

}  // namespace huygens
