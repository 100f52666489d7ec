// Uniform neighbour grid and per-cell candidate gather: see huygens/sph/grid.hpp.
#include "huygens/sph/grid.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace huygens {

SphGrid::SphGrid(const std::array<float, 3>& extent, float cell, std::size_t max_particles)
    : cell_(cell), inv_(1.f / cell) {
  nx_ = std::max(1, static_cast<int>(std::ceil(extent[0] / cell)));
  ny_ = std::max(1, static_cast<int>(std::ceil(extent[1] / cell)));
  nz_ = std::max(1, static_cast<int>(std::ceil(extent[2] / cell)));
  start_.assign(cells() + 1, 0);
  sstart_.assign(cells() + 1, 0);
  cursor_.assign(cells() + 1, 0);
  cell_of_.assign(max_particles, 0);
  order_.assign(max_particles, 0);
}

std::size_t SphGrid::bytes() const {
  return (start_.size() + sstart_.size() + cursor_.size() + cell_of_.size() + order_.size()) * sizeof(std::uint32_t);
}

void SphGrid::build(const float* x, const float* y, const float* z, std::size_t n) {
  const std::size_t nc = cells();
  // cell of every particle
#pragma omp parallel for schedule(static) if (n > kSphParallelLight)
  for (std::size_t i = 0; i < n; ++i) cell_of_[i] = index(ix(x[i]), iy(y[i]), iz(z[i]));
  // histogram and exclusive prefix sum (serial: a few ns per particle, well under 2 % of a step)
  std::fill(cursor_.begin(), cursor_.end(), 0u);
  for (std::size_t i = 0; i < n; ++i) ++cursor_[cell_of_[i]];
  std::uint32_t acc = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    start_[c] = acc;
    acc += cursor_[c];
    cursor_[c] = start_[c];
  }
  start_[nc] = acc;
  // stable scatter: order[new] = old
  for (std::size_t i = 0; i < n; ++i) order_[cursor_[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
}

void SphGrid::build_static(const float* x, const float* y, const float* z, std::size_t n, std::uint32_t* order) {
  const std::size_t nc = cells();
  std::vector<std::uint32_t> cell(n), cur(nc + 1, 0u);  // once, before the steps
  for (std::size_t i = 0; i < n; ++i) {
    cell[i] = index(ix(x[i]), iy(y[i]), iz(z[i]));
    ++cur[cell[i]];
  }
  std::uint32_t acc = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    sstart_[c] = acc;
    acc += cur[c];
    cur[c] = sstart_[c];
  }
  sstart_[nc] = acc;
  for (std::size_t i = 0; i < n; ++i) order[cur[cell[i]]++] = static_cast<std::uint32_t>(i);
}

// ---------------------------------------------------------------------------------------------
// candidate gather

SphCellGather::SphCellGather(std::size_t capacity)
    : cap_((capacity + 15) & ~std::size_t(15)), threads_(std::max(omp_get_max_threads(), omp_get_num_procs())) {
  scratch_ = AlignedBuffer<float>(std::size_t(threads_) * kMaxArrays * (cap_ + 16));
}

}  // namespace huygens
