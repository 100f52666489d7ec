// 3D SPH of paper 000 after MCG03: see sph.hpp for the equations.
#include "huygens/sph.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "huygens/finite.hpp"
#include "huygens/solver.hpp"

namespace huygens {

namespace {
constexpr double kPi = std::numbers::pi;
// below this many particles a step is a few hundred microseconds: threads cost more than they give
constexpr std::size_t kParallelMin = 2048;
}  // namespace

// ---------------------------------------------------------------------------------------------
// kernels

SphKernels::SphKernels(float support)
    : h(support),
      h2(support * support),
      poly6_k(static_cast<float>(315.0 / (64.0 * kPi * std::pow(double(support), 9)))),
      spiky_k(static_cast<float>(45.0 / (kPi * std::pow(double(support), 6)))) {}

float SphKernels::viscosity(float r) const {
  if (r >= h || r <= 0.f) return 0.f;
  const double hd = h, rd = r;
  return static_cast<float>(15.0 / (2.0 * kPi * hd * hd * hd) *
                            (-rd * rd * rd / (2 * hd * hd * hd) + rd * rd / (hd * hd) + hd / (2 * rd) - 1.0));
}

// ---------------------------------------------------------------------------------------------
// obstacles

float SphObstacle::distance(float px, float py, float pz, float n[3]) const {
  if (type == Type::box) {
    const float c[3] = {0.5f * (min[0] + max[0]), 0.5f * (min[1] + max[1]), 0.5f * (min[2] + max[2])};
    const float e[3] = {0.5f * (max[0] - min[0]), 0.5f * (max[1] - min[1]), 0.5f * (max[2] - min[2])};
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
  const float dx = px - centre[0], dy = py - centre[1];
  const float rho = std::sqrt(dx * dx + dy * dy);
  const float dr = rho - radius;
  const float zc = 0.5f * (z0 + z1), ez = 0.5f * (z1 - z0);
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

// ---------------------------------------------------------------------------------------------
// construction

void SphSystem::allocate(std::size_t n) {
  n_ = n;
  for (auto* b : {&x_, &y_, &z_, &vx_, &vy_, &vz_, &ax_, &ay_, &az_, &rho_, &P_, &irho_, &p_arr_, &tx_, &ty_, &tz_,
                  &tvx_, &tvy_, &tvz_})
    *b = AlignedBuffer<float>(n + 8);  // padded to whole vectors (masked lanes read the zero tail)
  id_.assign(n, 0);
  tid_.assign(n, 0);
  grid_ = SphGrid(p_.container, h_, n);
}

SphSystem::SphSystem(const SphParams& params, std::size_t dt_history)
    : p_(params), k_(params.support()), h_(params.support()), g_(params.gravity), damping_(params.damping) {
  const float dx = p_.spacing;
  if (!(dx > 0.f)) throw std::invalid_argument("particle spacing must be positive");
  if (!(p_.support_factor >= 1.f && p_.support_factor <= 4.f))
    throw std::invalid_argument("support_factor must be in [1, 4]");
  for (int a = 0; a < 3; ++a)
    if (!(p_.container[a] >= 2.f * dx)) throw std::invalid_argument("container must be at least two spacings wide");
  if (!(p_.rest_density > 0.f) || !(p_.viscosity >= 0.f) || !(p_.artificial_viscosity >= 0.f))
    throw std::invalid_argument("bad density or viscosity");

  // mass: the poly6 sum over a lattice of the spacing equals rho0 exactly
  double lattice = 0.0;
  const int R = static_cast<int>(std::ceil(p_.support_factor)) + 1;
  for (int i = -R; i <= R; ++i)
    for (int j = -R; j <= R; ++j)
      for (int k = -R; k <= R; ++k) lattice += k_.poly6(float(i * i + j * j + k * k) * dx * dx);
  mass_ = static_cast<float>(p_.rest_density / lattice);

  // fluid blocks on the lattice of cell centres (i + 1/2) dx
  std::vector<float> px, py, pz;
  float top = 0.f;
  for (const auto& b : p_.fluid) {
    const int n0 = static_cast<int>(std::floor(b.min[0] / dx + 0.5f)),
              n1 = static_cast<int>(std::floor(b.max[0] / dx + 0.5f));
    const int m0 = static_cast<int>(std::floor(b.min[1] / dx + 0.5f)),
              m1 = static_cast<int>(std::floor(b.max[1] / dx + 0.5f));
    const int l0 = static_cast<int>(std::floor(b.min[2] / dx + 0.5f)),
              l1 = static_cast<int>(std::floor(b.max[2] / dx + 0.5f));
    for (int k = l0; k < l1; ++k)
      for (int j = m0; j < m1; ++j)
        for (int i = n0; i < n1; ++i) {
          const float X = (i + 0.5f) * dx, Y = (j + 0.5f) * dx, Z = (k + 0.5f) * dx;
          if (X < 0 || Y < 0 || Z < 0 || X > p_.container[0] || Y > p_.container[1] || Z > p_.container[2]) continue;
          bool blocked = false;
          float nrm[3];
          for (const auto& o : p_.obstacles) blocked = blocked || o.distance(X, Y, Z, nrm) < 0.5f * dx;
          if (blocked) continue;
          px.push_back(X);
          py.push_back(Y);
          pz.push_back(Z);
        }
    top = std::max(top, b.max[2]);
  }
  const float gmag = std::sqrt(g_[0] * g_[0] + g_[1] * g_[1] + g_[2] * g_[2]);
  c0_ = p_.sound_speed > 0.f ? p_.sound_speed : 10.f * std::sqrt(2.f * std::max(gmag, 1e-3f) * std::max(top, dx));
  B_ = p_.rest_density * c0_ * c0_ / p_.tait_gamma;
  nu_ = p_.viscosity + p_.artificial_viscosity * c0_ * h_;

  build_wall_tables();

  dt_hist_.assign(std::max<std::size_t>(dt_history, 1), 0.0);
  sid_.neighbours = stats_.add("neighbour search");
  sid_.density = stats_.add("density");
  sid_.forces = stats_.add("forces");
  sid_.integration = stats_.add("integration");
  set_particles(px, py, pz);
}

void SphSystem::set_particles(std::span<const float> px, std::span<const float> py, std::span<const float> pz) {
  allocate(px.size());
  for (std::size_t i = 0; i < n_; ++i) {
    x_[i] = px[i];
    y_[i] = py[i];
    z_[i] = pz[i];
    vx_[i] = vy_[i] = vz_[i] = 0.f;
    id_[i] = static_cast<std::uint32_t>(i);
  }
  stats_[sid_.neighbours].bytes = grid_.bytes() + n_ * 8 * sizeof(float);
  stats_[sid_.density].bytes = n_ * 4 * sizeof(float);
  stats_[sid_.forces].bytes = n_ * 3 * sizeof(float);
  stats_[sid_.integration].bytes = n_ * 6 * sizeof(float);
  refresh();
}

std::vector<double> SphSystem::dt_history() const {
  std::vector<double> out;
  const std::size_t cap = dt_hist_.size();
  const std::size_t cnt = std::min<std::size_t>(cap, static_cast<std::size_t>(dts_.count));
  for (std::size_t k = 0; k < cnt; ++k) out.push_back(dt_hist_[(dt_head_ + cap - cnt + k) % cap]);
  return out;
}

// ---------------------------------------------------------------------------------------------
// neighbour search: counting sort by cell, gather every SoA array into the new order

void SphSystem::sort_particles() {
  grid_.build(x_.data(), y_.data(), z_.data(), n_);
  const std::uint32_t* ord = grid_.order();
  const std::size_t n = n_;
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t o = ord[i];
    tx_[i] = x_[o];
    ty_[i] = y_[o];
    tz_[i] = z_[o];
    tvx_[i] = vx_[o];
    tvy_[i] = vy_[o];
    tvz_[i] = vz_[o];
    tid_[i] = id_[o];
  }
  std::swap(x_, tx_);
  std::swap(y_, ty_);
  std::swap(z_, tz_);
  std::swap(vx_, tvx_);
  std::swap(vy_, tvy_);
  std::swap(vz_, tvz_);
  std::swap(id_, tid_);
}

// ---------------------------------------------------------------------------------------------
// boundary: ghost lattices behind the container planes, tabulated (see sph.hpp)

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

}  // namespace

void SphSystem::build_wall_tables() {
  const float dx = p_.spacing;
  auto& w = wt_;
  w.n1 = 256;
  w.n2 = 48;
  w.n3 = 24;
  w.inv1 = w.n1 / h_;
  w.inv2 = w.n2 / h_;
  w.inv3 = w.n3 / h_;
  const int s1 = w.n1 + 2, s2 = w.n2 + 2, s3 = w.n3 + 2;
  w.d1.assign(s1, 0.f);
  w.f1.assign(s1, 0.f);
  w.d2.assign(s2 * s2, 0.f);
  w.f2.assign(s2 * s2, 0.f);
  w.d3.assign(s3 * s3 * s3, 0.f);
  w.f3.assign(s3 * s3 * s3, 0.f);
  double D, F;
  for (int a = 0; a < s1; ++a) {
    const double d[1] = {double(a) / w.inv1};
    ghost_sums(k_, dx, mass_, 1, d, D, F);
    w.d1[a] = static_cast<float>(D);
    w.f1[a] = static_cast<float>(F);
  }
  for (int b = 0; b < s2; ++b)
    for (int a = 0; a < s2; ++a) {
      const double d[2] = {double(a) / w.inv2, double(b) / w.inv2};
      ghost_sums(k_, dx, mass_, 2, d, D, F);
      w.d2[a + s2 * b] = static_cast<float>(D);
      w.f2[a + s2 * b] = static_cast<float>(F);
    }
  for (int c = 0; c < s3; ++c)
    for (int b = 0; b < s3; ++b)
      for (int a = 0; a < s3; ++a) {
        const double d[3] = {double(a) / w.inv3, double(b) / w.inv3, double(c) / w.inv3};
        ghost_sums(k_, dx, mass_, 3, d, D, F);
        w.d3[a + s3 * (b + s3 * c)] = static_cast<float>(D);
        w.f3[a + s3 * (b + s3 * c)] = static_cast<float>(F);
      }
}

namespace {

struct Plane {
  float d;     // distance from the particle (>= 0)
  int axis;    // 0, 1, 2; -1 for an obstacle
  float n[3];  // unit normal into the fluid
};

inline float lerp1(const std::vector<float>& t, float inv, int n, float d) {
  const float u = std::min(std::max(d, 0.f) * inv, float(n));
  const int i = std::min(static_cast<int>(u), n);
  const float f = u - i;
  return (1.f - f) * t[i] + f * t[i + 1];
}

inline float lerp2(const std::vector<float>& t, float inv, int n, float da, float db) {
  const int s = n + 2;
  const float u = std::min(std::max(da, 0.f) * inv, float(n)), v = std::min(std::max(db, 0.f) * inv, float(n));
  const int i = std::min(static_cast<int>(u), n), j = std::min(static_cast<int>(v), n);
  const float fu = u - i, fv = v - j;
  const float* p = t.data() + i + s * j;
  return (1.f - fv) * ((1.f - fu) * p[0] + fu * p[1]) + fv * ((1.f - fu) * p[s] + fu * p[s + 1]);
}

inline float lerp3(const std::vector<float>& t, float inv, int n, float da, float db, float dc) {
  const int s = n + 2;
  const float u = std::min(std::max(da, 0.f) * inv, float(n)), v = std::min(std::max(db, 0.f) * inv, float(n)),
              w = std::min(std::max(dc, 0.f) * inv, float(n));
  const int i = std::min(static_cast<int>(u), n), j = std::min(static_cast<int>(v), n),
            k = std::min(static_cast<int>(w), n);
  const float fu = u - i, fv = v - j, fw = w - k;
  const float* p = t.data() + i + s * (j + s * k);
  auto bil = [&](const float* q) {
    return (1.f - fv) * ((1.f - fu) * q[0] + fu * q[1]) + fv * ((1.f - fu) * q[s] + fu * q[s + 1]);
  };
  return (1.f - fw) * bil(p) + fw * bil(p + s * s);
}

// the container planes (and obstacle surfaces) within the support radius of a particle
inline int near_planes(const SphParams& prm, const std::vector<SphObstacle>& obs, float h, float x, float y, float z,
                       Plane* out) {
  int n = 0;
  const float pos[3] = {x, y, z};
  for (int a = 0; a < 3; ++a) {
    if (pos[a] < h) {
      out[n] = {pos[a], a, {0.f, 0.f, 0.f}};
      out[n].n[a] = 1.f;
      ++n;
    }
    if (prm.container[a] - pos[a] < h) {
      out[n] = {prm.container[a] - pos[a], a, {0.f, 0.f, 0.f}};
      out[n].n[a] = -1.f;
      ++n;
    }
  }
  for (const auto& o : obs) {
    if (n >= 14) break;
    Plane p{};
    p.d = o.distance(x, y, z, p.n);
    p.axis = -1;
    if (p.d < h) out[n++] = p;
  }
  return n;
}

}  // namespace

void SphSystem::boundary_density(std::size_t i, float& rho) const {
  Plane pl[16];
  const int n = near_planes(p_, p_.obstacles, h_, x_[i], y_[i], z_[i], pl);
  if (n == 0) return;
  const auto& w = wt_;
  float r = 0.f;
  for (int a = 0; a < n; ++a) r += lerp1(w.d1, w.inv1, w.n1, pl[a].d);
  // inclusion-exclusion over container planes of different axes (edges and corners)
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      if (pl[a].axis < 0 || pl[b].axis < 0 || pl[a].axis == pl[b].axis) continue;
      r -= lerp2(w.d2, w.inv2, w.n2, pl[a].d, pl[b].d);
      for (int c = b + 1; c < n; ++c) {
        if (pl[c].axis < 0 || pl[c].axis == pl[a].axis || pl[c].axis == pl[b].axis) continue;
        r += lerp3(w.d3, w.inv3, w.n3, pl[a].d, pl[b].d, pl[c].d);
      }
    }
  rho += r;
}

