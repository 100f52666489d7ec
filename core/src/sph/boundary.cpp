// Container mirror images and obstacle ghost tables: see huygens/sph/boundary.hpp.
#include "huygens/sph/boundary.hpp"

#include <algorithm>
#include <cmath>

namespace huygens {

float SphObstacle::distance(float px, float py, float pz, float n[3]) const {
  if (type == Type::box) {
    const float c[3] = {0.5f * (min_m[0] + max_m[0]), 0.5f * (min_m[1] + max_m[1]), 0.5f * (min_m[2] + max_m[2])};
    const float e[3] = {0.5f * (max_m[0] - min_m[0]), 0.5f * (max_m[1] - min_m[1]), 0.5f * (max_m[2] - min_m[2])};
    const float p[3] = {px - c[0], py - c[1], pz - c[2]};
    float q[3], outside2 = 0.f, inside = -1e30f;
    int axis = 0;
    for (int k = 0; k < 3; ++k) {
      q[k] = std::fabs(p[k]) - e[k];
      if (q[k] > 0.f) outside2 += q[k] * q[k];
      if (q[k] > inside) {
        inside = q[k];
        axis = k;
      }
    }
    if (outside2 > 0.f) {
      const float d = std::sqrt(outside2);
      for (int k = 0; k < 3; ++k) n[k] = q[k] > 0.f ? std::copysign(q[k], p[k]) / d : 0.f;
      return d;
    }
    for (int k = 0; k < 3; ++k) n[k] = 0.f;
    n[axis] = std::copysign(1.f, p[axis]);
    return inside;
  }
  // vertical cylinder between z0 and z1
  const float dx = px - centre_m[0], dy = py - centre_m[1];
  const float rho = std::sqrt(dx * dx + dy * dy);
  const float dr = rho - radius_m;
  const float zc = 0.5f * (z0_m + z1_m), ez = 0.5f * (z1_m - z0_m);
  const float dz = std::fabs(pz - zc) - ez;
  const float nr[2] = {rho > 1e-12f ? dx / rho : 1.f, rho > 1e-12f ? dy / rho : 0.f};
  if (dr > 0.f && dz > 0.f) {
    const float d = std::sqrt(dr * dr + dz * dz);
    n[0] = nr[0] * dr / d;
    n[1] = nr[1] * dr / d;
    n[2] = std::copysign(dz, pz - zc) / d;
    return d;
  }
  if (dr >= dz) {
    n[0] = nr[0];
    n[1] = nr[1];
    n[2] = 0.f;
    return dr;
  }
  n[0] = n[1] = 0.f;
  n[2] = std::copysign(1.f, pz - zc);
  return dz;
}

// The images of every subset of the planes within h that holds at most one plane per axis: a
// per-axis sign flip x_a' = 2 w_a - x_a (see the header for o, s, G0 and gs).
int sph_container_images(float x, float y, float z, float h, const std::array<float, 3>& container_m,
                         const std::array<float, 3>& g, SphImage* out) {
  struct Pl {
    int axis;
    float w;
  } pl[6];
  int np = 0;
  const float pos[3] = {x, y, z};
  for (int a = 0; a < 3; ++a) {
    if (pos[a] < h) pl[np++] = {a, 0.f};
    if (container_m[a] - pos[a] < h) pl[np++] = {a, container_m[a]};
  }
  int n = 0;
  for (int mask = 1; mask < (1 << np); ++mask) {
    int axes = 0;
    bool ok = true;
    for (int k = 0; k < np && ok; ++k)
      if (mask & (1 << k)) {
        ok = !(axes & (1 << pl[k].axis));
        axes |= 1 << pl[k].axis;
      }
    if (!ok) continue;
    SphImage im{};
    for (int a = 0; a < 3; ++a) {
      im.o[a] = pos[a];
      im.s[a] = -1.f;
      im.gs[a] = 0.f;
    }
    im.G0 = 0.f;
    for (int k = 0; k < np; ++k)
      if (mask & (1 << k)) {
        const int a = pl[k].axis;
        im.o[a] = pos[a] - 2.f * pl[k].w;
        im.s[a] = 1.f;
        if (a == 2 && pl[k].w == 0.f) im.floor = 1;
        im.G0 += 2.f * g[a] * pl[k].w;
        im.gs[a] = -2.f * g[a];
      }
    out[n++] = im;
  }
  return n;
}

// ---------------------------------------------------------------------------------------------
// obstacles: ghost lattices behind one plane, tabulated over the distance

namespace {

// Sums over the ghost lattice beyond `np` perpendicular planes at distances d[0..np-1] from the
// particle (particle at the origin, plane a normal to axis a, ghosts at -(d_a + dx/2 + k dx) on
// plane axes and at i dx on the others). D = m sum W_poly6 and F = 2 (-dD/dd_0) = 2 m sum 6 K (h^2 - r^2)^2 r_0:
// the mirrored pressure (factor 2) along the first plane's normal of minus the gradient of D.
void ghost_sums(const SphKernels& k, float dx, float m, int np, const double* d, double& D, double& F) {
  const double h = k.h, h2 = double(k.h) * k.h;
  const int M = static_cast<int>(std::ceil(h / dx)) + 1;
  D = F = 0;
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = a < np ? 0 : -M;
    hi[a] = M;
  }
  for (int i = lo[0]; i <= hi[0]; ++i)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int l = lo[2]; l <= hi[2]; ++l) {
        const int idx[3] = {i, j, l};
        double c[3];
        for (int a = 0; a < 3; ++a) c[a] = a < np ? d[a] + dx * (0.5 + idx[a]) : double(dx) * idx[a];
        const double r2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        if (r2 >= h2) continue;
        D += m * double(k.poly6(static_cast<float>(r2)));
        F += 2.0 * m * 6.0 * double(k.poly6_k) * (h2 - r2) * (h2 - r2) * c[0];
      }
}

