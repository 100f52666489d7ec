#pragma once
// Uniform neighbour grid for SPH (paper 000 section 3; Mueller, Charypar and Gross 2003 section
// 6): cubic cells of side = support radius h over the container, cell index c = ix + nx (iy + ny iz)
// (x fastest). Particles are reordered by cell with a counting sort every step, so the particles
// of a cell are contiguous and the three x-neighbour cells of a row form ONE contiguous index
// range: a particle's neighbours lie in 9 ranges (the 27 cells), scanned by flat vectorisable
// loops. WCSPH builds no per-particle neighbour lists (DFSPH builds one per step for the
// iterations of its solves, from these ranges: dfsph.hpp). The static boundary particles (boundary.hpp)
// have a second start table over the same cells, sorted once (build_static); points outside the
// container fall into the edge cells (cell coordinates are clamped). SphCellGather copies the 9
// fluid ranges and the 9 boundary ranges of a cell once into per-thread contiguous scratch, so
// each particle of the cell runs one loop over the fluid and one over the boundary candidates.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "huygens/common/fft.hpp"

namespace huygens {

/// Below this many particles an SPH step takes a few hundred microseconds: the neighbour passes
/// stay on one thread (threads cost more than they give).
inline constexpr std::size_t kSphParallelMin = 2048;
/// The streaming loops (sort gather, cell index, integration) cost a few ns per particle: below
/// this many particles waking a second thread costs more than the loop (docs/sph.md).
inline constexpr std::size_t kSphParallelLight = std::size_t(1) << 16;

class SphGrid {
 public:
  SphGrid() = default;
  /// A grid covering [0, extent] on each axis with cells of side `cell` (unit: m).
  SphGrid(const std::array<float, 3>& extent, float cell, std::size_t max_particles);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  int nz() const { return nz_; }
  /// Cell side (unit: m).
  float cell() const { return cell_; }
  std::size_t cells() const { return static_cast<std::size_t>(nx_) * ny_ * nz_; }

  /// Cell coordinates of a point (unit: m), clamped to the grid.
  int ix(float x) const { return clampi(static_cast<int>(x * inv_), nx_); }
  int iy(float y) const { return clampi(static_cast<int>(y * inv_), ny_); }
  int iz(float z) const { return clampi(static_cast<int>(z * inv_), nz_); }
  std::uint32_t index(int i, int j, int k) const { return static_cast<std::uint32_t>(i + nx_ * (j + ny_ * k)); }

  /// Counting sort of n particles by cell: fills cell_of (per particle, input order), the
  /// cell start table, and `order` (order[new] = old index). No allocation.
  void build(const float* x, const float* y, const float* z, std::size_t n);
  /// Counting sort of the n static (boundary) particles into the second start table; `order`
  /// (order[new] = old index, n entries) receives their order. Call once, before the steps.
  void build_static(const float* x, const float* y, const float* z, std::size_t n, std::uint32_t* order);
  /// First particle of cell c in sorted order; start(c + 1) is one past its last.
  std::uint32_t start(std::size_t c) const { return start_[c]; }
  /// First static (boundary) particle of cell c; static_start(c + 1) is one past its last.
  std::uint32_t static_start(std::size_t c) const { return sstart_[c]; }
  const std::uint32_t* order() const { return order_.data(); }
  /// Sorted index range [begin, end) of the cells ix0..ix1 of row (iy, iz) (kStatic: of the boundary particles).
  template <bool kStatic = false>
  void row_range(int ix0, int ix1, int iy, int iz, std::uint32_t& begin, std::uint32_t& end) const {
    const std::uint32_t* st = kStatic ? sstart_.data() : start_.data();
    begin = st[index(ix0, iy, iz)];
    end = st[index(ix1, iy, iz) + 1];
  }
  /// Calls row(begin, end, kz) for the 9 sorted index ranges of the 27 cells around (cx, cy, cz)
  /// (clipped to the grid), z layer by z layer from below; stops when row returns false. kStatic:
  /// the ranges of the boundary particles.
  template <bool kStatic = false, class Row>
  bool for_each_row(int cx, int cy, int cz, Row&& row) const {
    const int x0 = std::max(cx - 1, 0), x1 = std::min(cx + 1, nx_ - 1);
    for (int kz = std::max(cz - 1, 0); kz <= std::min(cz + 1, nz_ - 1); ++kz)
      for (int ky = std::max(cy - 1, 0); ky <= std::min(cy + 1, ny_ - 1); ++ky) {
        std::uint32_t b, e;
        row_range<kStatic>(x0, x1, ky, kz, b, e);
        if (!row(b, e, kz)) return false;
      }
    return true;
  }
  /// Bytes held by the grid tables.
  std::size_t bytes() const;

