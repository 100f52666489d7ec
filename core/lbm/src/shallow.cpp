#include "huygens/lbm/shallow.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "huygens/common/finite.hpp"
#include "lattice_cell.hpp"

// The lattice's set-up, its step and its fields; the parts of the step are in their own files:
// checks.cpp (the scene's refusals, the bad-cell stops), boundaries.cpp (ghost rules), kernel.cpp
// (the all-wet fused pass), wet_dry.cpp (the wet/dry pass), halo.cpp (MPI rows).

namespace huygens {

using namespace lbm_cell;

std::array<double, 9> lbm_equilibrium(double g, double h, double ux, double uy) {
  std::array<double, 9> f{};
  const double usq = ux * ux + uy * uy;
  for (int a = 1; a < 9; ++a) {
    const double eu = kEx[a] * ux + kEy[a] * uy;
    f[a] = kLambda[a] * h * (g * h / 6.0 + eu / 3.0 + eu * eu / 2.0 - usq / 6.0);
  }
  f[0] = h * (1.0 - 5.0 * g * h / 6.0 - 2.0 * usq / 3.0);
  return f;
}

LbmShallow::LbmShallow(const LbmParams& p, const LbmFields& in, LbmDecomposition d) : p_(p), lat_(lbm_check(p, in)) {
  set_slab(d);  // this rank's rows and halo (all rows with one rank)
  const int nx = p.cols;
  const int lattice_rows = rows_ + 2 * halo_ + (image_row_ >= 0 ? 1 : 0);  // one rank: rows + 2 ghost rows
  stride_ = (kPad + static_cast<std::size_t>(nx) + 1 + 15) / 16 * 16;
  plane_ = stride_ * static_cast<std::size_t>(lattice_rows) + 64;  // skew planes against cache-set aliasing
  fa_ = AlignedBuffer<float>(9 * plane_);
  fb_ = AlignedBuffer<float>(9 * plane_);
  ha_ = AlignedBuffer<float>(plane_);
  hb_ = AlignedBuffer<float>(plane_);
  z_ = AlignedBuffer<float>(plane_);
  theta_ = AlignedBuffer<float>(plane_);
  solid_.assign(plane_, 1);
  if (lbm_starts_dry(p, in)) carry_ = AlignedBuffer<float>(plane_);  // zeroed (see the header)

  omega_ = static_cast<float>(1.0 / lat_.tau);
  g_ = static_cast<float>(lat_.g_lat_pm);
  const double acc = p.dt_s * p.dt_s / p.cell_m;  // m/s^2 -> lattice units
  ax_ = static_cast<float>(p.accel_mps2[0] * acc);
  ay_ = static_cast<float>(p.accel_mps2[1] * acc);
  hmin_ = static_cast<float>(p.min_depth_m);
  umax_ = static_cast<float>(std::min(0.7, std::max(lat_.signal_ratio, lat_.riemann_ratio)));
  init_lattice(in);
  build_rules(in);

  const std::uint64_t bytes =
      (fa_.size() + fb_.size() + ha_.size() + hb_.size() + z_.size() + carry_.size()) * sizeof(float);
  st_fill_ = stats_.add("boundary_fill", rules_.size() * sizeof(Rule));
  st_kernel_ = stats_.add("stream_collide", bytes);
  if (ranks_ > 1) {
    std::uint64_t buffers = 0;
    for (int i = 0; i < 3; ++i) buffers += (send_[i].size() + recv_[i].size()) * sizeof(float);
    st_halo_ = stats_.add("halo_exchange", buffers);
    st_reduce_ = stats_.add("reduce", 0);
  }
}

// Bed, fluid flags, initial populations and depth over the lattice rows of this rank (its rows,
// halo rows and image row: every rank starts from the same global fields), the row spans.
void LbmShallow::init_lattice(const LbmFields& in) {
  const int nx = p_.cols, ny = p_.rows;
  // Bed everywhere in the lattice: ghosts take the nearest interior value.
  const auto at = [&](const std::vector<float>& v, int r, int c) {
    return v.empty() ? 0.0f : v[static_cast<std::size_t>(r) * nx + c];
  };
  for_lattice_rows([&](int r) {
    for (int c = -1; c <= nx; ++c) z_[idx(r, c)] = at(in.bed_m, std::clamp(r, 0, ny - 1), std::clamp(c, 0, nx - 1));
  });
  float zlo = at(in.bed_m, 0, 0), zhi = zlo;  // over the whole grid: every rank takes the same kernel
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) {
      zlo = std::min(zlo, at(in.bed_m, r, c));
      zhi = std::max(zhi, at(in.bed_m, r, c));
    }
  has_bed_ = zhi > zlo;

