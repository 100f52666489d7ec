#include "foam.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dye.hpp"

namespace huygens {

namespace {
// clamp((x - on) / (full - on), 0, 1)
float ramp(double x, double on, double full) {
  return static_cast<float>(std::clamp((x - on) / std::max(full - on, 1e-12), 0.0, 1.0));
}
}  // namespace

FoamField::FoamField(const GridPlacement& grid, std::span<const float> bed, const FoamParams& params)
    : grid_(grid), p_(params) {
  const std::size_t n = grid_.rows * grid_.cols;
  bed_.assign(n, 0.0f);
  if (bed.size() == n) std::copy(bed.begin(), bed.end(), bed_.begin());
  next_.assign(n, 0.0f);
  s_.assign(n, 0.0f);
  hu_.assign(3 * n, 0.0f);
  reset();
}

void FoamField::reset() {
  f_.assign(grid_.rows * grid_.cols, 0.0f);
  std::fill(s_.begin(), s_.end(), 0.0f);
}

// The seed s = max(ramp(Fr), ramp(B), ramp(W)) (foam.hpp), from central differences (one-sided
// at the region's edges) of (h, h u, h v) and of u.
void FoamField::compute_seed(std::span<const float> height, std::span<const float> velocity) {
  const std::size_t R = grid_.rows, C = grid_.cols;
  for (std::size_t k = 0; k < R * C; ++k) {
    const float h = std::max(0.0f, height[k] - bed_[k]);
    hu_[3 * k] = h, hu_[3 * k + 1] = h * velocity[2 * k], hu_[3 * k + 2] = h * velocity[2 * k + 1];
  }
  const double g = p_.gravity_mps2;
  for (std::size_t i = 0; i < R; ++i) {
    const std::size_t im = i > 0 ? i - 1 : i, ip = i + 1 < R ? i + 1 : i;
    const double dy = static_cast<double>(ip - im) * grid_.dx;
    for (std::size_t j = 0; j < C; ++j) {
      const std::size_t k = i * C + j;
      const double h = hu_[3 * k];
      if (h < p_.min_depth_m) {
        s_[k] = 0.0f;
        continue;
      }
      const std::size_t jm = j > 0 ? j - 1 : j, jp = j + 1 < C ? j + 1 : j;
      const double dx = static_cast<double>(jp - jm) * grid_.dx;
      const std::size_t kw = i * C + jm, ke = i * C + jp, ks = im * C + j, kn = ip * C + j;
      // div(h u) and omega = dv/dx - du/dy (0 along a direction with a single point)
      const double div = (dx > 0 ? (hu_[3 * ke + 1] - hu_[3 * kw + 1]) / dx : 0.0) +
                         (dy > 0 ? (hu_[3 * kn + 2] - hu_[3 * ks + 2]) / dy : 0.0);
      const double omega = (dx > 0 ? (velocity[2 * ke + 1] - velocity[2 * kw + 1]) / dx : 0.0) -
                           (dy > 0 ? (velocity[2 * kn] - velocity[2 * ks]) / dy : 0.0);
      const double c = std::sqrt(g * h);
      const double ux = velocity[2 * k], uy = velocity[2 * k + 1];
      const double fr = std::sqrt(ux * ux + uy * uy) / c, b = -div / c, w = std::abs(omega) * h / c;
      s_[k] = std::max({ramp(fr, p_.froude_on, p_.froude_full), ramp(b, p_.breaking_on, p_.breaking_full),
                        ramp(w, p_.shear_on, p_.shear_full)});
    }
  }
}

void FoamField::step(std::span<const float> height, std::span<const float> velocity, double dt) {
  const std::size_t R = grid_.rows, C = grid_.cols;
  if (velocity.size() != 2 * R * C || height.size() != R * C || !(dt > 0.0) || R < 2 || C < 2) return;
  advect_semi_lagrangian(grid_, velocity, dt, f_, next_);
  f_.swap(next_);
  compute_seed(height, velocity);
  // df/dt = -lambda f + r s (1 - f), exact for s held over the step
  const double lambda = std::numbers::ln2 / p_.half_life_s, r = 1.0 / p_.seed_time_s;
  const float fade = static_cast<float>(std::exp(-lambda * dt));
  for (std::size_t k = 0; k < R * C; ++k) {
    const double rs = r * s_[k];
    if (rs == 0.0) {
      f_[k] *= fade;
      continue;
    }
    const double fs = rs / (lambda + rs);
    f_[k] = static_cast<float>(fs + (f_[k] - fs) * std::exp(-(lambda + rs) * dt));
  }
}

}  // namespace huygens