struct Plane {
  float d;     // distance from the particle (>= 0)
  float n[3];  // unit normal into the fluid
};

inline float lerp1(const std::vector<float>& t, float inv, int n, float d) {
  const float u = std::min(std::max(d, 0.f) * inv, float(n));
  const int i = std::min(static_cast<int>(u), n);
  const float f = u - i;
  return (1.f - f) * t[i] + f * t[i + 1];
}

// the obstacle surfaces within the support radius h of a particle (at most 16)
inline int near_obstacles(const std::vector<SphObstacle>& obs, float h, float x, float y, float z, Plane* out) {
  int n = 0;
  for (const auto& o : obs) {
    if (n >= 16) break;
    if (!o.near(x, y, z, h)) continue;
    Plane p{};
    p.d = o.distance(x, y, z, p.n);
    if (p.d < h) out[n++] = p;
  }
  return n;
}

}  // namespace

SphObstacleWalls::SphObstacleWalls(const std::vector<SphObstacle>& obstacles, const SphKernels& k, float spacing,
                                   float mass)
    : obstacles_(obstacles), h_(k.h) {
  n1_ = 256;
  inv1_ = n1_ / h_;
  const int s1 = n1_ + 2;
  d1_.assign(s1, 0.f);
  f1_.assign(s1, 0.f);
  double D, F;
  for (int a = 0; a < s1; ++a) {
    const double d[1] = {double(a) / inv1_};
    ghost_sums(k, spacing, mass, 1, d, D, F);
    d1_[a] = static_cast<float>(D);
    f1_[a] = static_cast<float>(F);
  }
}

void SphObstacleWalls::add_density_near(float x, float y, float z, float& rho) const {
  Plane pl[16];
  const int n = near_obstacles(obstacles_, h_, x, y, z, pl);
  for (int a = 0; a < n; ++a) rho += lerp1(d1_, inv1_, n1_, pl[a].d);
}

void SphObstacleWalls::add_force_near(float x, float y, float z, float P, float& ax, float& ay, float& az) const {
  Plane pl[16];
  const int n = near_obstacles(obstacles_, h_, x, y, z, pl);
  for (int a = 0; a < n; ++a) {
    const float f = P * lerp1(f1_, inv1_, n1_, pl[a].d);
    ax += f * pl[a].n[0];
    ay += f * pl[a].n[1];
    az += f * pl[a].n[2];
  }
}

}  // namespace huygens
