// 3D SPH of paper 000 after MCG03: see sph.hpp for the equations.
#include "huygens/sph/system.hpp"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "huygens/common/finite.hpp"

namespace huygens {

namespace {
constexpr double kPi = std::numbers::pi;
// below this many particles a step is a few hundred microseconds: threads cost more than they give
constexpr std::size_t kParallelMin = 2048;
// the streaming loops (sort gather, integration) cost a few ns per particle: below this many
// particles waking a second thread (passive wait policy) costs more than the loop (measured:
// neighbour search and integration took 12 % each of a 3000-particle step with 2 threads)
constexpr std::size_t kParallelLight = std::size_t(1) << 16;
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
  for (auto* b : {&x_,    &y_,     &z_,    &vx_,    &vy_, &vz_, &ax_, &ay_,  &az_,  &rho_, &P_,
                  &irho_, &lirho_, &corr_, &p_arr_, &tx_, &ty_, &tz_, &tvx_, &tvy_, &tvz_, &tcorr_})
    *b = AlignedBuffer<float>(n + 8);  // padded to whole vectors (masked lanes read the zero tail)
  id_.assign(n, 0);
  tid_.assign(n, 0);
  grid_ = SphGrid(p_.container, h_, n);
  // per-thread candidate scratch: 27 cells at up to 4x the rest occupancy (h/dx)^3 (denser cells take the
  // direct path)
  const double occ = std::pow(double(p_.support_factor), 3);
  scratch_cap_ = (static_cast<std::size_t>(std::min(double(n) + 8.0, 27.0 * 4.0 * occ + 64.0)) + 15) & ~std::size_t(15);
  scratch_threads_ = std::max(omp_get_max_threads(), omp_get_num_procs());
  scratch_ = AlignedBuffer<float>(std::size_t(scratch_threads_) * kScratchArrays * (scratch_cap_ + 16));
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
  mvol_ = p_.gradient_correction ? mass_ / p_.rest_density * k_.spiky_k / 3.f : 0.f;
  nu_ = p_.viscosity + p_.artificial_viscosity * c0_ * h_;
  pik_ = p_.impact_alpha * c0_ * h_ / p_.rest_density;
  pbk_ = p_.impact_beta * h_ * h_ / p_.rest_density;

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

void SphSystem::set_velocities(std::span<const float> vx, std::span<const float> vy, std::span<const float> vz) {
  if (vx.size() != n_ || vy.size() != n_ || vz.size() != n_)
    throw std::invalid_argument("set_velocities: one value per particle expected");
  std::copy(vx.begin(), vx.end(), vx_.data());
  std::copy(vy.begin(), vy.end(), vy_.data());
  std::copy(vz.begin(), vz.end(), vz_.data());
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
#pragma omp parallel for schedule(static) if (n > kParallelLight)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t o = ord[i];
    tx_[i] = x_[o];
    ty_[i] = y_[o];
    tz_[i] = z_[o];
    tvx_[i] = vx_[o];
    tvy_[i] = vy_[o];
    tvz_[i] = vz_[o];
    tcorr_[i] = corr_[o];
    tid_[i] = id_[o];
  }
  std::swap(x_, tx_);
  std::swap(y_, ty_);
  std::swap(z_, tz_);
  std::swap(vx_, tvx_);
  std::swap(vy_, tvy_);
  std::swap(vz_, tvz_);
  std::swap(corr_, tcorr_);
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
  // one-plane ghost tables, used by the obstacles (the container walls use mirror images, see compute_density)
  const float dx = p_.spacing;
  auto& w = wt_;
  w.n1 = 256;
  w.inv1 = w.n1 / h_;
  const int s1 = w.n1 + 2;
  w.d1.assign(s1, 0.f);
  w.f1.assign(s1, 0.f);
  double D, F;
  for (int a = 0; a < s1; ++a) {
    const double d[1] = {double(a) / w.inv1};
    ghost_sums(k_, dx, mass_, 1, d, D, F);
    w.d1[a] = static_cast<float>(D);
    w.f1[a] = static_cast<float>(F);
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

// the obstacle surfaces within the support radius of a particle
// false when (x, y, z) is farther than `margin` from the obstacle's bounding box (then its signed
// distance exceeds margin too): skips the distance function for most particles
inline bool near_box(const SphObstacle& o, float x, float y, float z, float margin) {
  float lo[3], hi[3];
  if (o.type == SphObstacle::Type::box) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = o.min[a];
      hi[a] = o.max[a];
    }
  } else {
    lo[0] = o.centre[0] - o.radius;
    hi[0] = o.centre[0] + o.radius;
    lo[1] = o.centre[1] - o.radius;
    hi[1] = o.centre[1] + o.radius;
    lo[2] = o.z0;
    hi[2] = o.z1;
  }
  return x > lo[0] - margin && x < hi[0] + margin && y > lo[1] - margin && y < hi[1] + margin && z > lo[2] - margin &&
         z < hi[2] + margin;
}

inline int near_obstacles(const std::vector<SphObstacle>& obs, float h, float x, float y, float z, Plane* out) {
  int n = 0;
  for (const auto& o : obs) {
    if (n >= 16) break;
    if (!near_box(o, x, y, z, h)) continue;
    Plane p{};
    p.d = o.distance(x, y, z, p.n);
    p.axis = -1;
    if (p.d < h) out[n++] = p;
  }
  return n;
}

}  // namespace