void SphSystem::boundary_force(std::size_t i, float P, float& ax, float& ay, float& az) const {
  if (P <= 0.f) return;
  Plane pl[16];
  const int n = near_planes(p_, p_.obstacles, h_, x_[i], y_[i], z_[i], pl);
  if (n == 0) return;
  const auto& w = wt_;
  float f[3] = {0.f, 0.f, 0.f};
  auto add = [&](const Plane& q, float s) {
    f[0] += s * q.n[0];
    f[1] += s * q.n[1];
    f[2] += s * q.n[2];
  };
  for (int a = 0; a < n; ++a) add(pl[a], lerp1(w.f1, w.inv1, w.n1, pl[a].d));
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      if (pl[a].axis < 0 || pl[b].axis < 0 || pl[a].axis == pl[b].axis) continue;
      add(pl[a], -lerp2(w.f2, w.inv2, w.n2, pl[a].d, pl[b].d));
      add(pl[b], -lerp2(w.f2, w.inv2, w.n2, pl[b].d, pl[a].d));
      for (int c = b + 1; c < n; ++c) {
        if (pl[c].axis < 0 || pl[c].axis == pl[a].axis || pl[c].axis == pl[b].axis) continue;
        add(pl[a], lerp3(w.f3, w.inv3, w.n3, pl[a].d, pl[b].d, pl[c].d));
        add(pl[b], lerp3(w.f3, w.inv3, w.n3, pl[b].d, pl[a].d, pl[c].d));
        add(pl[c], lerp3(w.f3, w.inv3, w.n3, pl[c].d, pl[a].d, pl[b].d));
      }
    }
  ax += P * f[0];
  ay += P * f[1];
  az += P * f[2];
}

