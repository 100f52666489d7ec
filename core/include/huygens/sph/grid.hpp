#pragma once
// Uniform neighbour grid for SPH (paper 000 section 3; MCG03 section 6): cubic cells of side
// = support radius h over the container, cell index c = ix + nx (iy + ny iz) (x fastest).
// Particles are reordered by cell with a counting sort every step, so the particles of a cell
// are contiguous and the three x-neighbour cells of a row form ONE contiguous index range:
// a particle's neighbours lie in 9 ranges (the 27 cells), scanned by flat vectorisable loops.
// No per-particle neighbour lists are built.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace huygens {

class SphGrid {
 public:
  SphGrid() = default;
  /// A grid covering [0, extent] on each axis with cells of side `cell` (unit: m).
  SphGrid(const std::array<float, 3>& extent, float cell, std::size_t max_particles);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nz() const { return nz_; }
  float cell() const { return cell_; }
  std::size_t cells() const { return static_cast<std::size_t>(nx_) * ny_ * nz_; }

  /// Cell coordinates of a point, clamped to the grid.
  int ix(float x) const { return clampi(static_cast<int>(x * inv_), nx_); }
  int iy(float y) const { return clampi(static_cast<int>(y * inv_), ny_); }
  int iz(float z) const { return clampi(static_cast<int>(z * inv_), nz_); }
  std::uint32_t index(int i, int j, int k) const { return static_cast<std::uint32_t>(i + nx_ * (j + ny_ * k)); }

  /// Counting sort of n particles by cell: fills cell_of (per particle, input order), the
  /// cell start table, and `order` (order[new] = old index). No allocation.
  void build(const float* x, const float* y, const float* z, std::size_t n);
  /// First particle of cell c in sorted order; start(c + 1) is one past its last.
  std::uint32_t start(std::size_t c) const { return start_[c]; }
  const std::uint32_t* order() const { return order_.data(); }
  /// Sorted index range [begin, end) of the cells ix0..ix1 of row (iy, iz).
  void row_range(int ix0, int ix1, int iy, int iz, std::uint32_t& begin, std::uint32_t& end) const {
    begin = start_[index(ix0, iy, iz)];
    end = start_[index(ix1, iy, iz) + 1];
  }
  /// Bytes held by the grid tables.
  std::size_t bytes() const;

 private:
  static int clampi(int v, int n) { return v < 0 ? 0 : (v >= n ? n - 1 : v); }
  int nx_ = 1, ny_ = 1, nz_ = 1;
  float cell_ = 1.f, inv_ = 1.f;
  std::vector<std::uint32_t> start_;    // cells + 1 entries
  std::vector<std::uint32_t> cursor_;   // scatter cursors
  std::vector<std::uint32_t> cell_of_;  // per particle
  std::vector<std::uint32_t> order_;    // sorted -> original index
};

}  // namespace huygens