// Container walls: mirror images. For the container planes within h of particle i, every
// neighbour j has an image x_j' reflected across the plane (and across each pair and the triple
// of planes of different axes, for edges and corners): a per-axis sign flip, x_a' = 2 w_a - x_a.
// The image carries j's density, the mirrored velocity (normal component reversed: free slip) and
// j's pressure plus the hydrostatic difference, p_j' = p_j + rho_j g . (x_j' - x_j) (the wall
// pressure extrapolation of Adami, Hu and Adams 2012, eq. 27, for a wall at rest). With
// d = x_i - x_j' = o + s X_j (s_a = +1 on reflected axes, -1 elsewhere), the image term is
// P_j' = p_j'/rho_j^2 = P_j + (G0 + gs . X_j) / rho_j, G0 = sum_a 2 g_a w_a, gs_a = -2 g_a.
int SphSystem::container_images(float x, float y, float z, SphImage* out) const {
  struct Pl {
    int axis;
    float w;
  } pl[6];
  int np = 0;
  const float pos[3] = {x, y, z};
  for (int a = 0; a < 3; ++a) {
    if (pos[a] < h_) pl[np++] = {a, 0.f};
    if (p_.container[a] - pos[a] < h_) pl[np++] = {a, p_.container[a]};
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
        im.G0 += 2.f * g_[a] * pl[k].w;
        im.gs[a] = -2.f * g_[a];
      }
    out[n++] = im;
  }
  return n;
}

void SphSystem::boundary_density(std::size_t i, float& rho) const {
  if (p_.obstacles.empty()) return;
  Plane pl[16];
  const int n = near_obstacles(p_.obstacles, h_, x_[i], y_[i], z_[i], pl);
  for (int a = 0; a < n; ++a) rho += lerp1(wt_.d1, wt_.inv1, wt_.n1, pl[a].d);
}

void SphSystem::boundary_force(std::size_t i, float P, float& ax, float& ay, float& az) const {
  if (P <= 0.f || p_.obstacles.empty()) return;
  Plane pl[16];
  const int n = near_obstacles(p_.obstacles, h_, x_[i], y_[i], z_[i], pl);
  for (int a = 0; a < n; ++a) {
    const float f = P * lerp1(wt_.f1, wt_.inv1, wt_.n1, pl[a].d);
    ax += f * pl[a].n[0];
    ay += f * pl[a].n[1];
    az += f * pl[a].n[2];
  }
}