// ---------------------------------------------------------------------------------------------
// density and pressure: rho_i = m sum_j W_poly6 + walls; p = max(0, B ((rho/rho0)^gamma - 1))

void SphSystem::compute_density() {
  const std::size_t n = n_;
  const float* X = x_.data();
  const float* Y = y_.data();
  const float* Z = z_.data();
  const float h2 = k_.h2, mk = mass_ * k_.poly6_k, rho0 = p_.rest_density, inv_rho0 = 1.f / rho0;
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  const bool tait7 = p_.tait_gamma == 7.f;
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    const float xi = X[i], yi = Y[i], zi = Z[i];
    const int cx = grid_.ix(xi), cy = grid_.iy(yi), cz = grid_.iz(zi);
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx - 1);
    float sum = 0.f;
    for (int kz = std::max(cz - 1, 0); kz <= std::min(cz + 1, nz - 1); ++kz)
      for (int ky = std::max(cy - 1, 0); ky <= std::min(cy + 1, ny - 1); ++ky) {
        std::uint32_t b, e;
        grid_.row_range(x0, x1, ky, kz, b, e);
        // whole aligned vectors over [b0, e0) with the lanes outside [b, e) masked: no scalar remainder
        const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
#pragma omp simd reduction(+ : sum) aligned(X, Y, Z : 32)
        for (std::uint32_t j = b0; j < e0; ++j) {
          const float dx = xi - X[j], dy = yi - Y[j], dz = zi - Z[j];
          const float q = std::max(h2 - (dx * dx + dy * dy + dz * dz), 0.f);
          sum += (j >= b && j < e) ? q * q * q : 0.f;
        }
      }
    float rho = mk * sum;
    boundary_density(i, rho);
    rho_[i] = rho;
    const float ratio = rho * inv_rho0;
    float rg;
    if (tait7) {
      const float r2 = ratio * ratio, r4 = r2 * r2;
      rg = r4 * r2 * ratio;
    } else {
      rg = std::pow(ratio, p_.tait_gamma);
    }
    const float p = std::max(B_ * (rg - 1.f), 0.f);
    p_arr_[i] = p;
    irho_[i] = 1.f / rho;
    P_[i] = p / (rho * rho);
  }
}