  // Fluid cells and their initial equilibrium populations, shifted by the still-water
  // equilibrium of the mean depth; with a dry cell, unshifted (a dry cell's f_a = 0 is then exact).
  const double vl = p_.dt_s / p_.cell_m;  // m/s -> lattice
  double hsum = 0;
  std::size_t nfluid = 0;
  for (std::size_t i = 0; i < in.depth_m.size(); ++i)
    if (in.solid.empty() || !in.solid[i]) {
      hsum += in.depth_m[i];
      ++nfluid;
      if (in.depth_m[i] < p_.min_depth_m) ++dry_;
    }
  href_ = dry_ ? 0.0f : static_cast<float>(hsum / static_cast<double>(nfluid));
  shift_ = lbm_equilibrium(lat_.g_lat_pm, href_, 0.0, 0.0);
  for (int a = 0; a < 9; ++a) shift_f_[a] = static_cast<float>(shift_[a]);
  for_lattice_rows([&](int r) {
    if (r < 0 || r >= ny) return;
    for (int c = 0; c < nx; ++c) {
      const std::size_t i = static_cast<std::size_t>(r) * nx + c;
      if (!in.solid.empty() && in.solid[i]) continue;
      const std::size_t k = idx(r, c);
      solid_[k] = 0;
      const double h = in.depth_m[i];
      auto f = lbm_equilibrium(lat_.g_lat_pm, h, at(in.ux_mps, r, c) * vl, at(in.uy_mps, r, c) * vl);
      if (h < p_.min_depth_m) f = {h, 0, 0, 0, 0, 0, 0, 0, 0};  // dry: all water at rest
      for (int a = 0; a < 9; ++a) fa_[a * plane_ + k] = fb_[a * plane_ + k] = static_cast<float>(f[a] - shift_[a]);
      ha_[k] = hb_[k] = static_cast<float>(h);
    }
  });
  // Row spans of fluid cells: this rank's rows (the kernels), the first halo rows and the image
  // row (their populations are unshifted with the rank's own, halo.cpp).
  auto add_spans = [&](int r, std::vector<Span>& out) {
    int c = 0;
    while (c < nx) {
      while (c < nx && solid_[idx(r, c)]) ++c;
      const int c0 = c;
      while (c < nx && !solid_[idx(r, c)]) ++c;
      if (c > c0)
        out.push_back({static_cast<std::uint32_t>(idx(r, c0)), static_cast<std::uint32_t>(idx(r, c0) + (c - c0))});
    }
  };
  for (int r = row0_; r < row0_ + rows_; ++r) add_spans(r, spans_);
  if (ranks_ > 1)
    for (int r : {row0_ - 1, row0_ + rows_, image_row_})
      if (r >= 0 && r < ny && (r != image_row_ || image_row_ >= 0)) add_spans(r, halo_spans_);
  for (const Span& sp : spans_) ncells_ += sp.end - sp.begin;
  if (ranks_ > 1) {  // the edge rows read the halo, the inner rows do not
    for (int r = row0_; r < row0_ + rows_; ++r)
      add_spans(r, r == row0_ || r == row0_ + rows_ - 1 ? edge_spans_ : inner_spans_);
  }
}

