#pragma once
// Where the Huygens stages run (docs/huygens.md, docs/scale.md "Huygens on slabs"): the rows of
// the N x N field and of its spectrum this process holds, how it transforms them and how it sums
// over the processes. One process holds the whole grid (whole_grid_layout); an MPI rank a row
// slab (slab_layout, slab_solver.hpp): spatial rows y in [row0, row0 + rows) and spectrum rows
// [krow0, krow0 + krows), ky indices in the normal layout or kx indices when the spectrum is kept
// transposed (FFTW_MPI_TRANSPOSED_OUT). Every stage (propagator.hpp, stokes.hpp, spectral_solver.hpp)
// is written once against it: per-mode tables depend on |k| only and are read by the quadrant
// index (|row index|, |col index|), the same in either layout.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "huygens/common/fft.hpp"

namespace huygens {

/// One N x N complex transform over a layout's buffers: Fft2D on the whole grid, SlabFft on a
/// slab. Unnormalised, FFTW's sign convention (fft.hpp). Executing never allocates.
class GridTransform {
 public:
  virtual ~GridTransform() = default;
  /// Runs the plan on its buffers, or on others of the same size, alignment and placement.
  virtual void execute() const = 0;
  virtual void execute(cfloat* in, cfloat* out) const = 0;
  /// Bytes this process sends to others in one execution (unit: bytes; 0 on one process).
  virtual std::uint64_t sent_bytes() const { return 0; }
};

/// Plans one transform of `sign` (Fft2D::forward or backward) on (in, out); measured planning
/// overwrites them (plan before filling). Collective on a slab.
using TransformMaker = std::function<std::unique_ptr<GridTransform>(cfloat* in, cfloat* out, int sign)>;

/// The visible rows (the margin M excluded) a layout holds.
struct VisibleRows {
  /// First held spatial row inside the visible region, as a local row index.
  std::ptrdiff_t first = 0;
  /// How many (0 when the slab lies in a margin).
  std::ptrdiff_t count = 0;
  /// Row of the global visible region (N - 2M rows) where they start.
  std::ptrdiff_t row0 = 0;
};

struct GridLayout {
  int n = 0;
  /// Spatial rows (y) held: [row0, row0 + rows).
  std::ptrdiff_t row0 = 0, rows = 0;
  /// Spectrum rows held: [krow0, krow0 + krows), each a row of N values.
  std::ptrdiff_t krow0 = 0, krows = 0;
  /// Spectrum rows are kx indices (columns ky); false: rows are ky, as in the field.
  bool transposed = false;
  /// Complex values each field or spectrum buffer needs (>= rows N and krows N).
  std::ptrdiff_t alloc = 0;
  /// One process with the whole grid: a stage may read Z^(-k) beside Z^(k) (the packed height,
  /// the energy) and take commands. False on a slab, even a slab of one rank.
  bool whole = true;
  /// The layout's transforms.
  TransformMaker make_transform;
  /// Sums the values over the processes in place (one reduction; nothing on one process).
  std::function<void(std::span<double>)> sum_over_ranks;

  std::size_t field_size() const { return static_cast<std::size_t>(rows) * static_cast<std::size_t>(n); }
  std::size_t spectrum_size() const { return static_cast<std::size_t>(krows) * static_cast<std::size_t>(n); }
  /// Global index of local spectrum row lr: the row's FFT index (ky, or kx when transposed).
  int spectrum_row(std::ptrdiff_t lr) const { return static_cast<int>(krow0 + lr); }
  /// The visible rows of a margin of M cells.
  VisibleRows visible(int margin) const;
};

/// The whole N x N grid on one process, transforms by Fft2D of this planning effort.
GridLayout whole_grid_layout(int n, PlanEffort effort);

/// Quadrant index of FFT index i (|signed index|, 0 .. N/2): the row or column of a per-mode table
/// that depends on |k| only.
inline int quadrant_index(int i, int n) { return i <= n / 2 ? i : n - i; }

}  // namespace huygens