// ---------------------------------------------------------------------------------------------
// forces: symmetric spiky pressure + viscosity Laplacian + gravity + walls

void SphSystem::compute_forces() {
  const std::size_t n = n_;
  const float* X = x_.data();
  const float* Y = y_.data();
  const float* Z = z_.data();
  const float* VX = vx_.data();
  const float* VY = vy_.data();
  const float* VZ = vz_.data();
  const float* PP = P_.data();
  const float* IR = irho_.data();
  const float h = h_, h2 = k_.h2, rmin = 1e-6f * h_;
  const float cp = mass_ * k_.spiky_k;                          // m 45/(pi h^6)
  const float cv = nu_ * p_.rest_density * mass_ * k_.spiky_k;  // nu rho0 m 45/(pi h^6)
  const float gx = g_[0], gy = g_[1], gz = g_[2];
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  float amax2 = 0.f, vmax2 = 0.f;
#pragma omp parallel for schedule(static) reduction(max : amax2, vmax2) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    const float xi = X[i], yi = Y[i], zi = Z[i], vxi = VX[i], vyi = VY[i], vzi = VZ[i], Pi = PP[i];
    const int cx = grid_.ix(xi), cy = grid_.iy(yi), cz = grid_.iz(zi);
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx - 1);
    float fpx = 0.f, fpy = 0.f, fpz = 0.f, fvx = 0.f, fvy = 0.f, fvz = 0.f;
    for (int kz = std::max(cz - 1, 0); kz <= std::min(cz + 1, nz - 1); ++kz)
      for (int ky = std::max(cy - 1, 0); ky <= std::min(cy + 1, ny - 1); ++ky) {
        std::uint32_t b, e;
        grid_.row_range(x0, x1, ky, kz, b, e);
        const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
#pragma omp simd reduction(+ : fpx, fpy, fpz, fvx, fvy, fvz) aligned(X, Y, Z, VX, VY, VZ, PP, IR : 32)
        for (std::uint32_t j = b0; j < e0; ++j) {
          const float dx = xi - X[j], dy = yi - Y[j], dz = zi - Z[j];
          const float r2 = dx * dx + dy * dy + dz * dz;
          const float r = std::sqrt(r2);
          const float hr = (r2 < h2 && j >= b && j < e) ? h - r : 0.f;
          // pressure: (P_i + P_j) (h - r)^2 / r along x_i - x_j (repulsive)
          const float fp = (Pi + PP[j]) * hr * hr / std::max(r, rmin);
          fpx += fp * dx;
          fpy += fp * dy;
          fpz += fp * dz;
          // viscosity: (v_j - v_i) (h - r) / rho_j
          const float fv = hr * IR[j];
          fvx += fv * (VX[j] - vxi);
          fvy += fv * (VY[j] - vyi);
          fvz += fv * (VZ[j] - vzi);
        }
      }
    const float vis = cv * IR[i];
    float ax = gx + cp * fpx + vis * fvx;
    float ay = gy + cp * fpy + vis * fvy;
    float az = gz + cp * fpz + vis * fvz;
    boundary_force(i, Pi, ax, ay, az);
    ax_[i] = ax;
    ay_[i] = ay;
    az_[i] = az;
    amax2 = std::max(amax2, ax * ax + ay * ay + az * az);
    vmax2 = std::max(vmax2, vxi * vxi + vyi * vyi + vzi * vzi);
  }
  amax_ = std::sqrt(amax2);
  vmax_ = std::sqrt(vmax2);
}

