// The SPH particle system: set-up, the cell sort and the step's stages (see huygens/sph/system.hpp).
#include "huygens/sph/system.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "huygens/common/finite.hpp"

namespace huygens {

// ---------------------------------------------------------------------------------------------
// construction

void SphSystem::allocate(std::size_t n) {
  n_ = n;
  for (auto* b : {&x_,    &y_,     &z_,    &vx_,    &vy_, &vz_, &ax_, &ay_,  &az_,  &rho_, &P_,    &Pc_,
                  &irho_, &lirho_, &corr_, &p_arr_, &tx_, &ty_, &tz_, &tvx_, &tvy_, &tvz_, &tcorr_})
    *b = AlignedBuffer<float>(n + 8);  // padded to whole vectors (masked lanes read the zero tail)
  const double occ = std::pow(double(p_.support_factor), 3);  // (h/dx)^3
  if (p_.method == SphMethod::dfsph) {
    for (auto* b : {&alpha_, &kappa_, &kappav_, &kick_, &gbx_, &gby_, &gbz_, &err_, &tkappa_, &tkappav_, &dvok_, &cex_,
                    &cgx_, &cgy_, &cgz_, &ccd_, &kc_})
      *b = AlignedBuffer<float>(n + 8);
    nbeg_ = AlignedBuffer<std::uint32_t>(n + 8);
    nend_ = AlignedBuffer<std::uint32_t>(n + 8);
    // list slots per particle: 1.25 x the neighbours at rest, (4 pi / 3) (h/dx)^3, and the padding, whole vectors
    const auto slots = static_cast<std::size_t>(8.0 * std::ceil((1.25 * 4.18879 * occ + 8.0) / 8.0));
    dfsph_list_allocate((n + 8) * slots);
  }
  id_.assign(n, 0);
  tid_.assign(n, 0);
  grid_ = SphGrid(p_.container_m, h_, n);
  place_boundary();
  // candidate scratch per thread: 27 cells at up to 4x the rest occupancy (h/dx)^3 (denser cells
  // take the direct path)
  gather_ = SphCellGather(static_cast<std::size_t>(std::min(double(std::max(n, nb_)) + 8.0, 27.0 * 4.0 * occ + 64.0)));
  if (p_.method == SphMethod::dfsph)  // the DFSPH list's candidate flags, per thread with scratch
    nflag_ = AlignedBuffer<std::uint32_t>(std::size_t(gather_.threads()) * (gather_.capacity() + 16));
}

// The boundary particles into the grid's static table, their arrays in that order.
void SphSystem::place_boundary() {
  nb_ = bsample_.size();
  for (auto* b : {&bx_, &by_, &bz_, &bw_, &bP_, &bp_, &bnx_, &bny_, &bnz_}) *b = AlignedBuffer<float>(nb_ + 8);
  std::vector<std::uint32_t> order(nb_);
  grid_.build_static(bsample_.x.data(), bsample_.y.data(), bsample_.z.data(), nb_, order.data());
  for (std::size_t k = 0; k < nb_; ++k) {
    const std::uint32_t o = order[k];
    bx_[k] = bsample_.x[o];
    by_[k] = bsample_.y[o];
    bz_[k] = bsample_.z[o];
    bw_[k] = bsample_.w[o];
    bnx_[k] = bsample_.nx[o];
    bny_[k] = bsample_.ny[o];
    bnz_[k] = bsample_.nz[o];
  }
}

// The fluid blocks on the lattice of cell centres (i + 1/2) dx, leaving out positions outside the
// container or within dx/2 of an obstacle; `top` = the highest block top (unit: m).
void SphSystem::place_fluid(std::vector<float>& px, std::vector<float>& py, std::vector<float>& pz, float& top) const {
  const float dx = p_.spacing_m;
  top = 0.f;
  auto cell = [dx](float v) { return static_cast<int>(std::floor(v / dx + 0.5f)); };
  for (const auto& b : p_.fluid) {
    const int n0 = cell(b.min_m[0]), n1 = cell(b.max_m[0]);
    const int m0 = cell(b.min_m[1]), m1 = cell(b.max_m[1]);
    const int l0 = cell(b.min_m[2]), l1 = cell(b.max_m[2]);
    for (int k = l0; k < l1; ++k)
      for (int j = m0; j < m1; ++j)
        for (int i = n0; i < n1; ++i) {
          const float X = (i + 0.5f) * dx, Y = (j + 0.5f) * dx, Z = (k + 0.5f) * dx;
          const auto& c = p_.container_m;
          if (X < 0 || Y < 0 || Z < 0 || X > c[0] || Y > c[1] || Z > c[2]) continue;
          bool blocked = false;
          for (const auto& o : p_.obstacles) blocked = blocked || o.blocks(X, Y, Z, 0.5f * dx);
          if (blocked) continue;
          px.push_back(X);
          py.push_back(Y);
          pz.push_back(Z);
        }
    top = std::max(top, b.max_m[2]);
  }
}

SphSystem::SphSystem(const SphParams& params, std::size_t dt_history)
    : p_(params), k_(params.support()), h_(params.support()), g_(params.gravity_mps2), damping_(params.damping_ps) {
  const float dx = p_.spacing_m;
  if (!(dx > 0.f)) throw std::invalid_argument("particle spacing must be positive");
  if (!(p_.support_factor >= 1.f && p_.support_factor <= 4.f))
    throw std::invalid_argument("support_factor must be in [1, 4]");
  for (int a = 0; a < 3; ++a)
    if (!(p_.container_m[a] >= 2.f * dx)) throw std::invalid_argument("container must be at least two spacings wide");
  if (!(p_.rest_density_kgpm3 > 0.f) || !(p_.viscosity_m2s >= 0.f) || !(p_.artificial_viscosity >= 0.f))
    throw std::invalid_argument("bad density or viscosity");

  // mass: the density kernel's sum over a lattice of the spacing equals rho0 exactly (poly6; the
  // cubic spline with DFSPH, dfsph.hpp)
  const bool df = p_.method == SphMethod::dfsph;
  double lattice = 0.0;
  const int R = static_cast<int>(std::ceil(p_.support_factor)) + 1;
  for (int i = -R; i <= R; ++i)
    for (int j = -R; j <= R; ++j)
      for (int k = -R; k <= R; ++k) {
        const float r2 = float(i * i + j * j + k * k) * dx * dx;
        lattice += df ? k_.cubic(std::sqrt(r2)) : k_.poly6(r2);
      }
  mass_ = static_cast<float>(p_.rest_density_kgpm3 / lattice);

  std::vector<float> px, py, pz;
  float top = 0.f;
  place_fluid(px, py, pz, top);
  const float rho0 = p_.rest_density_kgpm3;
  const float gmag = std::sqrt(g_[0] * g_[0] + g_[1] * g_[1] + g_[2] * g_[2]);
  c0_ =
      p_.sound_speed_mps > 0.f ? p_.sound_speed_mps : 10.f * std::sqrt(2.f * std::max(gmag, 1e-3f) * std::max(top, dx));
  B_ = rho0 * c0_ * c0_ / p_.tait_gamma;
  mvol_ = p_.gradient_correction ? mass_ / rho0 * (df ? k_.cubic_g : k_.spiky_k) / 3.f : 0.f;
  nu_ = p_.viscosity_m2s + p_.artificial_viscosity * c0_ * h_;
  pik_ = p_.impact_alpha * c0_ * h_ / rho0;
  pikw_ = std::max(p_.impact_alpha, p_.wall_alpha) * c0_ * h_ / rho0;
  pbk_ = p_.impact_beta * h_ * h_ / rho0;
  const int layers = sph_boundary_layers(h_, dx);
  sph_sample_container(p_.container_m, dx, layers, bsample_);
  for (const auto& o : p_.obstacles) sph_sample_obstacle(o, p_.container_m, dx, layers, bsample_);

  dt_hist_.assign(std::max<std::size_t>(dt_history, 1), 0.0);
  sid_.neighbours = stats_.add("neighbour search");
  sid_.density = stats_.add("density");
  sid_.boundary = stats_.add("boundary");
  if (df) sid_.divergence_solve = stats_.add("divergence solve");
  sid_.forces = stats_.add("forces");
  if (df) sid_.density_solve = stats_.add("density solve");
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
#pragma omp parallel for schedule(static) if (n > kSphParallelLight)
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
  if (p_.method != SphMethod::dfsph) return;
    // the warm-start values of DFSPH travel with their particle
#pragma omp parallel for schedule(static) if (n > kSphParallelLight)
  for (std::size_t i = 0; i < n; ++i) {
    tkappa_[i] = kappa_[ord[i]];
    tkappav_[i] = kappav_[ord[i]];
  }
  std::swap(kappa_, tkappa_);
  std::swap(kappav_, tkappav_);
}

// ---------------------------------------------------------------------------------------------
// the step: sort, density, forces, time step and integration

double SphSystem::step() {
  if (p_.method == SphMethod::dfsph) return step_dfsph();
  {
    StageTimer t(stats_[sid_.neighbours]);
    sort_particles();
  }
  {
    StageTimer t(stats_[sid_.density]);
    compute_density(false);
  }
  {
    StageTimer t(stats_[sid_.boundary]);
    compute_boundary_pressure();
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
    dt = sph_choose_dt(p_, h_, c0_, nu_, vmax_, amax_, dts_.limiter);
    const SphMotion m{x_.data(),  y_.data(),  z_.data(),  vx_.data(), vy_.data(),
                      vz_.data(), ax_.data(), ay_.data(), az_.data(), n_};
    sph_integrate(damping_, static_cast<float>(dt), m);
  }
  if (!all_finite(x()) || !all_finite(y()) || !all_finite(z()) || !all_finite(vx()) || !all_finite(vy()) ||
      !all_finite(vz()))
    throw NonFiniteError("integration", steps_);
  record_dt(dt);
  return dt;
}

void SphSystem::record_dt(double dt) {
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
}

void SphSystem::refresh() {
  sort_particles();
  if (p_.method == SphMethod::dfsph) {
    dfsph_factors();
    dfsph_pressure();
    dts_.limiter = "dt_max";
    return;
  }
  compute_density(true);
  compute_boundary_pressure();
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

}  // namespace huygens
