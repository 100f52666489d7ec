#include "dye.hpp"

#include <algorithm>
#include <cmath>

namespace huygens {

DyeField::DyeField(const GridPlacement& grid, int bands) : grid_(grid), bands_(std::max(1, bands)) { reset(); }

void DyeField::reset() {
  const std::size_t R = grid_.rows, C = grid_.cols;
  c_.assign(R * C, 0.0f);
  next_.assign(R * C, 0.0f);
  for (std::size_t i = 0; i < R; ++i) {
    const float v = static_cast<float>((i * static_cast<std::size_t>(bands_) / R) % 2);
    std::fill(c_.begin() + static_cast<std::ptrdiff_t>(i * C), c_.begin() + static_cast<std::ptrdiff_t>((i + 1) * C),
              v);
  }
}

void advect_semi_lagrangian(const GridPlacement& grid, std::span<const float> velocity, double dt,
                            std::span<const float> in, std::span<float> out) {
  const std::size_t R = grid.rows, C = grid.cols;
  const double s = dt / grid.dx;  // grid points per (m/s) over the step
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t j = 0; j < C; ++j) {
      const std::size_t k = i * C + j;
      // where the water at this point came from, clamped to the region
      const double x = std::clamp(static_cast<double>(j) - s * velocity[2 * k], 0.0, static_cast<double>(C - 1));
      const double y = std::clamp(static_cast<double>(i) - s * velocity[2 * k + 1], 0.0, static_cast<double>(R - 1));
      const std::size_t j0 = std::min(static_cast<std::size_t>(x), C - 2),
                        i0 = std::min(static_cast<std::size_t>(y), R - 2);
      const float fx = static_cast<float>(x - static_cast<double>(j0)),
                  fy = static_cast<float>(y - static_cast<double>(i0));
      const float* r0 = &in[i0 * C + j0];
      const float* r1 = r0 + C;
      out[k] = (1 - fy) * ((1 - fx) * r0[0] + fx * r0[1]) + fy * ((1 - fx) * r1[0] + fx * r1[1]);
    }
}

void DyeField::advect(std::span<const float> velocity, double dt) {
  const std::size_t R = grid_.rows, C = grid_.cols;
  if (velocity.size() != 2 * R * C || !(dt > 0.0) || R < 2 || C < 2) return;
  advect_semi_lagrangian(grid_, velocity, dt, c_, next_);
  c_.swap(next_);
}

}  // namespace huygens