// ---------------------------------------------------------------------------------------------
// time step and integration

double SphSystem::choose_dt() {
  const double h = h_;
  double dt = p_.dt_max;
  const char* lim = "dt_max";
  const double dcfl = p_.cfl * h / (c0_ + vmax_);
  if (dcfl < dt) {
    dt = dcfl;
    lim = "cfl";
  }
  if (amax_ > 0.f) {
    const double df = p_.force_factor * std::sqrt(h / amax_);
    if (df < dt) {
      dt = df;
      lim = "force";
    }
  }
  if (nu_ > 0.f) {
    const double dv = p_.viscous_factor * h * h / nu_;
    if (dv < dt) {
      dt = dv;
      lim = "viscous";
    }
  }
  dts_.limiter = lim;
  return dt;
}

void SphSystem::integrate(float dt) {
  const std::size_t n = n_;
  const float damp = 1.f / (1.f + damping_ * dt);
  const float eps = 0.1f * p_.spacing;
  const float lo[3] = {eps, eps, eps};
  const float hi[3] = {p_.container[0] - eps, p_.container[1] - eps, p_.container[2] - eps};
  float* X = x_.data();
  float* Y = y_.data();
  float* Z = z_.data();
  float* VX = vx_.data();
  float* VY = vy_.data();
  float* VZ = vz_.data();
  const float* AX = ax_.data();
  const float* AY = ay_.data();
  const float* AZ = az_.data();
  // symplectic Euler
#pragma omp parallel for simd schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    VX[i] = (VX[i] + AX[i] * dt) * damp;
    VY[i] = (VY[i] + AY[i] * dt) * damp;
    VZ[i] = (VZ[i] + AZ[i] * dt) * damp;
    X[i] += VX[i] * dt;
    Y[i] += VY[i] * dt;
    Z[i] += VZ[i] * dt;
  }
  // no leakage: clamp into the container, remove the normal velocity into a wall
  auto clamp_axis = [](float& p, float& v, float a, float b) {
    if (p < a) {
      p = a;
      v = std::max(v, 0.f);
    }
    if (p > b) {
      p = b;
      v = std::min(v, 0.f);
    }
  };
  const bool obst = !p_.obstacles.empty();
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    clamp_axis(X[i], VX[i], lo[0], hi[0]);
    clamp_axis(Y[i], VY[i], lo[1], hi[1]);
    clamp_axis(Z[i], VZ[i], lo[2], hi[2]);
    if (obst) {
      float nrm[3];
      for (const auto& o : p_.obstacles) {
        const float d = o.distance(X[i], Y[i], Z[i], nrm);
        if (d < eps) {
          X[i] += (eps - d) * nrm[0];
          Y[i] += (eps - d) * nrm[1];
          Z[i] += (eps - d) * nrm[2];
          const float vn = VX[i] * nrm[0] + VY[i] * nrm[1] + VZ[i] * nrm[2];
          if (vn < 0.f) {
            VX[i] -= vn * nrm[0];
            VY[i] -= vn * nrm[1];
            VZ[i] -= vn * nrm[2];
          }
        }
      }
      clamp_axis(X[i], VX[i], lo[0], hi[0]);
      clamp_axis(Y[i], VY[i], lo[1], hi[1]);
      clamp_axis(Z[i], VZ[i], lo[2], hi[2]);
    }
  }
}