void LbmShallow::step() {
  const bool wet_dry = dry_ > 0;
  if (wet_dry && ranks_ > 1 && image_row_ >= 0) throw_periodic_wet_dry();
  int flagged = 0, bad = 0;
  // several ranks, all wet: the halo exchange overlaps the inner rows' update (halo.cpp)
  const bool overlap = ranks_ > 1 && !wet_dry;
  if (overlap) all_wet_overlapped(flagged);
  if (ranks_ > 1 && !overlap) exchange_halos();  // the neighbours' rows this step reads (halo.cpp)
  if (!overlap) {
    StageTimer t(stats_[st_fill_]);
    if (wet_dry) set_ghost_depths();
    fill_ghosts(wet_dry);
  }
  {
    StageTimer t(stats_[st_kernel_]);
    if (wet_dry)
      stream_collide_wet_dry(flagged, bad);
    else if (!overlap)
      all_wet_kernel(flagged);
    agree(flagged, bad);  // several ranks: the counts of all ranks
    if (!wet_dry && flagged) {
      // A cell fell below h_min (or went negative) in the all-wet pass: the populations it read
      // are intact (pull scheme), so the step is redone by the wet/dry pass. The naive bed term
      // has no wet/dry form: that run stops.
      if (p_.bed_force == LbmBedForce::naive && has_bed_) {
        bad = 1;
      } else {
        if (image_row_ >= 0) throw_periodic_wet_dry();
        ++redone_;
        unshift();
        set_ghost_depths();
        fill_ghosts(true);
        stream_collide_wet_dry(flagged, bad);
        agree(flagged, bad);
      }
    }
  }
  std::swap(fa_, fb_);
  std::swap(ha_, hb_);
  ++steps_;
  if (bad) throw_bad_cell();
  dry_ = static_cast<std::size_t>(flagged);
}

void LbmShallow::unshift() {
  // h - H of a cell near dry has the float resolution of H, coarser than a thin film: once a cell
  // dries, populations are stored unshifted (a dry cell's zero populations and depth are exact).
  if (href_ == 0.0f) return;
  for (const auto* spans : {&spans_, &halo_spans_})  // halo rows: as their owners do
    for (const Span& sp : *spans)
      for (int a = 0; a < 9; ++a) {
        float* f = fa_.data() + static_cast<std::size_t>(a) * plane_;
        for (std::uint32_t c = sp.begin; c < sp.end; ++c) f[c] += shift_f_[a];
      }
  shift_ = {};
  shift_f_ = {};
  href_ = 0.0f;
}

double LbmShallow::volume_m3() const {
  // From the populations (h = H + sum of shifted populations), in double.
  double sum = 0;
  std::size_t cells = 0;
  for (const Span& sp : spans_) {
    for (int a = 0; a < 9; ++a) {
      const float* f = fa_.data() + a * plane_;
      for (std::uint32_t c = sp.begin; c < sp.end; ++c) sum += f[c];
    }
    cells += sp.end - sp.begin;
  }
  return (sum + static_cast<double>(href_) * static_cast<double>(cells)) * p_.cell_m * p_.cell_m;
}

void LbmShallow::depth(std::span<float> out) const {
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < p_.cols; ++c) out[static_cast<std::size_t>(r) * p_.cols + c] = depth_at(row0_ + r, c);
}

float LbmShallow::depth_at(int row, int col) const {
  const std::size_t k = idx(row, col);
  return solid_[k] ? 0.0f : ha_[k];
}

std::array<float, 2> LbmShallow::velocity_at(int row, int col) const {
  const std::size_t k = idx(row, col);
  if (solid_[k] || ha_[k] < hmin_) return {0.0f, 0.0f};  // dry cells are at rest
  double h = href_, mx = 0, my = 0;
  for (int a = 0; a < 9; ++a) {
    const double f = fa_[a * plane_ + k];  // shifted populations
    h += f;
    mx += kEx[a] * f;
    my += kEy[a] * f;
  }
  // Post-collision momentum includes the external force h a: remove it to get u of the step.
  const double e = lat_.speed_mps;
  return {static_cast<float>((mx / h - ax_) * e), static_cast<float>((my / h - ay_) * e)};
}

void LbmShallow::velocity(std::span<float> out) const {
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < p_.cols; ++c) {
      const auto u = velocity_at(row0_ + r, c);
      const std::size_t i = 2 * (static_cast<std::size_t>(r) * p_.cols + c);
      out[i] = u[0];
      out[i + 1] = u[1];
    }
}

void LbmShallow::bed(std::span<float> out) const {
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < p_.cols; ++c) out[static_cast<std::size_t>(r) * p_.cols + c] = z_[idx(row0_ + r, c)];
}

int LbmShallow::bytes_per_cell() const {
  // 9 populations read and written, the new depth written; a bed adds z and the old depth.
  return has_bed_ ? 21 * 4 : 19 * 4;
}

}  // namespace huygens