 private:
  static int clampi(int v, int n) { return v < 0 ? 0 : (v >= n ? n - 1 : v); }
  int nx_ = 1, ny_ = 1, nz_ = 1;
  float cell_ = 1.f, inv_ = 1.f;
  std::vector<std::uint32_t> start_;    // cells + 1 entries
  std::vector<std::uint32_t> sstart_;   // cells + 1 entries, the static (boundary) particles
  std::vector<std::uint32_t> cursor_;   // scatter cursors
  std::vector<std::uint32_t> cell_of_;  // per particle
  std::vector<std::uint32_t> order_;    // sorted -> original index
};

/// Per-thread scratch for the candidates of one cell (up to kMaxArrays float arrays, SoA,
/// 64-byte aligned and padded to whole vectors): fluid arrays, then boundary arrays.
class SphCellGather {
 public:
  static constexpr int kMaxArrays = 17;
  SphCellGather() = default;
  /// Room for `capacity` candidates per array and thread, for every thread OpenMP may run.
  explicit SphCellGather(std::size_t capacity);
  /// Candidates per array and thread, and the threads with scratch (higher thread numbers take the direct path).
  std::size_t capacity() const { return cap_; }
  int threads() const { return threads_; }

  /// One thread's walk over the cells of its particles (in sorted order, so each cell is
  /// gathered once per thread). `src` holds `arrays` fluid arrays in the grid's sorted order,
  /// `bsrc` `barrays` boundary arrays in the grid's static order (arrays + barrays <= kMaxArrays).
  class Cursor {
   public:
    Cursor(const SphGrid& grid, SphCellGather& gather, int thread, const float* const* src, int arrays,
           const float* const* bsrc = nullptr, int barrays = 0)
        : grid_(&grid), arrays_(arrays), barrays_(barrays), cap_(gather.cap_), own_(thread < gather.threads_) {
      for (int a = 0; a < kMaxArrays; ++a) {
        src_[a] = a < arrays ? src[a] : a < arrays + barrays ? bsrc[a - arrays] : nullptr;
        dst_[a] = own_ ? gather.scratch_.data() + (std::size_t(thread) * kMaxArrays + a) * (gather.cap_ + 16) : nullptr;
      }
    }
    /// The gathered copy of src[a] (a < arrays) or bsrc[a - arrays].
    const float* scratch(int a) const { return dst_[a]; }
    /// Visits the candidates of cell (cx, cy, cz): fn(true, false, 0, count) on the gathered fluid
    /// copies and fn(true, true, 0, bcount) on the gathered boundary copies (when barrays > 0 and
    /// bcount > 0), or, when this thread has no scratch or the candidates overflow it,
    /// fn(false, boundary, b, e) for each of the nine ranges of the source arrays. Returns whether
    /// the candidates were gathered.
    template <class Visit>
    bool visit(int cx, int cy, int cz, Visit&& fn) {
      const std::uint32_t c = grid_->index(cx, cy, cz);
      if (own_ && c != cell_) {
        cell_ = c;
        gathered_ = gather(cx, cy, cz);
      }
      if (own_ && gathered_) {
        fn(true, false, std::uint32_t(0), count_);
        if (barrays_ > 0 && bcount_ > 0) fn(true, true, std::uint32_t(0), bcount_);
        return true;
      }
      grid_->for_each_row(cx, cy, cz, [&](std::uint32_t b, std::uint32_t e, int) {
        fn(false, false, b, e);
        return true;
      });
      if (barrays_ > 0)
        grid_->for_each_row<true>(cx, cy, cz, [&](std::uint32_t b, std::uint32_t e, int) {
          if (e > b) fn(false, true, b, e);
          return true;
        });
      return false;
    }

   private:
    /// Copies the candidates into the scratch; false when they do not fit. Inline, with the
    /// constructor, so the cursor's state stays in registers in the neighbour loops.
    bool gather(int cx, int cy, int cz) {
      std::size_t cnt = 0;
      const bool fits = grid_->for_each_row(cx, cy, cz, [&](std::uint32_t b, std::uint32_t e, int) {
        if (cnt + (e - b) > cap_) return false;
        for (int a = 0; a < arrays_; ++a) std::copy(src_[a] + b, src_[a] + e, dst_[a] + cnt);
        cnt += e - b;
        return true;
      });
      count_ = static_cast<std::uint32_t>(cnt);
      if (!fits || barrays_ == 0) return fits;
      cnt = 0;
      const bool bfits = grid_->for_each_row<true>(cx, cy, cz, [&](std::uint32_t b, std::uint32_t e, int) {
        if (cnt + (e - b) > cap_) return false;
        for (int a = arrays_; a < arrays_ + barrays_; ++a) std::copy(src_[a] + b, src_[a] + e, dst_[a] + cnt);
        cnt += e - b;
        return true;
      });
      bcount_ = static_cast<std::uint32_t>(cnt);
      return bfits;
    }
    const SphGrid* grid_;
    const float* src_[kMaxArrays];
    float* dst_[kMaxArrays];
    int arrays_, barrays_;
    std::size_t cap_;
    bool own_;
    std::uint32_t cell_ = ~0u, count_ = 0, bcount_ = 0;
    bool gathered_ = false;
  };

 private:
  AlignedBuffer<float> scratch_;
  std::size_t cap_ = 0;
  int threads_ = 0;
};

}  // namespace huygens