double SphSystem::step() {
  {
    StageTimer t(stats_[sid_.neighbours]);
    sort_particles();
  }
  {
    StageTimer t(stats_[sid_.density]);
    compute_density();
  }
  if (!all_finite(density())) throw NonFiniteError("density", steps_);
  {
    StageTimer t(stats_[sid_.forces]);
    compute_forces();
  }
  if (!all_finite({ax_.data(), n_}) || !all_finite({ay_.data(), n_}) || !all_finite({az_.data(), n_}))
    throw NonFiniteError("forces", steps_);
  double dt;
  {
    StageTimer t(stats_[sid_.integration]);
    dt = choose_dt();
    integrate(static_cast<float>(dt));
  }
  if (!all_finite(x()) || !all_finite(y()) || !all_finite(z()) || !all_finite(vx()) || !all_finite(vy()) ||
      !all_finite(vz()))
    throw NonFiniteError("integration", steps_);
  t_ += dt;
  ++steps_;
  // dt history (ring buffer, preallocated)
  dts_.last = dt;
  dts_.min = dts_.count ? std::min(dts_.min, dt) : dt;
  dts_.max = dts_.count ? std::max(dts_.max, dt) : dt;
  dts_.sum += dt;
  ++dts_.count;
  dt_hist_[dt_head_] = dt;
  dt_head_ = (dt_head_ + 1) % dt_hist_.size();
  return dt;
}