// ---------------------------------------------------------------------------------------------
// density and pressure: rho_i = m sum_j W_poly6 + walls; p = max(0, B ((rho/rho0)^gamma - 1))

namespace {

// The neighbour sums over one contiguous index range [b, e) of the cell-sorted arrays, as whole
// aligned vectors over [b & ~7, (e + 7) & ~7) with the lanes outside [b, e) masked (no scalar
// remainder; the arrays are padded). kImage: the mirror images of the range across the planes of
// `im` (d = o + s X_j) instead of the particles themselves (d = x_i - X_j).
// 1/sqrt(x) without a square root or a division (both are slow in the vector units): the
// bit-level first guess of Lomont (2003) and two Newton steps y <- y (3/2 - x y^2 / 2); relative
// error below 5e-6. GCC vectorises it (integer shift and subtract on the float bits).
inline float rsqrt_nr(float x) {
  float y = std::bit_cast<float>(0x5f375a86u - (std::bit_cast<std::uint32_t>(x) >> 1));
  const float hx = 0.5f * x;
  y = y * (1.5f - hx * y * y);
  y = y * (1.5f - hx * y * y);
  return y;
}

struct SphView {
  const float *X, *Y, *Z, *VX, *VY, *VZ, *PP, *IR, *LR;
};

template <bool kImage, bool kMoment>
inline void poly6_range(const SphView& v, std::uint32_t b, std::uint32_t e, const SphImage& im, float h, float h2,
                        float& sum, float& msum) {
  const float* X = v.X;
  const float* Y = v.Y;
  const float* Z = v.Z;
  const float ox = im.o[0], oy = im.o[1], oz = im.o[2], sx = im.s[0], sy = im.s[1], sz = im.s[2];
  const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
  float s6 = 0.f, sm = 0.f;
#pragma omp simd reduction(+ : s6, sm) aligned(X, Y, Z : 32)
  for (std::uint32_t j = b0; j < e0; ++j) {
    const float dx = kImage ? ox + sx * X[j] : ox - X[j];
    const float dy = kImage ? oy + sy * Y[j] : oy - Y[j];
    const float dz = kImage ? oz + sz * Z[j] : oz - Z[j];
    const float r2 = dx * dx + dy * dy + dz * dz;
    const bool in = r2 < h2 && j >= b && j < e;
    const float q = in ? h2 - r2 : 0.f;
    s6 += q * q * q;
    if constexpr (kMoment) {
      // first moment of the spiky gradient: (h - r)^2 r
      const float r = r2 * rsqrt_nr(std::max(r2, 1e-30f));
      const float hr = in ? h - r : 0.f;
      sm += hr * hr * r;
    }
  }
  sum += s6;
  msum += sm;
}

// pressure: sum (P_i + P_j + Pi_ij) (h - r)^2 / r (x_i - x_j) (Pi_ij: impact viscosity, pik = alpha c0 h / rho0,
// pbk = beta h^2 / rho0);
// viscosity: sum (v_j - v_i) (h - r) / rho_j
template <bool kImage>
inline void force_range(const SphView& v, std::uint32_t b, std::uint32_t e, const SphImage& im, const float vi[3],
                        float Pi, float h, float h2, float rmin, float pik, float pbk, float acc[7]) {
  const float rmin2 = rmin * rmin, eta2 = 0.01f * h2;
  const float* X = v.X;
  const float* Y = v.Y;
  const float* Z = v.Z;
  const float* VX = v.VX;
  const float* VY = v.VY;
  const float* VZ = v.VZ;
  const float* PP = v.PP;
  const float* IR = v.IR;
  const float* LR = v.LR;
  const float ox = im.o[0], oy = im.o[1], oz = im.o[2], sx = im.s[0], sy = im.s[1], sz = im.s[2];
  const float G0 = im.G0, gx = im.gs[0], gy = im.gs[1], gz = im.gs[2];
  const float vxi = vi[0], vyi = vi[1], vzi = vi[2];
  const std::uint32_t b0 = b & ~7u, e0 = (e + 7u) & ~7u;
  float fpx = 0.f, fpy = 0.f, fpz = 0.f, fvx = 0.f, fvy = 0.f, fvz = 0.f, sm = 0.f;
#pragma omp simd reduction(+ : fpx, fpy, fpz, fvx, fvy, fvz, sm) aligned(X, Y, Z, VX, VY, VZ, PP, IR, LR : 32)
  for (std::uint32_t j = b0; j < e0; ++j) {
    const float dx = kImage ? ox + sx * X[j] : ox - X[j];
    const float dy = kImage ? oy + sy * Y[j] : oy - Y[j];
    const float dz = kImage ? oz + sz * Z[j] : oz - Z[j];
    const float r2 = dx * dx + dy * dy + dz * dz;
    const float ri = rsqrt_nr(std::max(r2, rmin2));  // 1 / r
    const float r = r2 * ri;
    const float hr = (r2 < h2 && j >= b && j < e) ? h - r : 0.f;
    const float Pj = kImage ? std::max(PP[j] + LR[j] * (G0 + gx * X[j] + gy * Y[j] + gz * Z[j]), 0.f) : PP[j];
    const float vjx = kImage ? -sx * VX[j] : VX[j], vjy = kImage ? -sy * VY[j] : VY[j],
                vjz = kImage ? -sz * VZ[j] : VZ[j];
    const float vr = (vxi - vjx) * dx + (vyi - vjy) * dy + (vzi - vjz) * dz;
    const float ie = rsqrt_nr(r2 + eta2);  // Monaghan's 1 / (r^2 + h^2/100), squared below
    const float mu = std::max(-vr, 0.f) * ie * ie;
    const float Pv = (pik + pbk * mu) * mu;
    const float fp = (Pi + Pj + Pv) * hr * hr * ri;
    fpx += fp * dx;
    fpy += fp * dy;
    fpz += fp * dz;
    const float fv = hr * IR[j];
    fvx += fv * (vjx - vxi);
    fvy += fv * (vjy - vyi);
    fvz += fv * (vjz - vzi);
    sm += hr * hr * r;  // first moment of the spiky gradient, for the next step's correction
  }
  acc[0] += fpx;
  acc[1] += fpy;
  acc[2] += fpz;
  acc[3] += fvx;
  acc[4] += fvy;
  acc[5] += fvz;
  acc[6] += sm;
}

inline SphImage self_image(float x, float y, float z) {
  SphImage im{};
  im.o[0] = x;
  im.o[1] = y;
  im.o[2] = z;
  return im;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// density and pressure: rho_i = m sum_j W_poly6 (neighbours and their wall images) + obstacles;
// p = max(0, B ((rho/rho0)^gamma - 1))

float SphSystem::pressure_of(float rho) const {
  const float ratio = rho / p_.rest_density;
  float rg;
  if (p_.tait_gamma == 7.f) {
    const float r2 = ratio * ratio, r4 = r2 * r2;
    rg = r4 * r2 * ratio;
  } else {
    rg = std::pow(ratio, p_.tait_gamma);
  }
  return std::max(B_ * (rg - 1.f), 0.f);
}

// The candidates of a cell: the particles of its 27 neighbour cells (9 contiguous index ranges of
// the sorted arrays), gathered once per cell into a contiguous per-thread scratch so every particle
// of the cell runs ONE vector loop with one reduction (instead of nine short loops, each ending in a
// horizontal reduction). Returns the count, or -1 when the scratch is too small (the caller then
// loops over the nine ranges directly).
int SphSystem::gather_cell(int cx, int cy, int cz, const float* const* src, int arrays, float* const* dst,
                           std::uint32_t& floor_end) const {
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx - 1);
  std::size_t cnt = 0;
  floor_end = 0;
  for (int kz = std::max(cz - 1, 0); kz <= std::min(cz + 1, nz - 1); ++kz) {
    for (int ky = std::max(cy - 1, 0); ky <= std::min(cy + 1, ny - 1); ++ky) {
      std::uint32_t b, e;
      grid_.row_range(x0, x1, ky, kz, b, e);
      if (cnt + (e - b) > scratch_cap_) return -1;
      for (int a = 0; a < arrays; ++a) std::copy(src[a] + b, src[a] + e, dst[a] + cnt);
      cnt += e - b;
    }
    if (kz == 0) floor_end = static_cast<std::uint32_t>(cnt);
  }
  return static_cast<int>(cnt);
}

void SphSystem::compute_density(bool fresh_moment) {
  const std::size_t n = n_;
  const SphView v{x_.data(),  y_.data(), z_.data(),    vx_.data(),   vy_.data(),
                  vz_.data(), P_.data(), irho_.data(), lirho_.data()};
  const float h = h_, h2 = k_.h2, mk = mass_ * k_.poly6_k;
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
#pragma omp parallel if (n > kParallelMin)
  {
    const int t = omp_get_thread_num();
    float* sc[3];
    for (int a = 0; a < 3; ++a) sc[a] = scratch_.data() + (std::size_t(t) * kScratchArrays + a) * (scratch_cap_ + 16);
    const float* src[3] = {v.X, v.Y, v.Z};
    const SphView sv{sc[0], sc[1], sc[2], nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
    std::uint32_t cur = ~0u, floor_end = 0;
    int cnt = -1;
    const bool own = t < scratch_threads_;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const float xi = v.X[i], yi = v.Y[i], zi = v.Z[i];
      SphImage im[8];
      im[0] = self_image(xi, yi, zi);
      const int ni = container_images(xi, yi, zi, im + 1);
      const int cx = grid_.ix(xi), cy = grid_.iy(yi), cz = grid_.iz(zi);
      const std::uint32_t c = grid_.index(cx, cy, cz);
      if (own && c != cur) {
        cur = c;
        cnt = gather_cell(cx, cy, cz, src, 3, sc, floor_end);
      }
      float sum = 0.f, msum = 0.f;
      if (own && cnt >= 0) {
        const auto e = static_cast<std::uint32_t>(cnt);
        // an image across the floor pairs only with candidates of the bottom cell layer (z_i + z_j < h)
        if (fresh_moment) {
          poly6_range<false, true>(sv, 0, e, im[0], h, h2, sum, msum);
          for (int k = 1; k <= ni; ++k)
            poly6_range<true, true>(sv, 0, im[k].floor ? floor_end : e, im[k], h, h2, sum, msum);
        } else {
          poly6_range<false, false>(sv, 0, e, im[0], h, h2, sum, msum);
          for (int k = 1; k <= ni; ++k)
            poly6_range<true, false>(sv, 0, im[k].floor ? floor_end : e, im[k], h, h2, sum, msum);
        }
      } else {
        const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx - 1);
        for (int kz = std::max(cz - 1, 0); kz <= std::min(cz + 1, nz - 1); ++kz)
          for (int ky = std::max(cy - 1, 0); ky <= std::min(cy + 1, ny - 1); ++ky) {
            std::uint32_t b, e;
            grid_.row_range(x0, x1, ky, kz, b, e);
            poly6_range<false, true>(v, b, e, im[0], h, h2, sum, msum);
            for (int k = 1; k <= ni; ++k) poly6_range<true, true>(v, b, e, im[k], h, h2, sum, msum);
          }
      }
      // a non-finite position is masked out of every neighbour sum: make its own density say so
      float rho = std::isfinite(xi + yi + zi) ? mk * sum : std::numeric_limits<float>::quiet_NaN();
      boundary_density(i, rho);
      rho_[i] = rho;
      const float p = pressure_of(rho);
      p_arr_[i] = p;
      // the correction of the previous force pass (positions one step older) or a fresh one
      const float l = fresh_moment || cnt < 0 || !own ? gradient_correction(msum) : corr_[i];
      corr_[i] = l;
      irho_[i] = 1.f / rho;
      lirho_[i] = l / rho;
      P_[i] = l * p / (rho * rho);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// forces: symmetric spiky pressure + viscosity Laplacian + gravity, with the wall images; obstacles

void SphSystem::compute_forces() {
  const std::size_t n = n_;
  const SphView v{x_.data(),  y_.data(), z_.data(),    vx_.data(),   vy_.data(),
                  vz_.data(), P_.data(), irho_.data(), lirho_.data()};
  const float h = h_, h2 = k_.h2, rmin = 1e-6f * h_;
  const float pik = pik_, pbk = pbk_;
  const float cp = mass_ * k_.spiky_k;                          // m 45/(pi h^6)
  const float cv = nu_ * p_.rest_density * mass_ * k_.spiky_k;  // nu rho0 m 45/(pi h^6)
  const float gx = g_[0], gy = g_[1], gz = g_[2];
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  float amax2 = 0.f, vmax2 = 0.f;
#pragma omp parallel if (n > kParallelMin) reduction(max : amax2, vmax2)
  {
    const int t = omp_get_thread_num();
    float* sc[kScratchArrays];
    for (int a = 0; a < kScratchArrays; ++a)
      sc[a] = scratch_.data() + (std::size_t(t) * kScratchArrays + a) * (scratch_cap_ + 16);
    const float* src[kScratchArrays] = {v.X, v.Y, v.Z, v.VX, v.VY, v.VZ, v.PP, v.IR, v.LR};
    const SphView sv{sc[0], sc[1], sc[2], sc[3], sc[4], sc[5], sc[6], sc[7], sc[8]};
    std::uint32_t cur = ~0u, floor_end = 0;
    int cnt = -1;
    const bool own = t < scratch_threads_;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const float xi = v.X[i], yi = v.Y[i], zi = v.Z[i], Pi = v.PP[i];
      const float vi[3] = {v.VX[i], v.VY[i], v.VZ[i]};
      SphImage im[8];
      im[0] = self_image(xi, yi, zi);
      const int ni = container_images(xi, yi, zi, im + 1);
      const int cx = grid_.ix(xi), cy = grid_.iy(yi), cz = grid_.iz(zi);
      const std::uint32_t c = grid_.index(cx, cy, cz);
      if (own && c != cur) {
        cur = c;
        cnt = gather_cell(cx, cy, cz, src, kScratchArrays, sc, floor_end);
      }
      float acc[7] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
      if (own && cnt >= 0) {
        const auto e = static_cast<std::uint32_t>(cnt);
        force_range<false>(sv, 0, e, im[0], vi, Pi, h, h2, rmin, pik, pbk, acc);
        for (int k = 1; k <= ni; ++k)
          force_range<true>(sv, 0, im[k].floor ? floor_end : e, im[k], vi, Pi, h, h2, rmin, pik, pbk, acc);
      } else {
        const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx - 1);
        for (int kz = std::max(cz - 1, 0); kz <= std::min(cz + 1, nz - 1); ++kz)
          for (int ky = std::max(cy - 1, 0); ky <= std::min(cy + 1, ny - 1); ++ky) {
            std::uint32_t b, e;
            grid_.row_range(x0, x1, ky, kz, b, e);
            force_range<false>(v, b, e, im[0], vi, Pi, h, h2, rmin, pik, pbk, acc);
            for (int k = 1; k <= ni; ++k) force_range<true>(v, b, e, im[k], vi, Pi, h, h2, rmin, pik, pbk, acc);
          }
      }
      const float vis = cv * v.IR[i];
      float ax = gx + cp * acc[0] + vis * acc[3];
      float ay = gy + cp * acc[1] + vis * acc[4];
      float az = gz + cp * acc[2] + vis * acc[5];
      boundary_force(i, Pi, ax, ay, az);
      ax_[i] = ax;
      ay_[i] = ay;
      az_[i] = az;
      corr_[i] = gradient_correction(acc[6]);
      amax2 = std::max(amax2, ax * ax + ay * ay + az * az);
      vmax2 = std::max(vmax2, vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]);
    }
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
#pragma omp parallel for simd schedule(static) if (n > kParallelLight)
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
#pragma omp parallel for schedule(static) if (n > (obst ? kParallelMin : kParallelLight))
  for (std::size_t i = 0; i < n; ++i) {
    clamp_axis(X[i], VX[i], lo[0], hi[0]);
    clamp_axis(Y[i], VY[i], lo[1], hi[1]);
    clamp_axis(Z[i], VZ[i], lo[2], hi[2]);
    if (obst) {
      float nrm[3];
      for (const auto& o : p_.obstacles) {
        if (!near_box(o, X[i], Y[i], Z[i], eps)) continue;
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
    compute_density(false);
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
  compute_density(true);
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
  compute_density(true);
  compute_forces();
  std::copy(ax_.data(), ax_.data() + n_, ax.begin());
  std::copy(ay_.data(), ay_.data() + n_, ay.begin());
  std::copy(az_.data(), az_.data() + n_, az.begin());
  std::copy(rho_.data(), rho_.data() + n_, rho.begin());
}

void SphSystem::brute_force_accelerations(std::span<float> ax, std::span<float> ay, std::span<float> az,
                                          std::span<float> rho) {
  // the same physics with every particle (and every wall image) tested against every other
  const std::size_t n = n_;
  const float h = h_, h2 = k_.h2, mk = mass_ * k_.poly6_k, rmin = 1e-6f * h_;
  const float pik = pik_, pbk = pbk_;
  float* R = rho.data();
  float* Pa = tx_.data();  // scratch: p / rho^2
  float* Ia = ty_.data();  // scratch: 1 / rho
  float* La = tz_.data();  // scratch: l / rho
  const auto un = static_cast<std::uint32_t>(n);
  const SphView v{x_.data(), y_.data(), z_.data(), vx_.data(), vy_.data(), vz_.data(), Pa, Ia, La};
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    SphImage im[8];
    im[0] = self_image(v.X[i], v.Y[i], v.Z[i]);
    const int ni = container_images(v.X[i], v.Y[i], v.Z[i], im + 1);
    float sum = 0.f, msum = 0.f;
    poly6_range<false, true>(v, 0, un, im[0], h, h2, sum, msum);
    for (int k = 1; k <= ni; ++k) poly6_range<true, true>(v, 0, un, im[k], h, h2, sum, msum);
    float r = mk * sum;
    boundary_density(i, r);
    R[i] = r;
    const float p = pressure_of(r);
    const float l = gradient_correction(msum);
    Ia[i] = 1.f / r;
    La[i] = l / r;
    Pa[i] = l * p / (r * r);
  }
  const float cp = mass_ * k_.spiky_k, cv = nu_ * p_.rest_density * mass_ * k_.spiky_k;
#pragma omp parallel for schedule(static) if (n > kParallelMin)
  for (std::size_t i = 0; i < n; ++i) {
    SphImage im[8];
    im[0] = self_image(v.X[i], v.Y[i], v.Z[i]);
    const int ni = container_images(v.X[i], v.Y[i], v.Z[i], im + 1);
    const float vi[3] = {v.VX[i], v.VY[i], v.VZ[i]};
    float acc[7] = {0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f};
    force_range<false>(v, 0, un, im[0], vi, Pa[i], h, h2, rmin, pik, pbk, acc);
    for (int k = 1; k <= ni; ++k) force_range<true>(v, 0, un, im[k], vi, Pa[i], h, h2, rmin, pik, pbk, acc);
    float a0 = g_[0] + cp * acc[0] + cv * Ia[i] * acc[3];
    float a1 = g_[1] + cp * acc[1] + cv * Ia[i] * acc[4];
    float a2 = g_[2] + cp * acc[2] + cv * Ia[i] * acc[5];
    boundary_force(i, Pa[i], a0, a1, a2);
    ax[i] = a0;
    ay[i] = a1;
    az[i] = a2;
  }
}

}  // namespace huygens