void SphSystem::refresh() {
  sort_particles();
  compute_density();
  compute_forces();
  dts_.limiter = "dt_max";
}

// ---------------------------------------------------------------------------------------------
// outputs and interaction

void SphSystem::positions_by_id(std::span<float> out) const {
  for (std::size_t i = 0; i < n_; ++i) {
    const std::size_t k = 3 * static_cast<std::size_t>(id_[i]);
    out[k] = x_[i];
    out[k + 1] = y_[i];
    out[k + 2] = z_[i];
  }
}

float SphSystem::max_speed() const {
  float v2 = 0.f;
  for (std::size_t i = 0; i < n_; ++i) v2 = std::max(v2, vx_[i] * vx_[i] + vy_[i] * vy_[i] + vz_[i] * vz_[i]);
  return std::sqrt(v2);
}

void SphSystem::add_velocity_splash(float x, float y, float radius, float speed) {
  float top = -1e30f;
  for (std::size_t i = 0; i < n_; ++i) {
    const float dx = x_[i] - x, dy = y_[i] - y;
    if (dx * dx + dy * dy < radius * radius) top = std::max(top, z_[i]);
  }
  if (top < -1e29f) return;
  for (std::size_t i = 0; i < n_; ++i) {
    const float dx = x_[i] - x, dy = y_[i] - y, dz = z_[i] - top;
    const float r2 = dx * dx + dy * dy + dz * dz;
    if (r2 < radius * radius) vz_[i] -= speed * (1.f - r2 / (radius * radius));
  }
}

// ---------------------------------------------------------------------------------------------
// reference paths for the benchmark: the grid step's physics, and an O(n^2) all-pairs version

void SphSystem::grid_accelerations(std::span<float> ax, std::span<float> ay, std::span<float> az,
                                   std::span<float> rho) {
  sort_particles();
  compute_density();
  compute_forces();
  std::copy(ax_.data(), ax_.data() + n_, ax.begin());
  std::copy(ay_.data(), ay_.data() + n_, ay.begin());
  std::copy(az_.data(), az_.data() + n_, az.begin());
  std::copy(rho_.data(), rho_.data() + n_, rho.begin());
}

void SphSystem::brute_force_accelerations(std::span<float> ax, std::span<float> ay, std::span<float> az,
                                          std::span<float> rho) {
  const std::size_t n = n_;
  const float* X = x_.data();
  const float* Y = y_.data();
  const float* Z = z_.data();
  const float h = h_, h2 = k_.h2, mk = mass_ * k_.poly6_k, rho0 = p_.rest_density, rmin = 1e-6f * h_;
  float* R = rho.data();
  float* Pa = tx_.data();  // scratch: p / rho^2
  float* Ia = ty_.data();  // scratch: 1 / rho
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    float sum = 0.f;
#pragma omp simd reduction(+ : sum)
    for (std::size_t j = 0; j < n; ++j) {
      const float dx = X[i] - X[j], dy = Y[i] - Y[j], dz = Z[i] - Z[j];
      const float q = std::max(h2 - (dx * dx + dy * dy + dz * dz), 0.f);
      sum += q * q * q;
    }
    float r = mk * sum;
    boundary_density(i, r);
    R[i] = r;
    const float ratio = r / rho0;
    const float p = std::max(B_ * (std::pow(ratio, p_.tait_gamma) - 1.f), 0.f);
    Ia[i] = 1.f / r;
    Pa[i] = p / (r * r);
  }
  const float cp = mass_ * k_.spiky_k, cv = nu_ * p_.rest_density * mass_ * k_.spiky_k;
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    float fpx = 0.f, fpy = 0.f, fpz = 0.f, fvx = 0.f, fvy = 0.f, fvz = 0.f;
    const float Pi = Pa[i];
#pragma omp simd reduction(+ : fpx, fpy, fpz, fvx, fvy, fvz)
    for (std::size_t j = 0; j < n; ++j) {
      const float dx = X[i] - X[j], dy = Y[i] - Y[j], dz = Z[i] - Z[j];
      const float r2 = dx * dx + dy * dy + dz * dz;
      const float r = std::sqrt(r2);
      const float hr = r2 < h2 ? h - r : 0.f;
      const float fp = (Pi + Pa[j]) * hr * hr / std::max(r, rmin);
      fpx += fp * dx;
      fpy += fp * dy;
      fpz += fp * dz;
      const float fv = hr * Ia[j];
      fvx += fv * (vx_[j] - vx_[i]);
      fvy += fv * (vy_[j] - vy_[i]);
      fvz += fv * (vz_[j] - vz_[i]);
    }
    float a0 = g_[0] + cp * fpx + cv * Ia[i] * fvx;
    float a1 = g_[1] + cp * fpy + cv * Ia[i] * fvy;
    float a2 = g_[2] + cp * fpz + cv * Ia[i] * fvz;
    boundary_force(i, Pi, a0, a1, a2);
    ax[i] = a0;
    ay[i] = a1;
    az[i] = a2;
  }
}

}  // namespace huygens
