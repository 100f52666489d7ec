#pragma once
// FFTW's MPI transforms on row slabs (issue 17, docs/scale.md "Huygens on slabs"). An N x N
// complex grid is split by rows over the ranks of a communicator (fftwf_mpi_local_size_2d_
// transposed): rank p owns the spatial rows y in [row0, row0 + rows). The spectrum is kept
// TRANSPOSED: rank p owns the rows of the transposed spectrum, i.e. the kx indices in
// [krow0, krow0 + krows), each row holding all N ky indices. The forward transform is planned
// with FFTW_MPI_TRANSPOSED_OUT and the backward one with FFTW_MPI_TRANSPOSED_IN, so each pays
// one all-to-all transpose instead of two. Per-mode tables that depend on |k| only are read the
// same way in either layout (their quadrant index (|i|, |j|) is symmetric).
// Built only with HUYGENS_HAVE_MPI (CMake option HUYGENS_MPI).
#ifdef HUYGENS_HAVE_MPI
#include <mpi.h>

#include <cstddef>
#include <memory>

#include "huygens/common/fft.hpp"

namespace huygens {

/// Initialises FFTW's threads and then FFTW-MPI, once per process (MPI must be initialised).
void slab_fft_init();

/// The row-slab split of an N x N grid over the ranks of a communicator.
struct SlabGrid {
  int n = 0;
  int rank = 0, ranks = 1;
  /// Spatial rows (y) owned: [row0, row0 + rows).
  std::ptrdiff_t row0 = 0, rows = 0;
  /// Rows of the transposed spectrum owned (kx indices; a row holds every ky): [krow0, krow0 + krows).
  std::ptrdiff_t krow0 = 0, krows = 0;
  /// This rank's share of the columns in a transpose (local_n1; the block it keeps).
  std::ptrdiff_t share = 0;
  /// Complex elements each slab buffer needs (unit: complex floats; >= rows N and krows N).
  std::ptrdiff_t alloc = 0;
  /// Spectrum layout: transposed (kx rows, one transpose per transform) or normal (ky rows, the
  /// same rows as the field, two transposes per transform).
  bool transposed = true;
  /// Transforms in Fft2D's row-column form (SlabFft; normal layout only), the one-process bits.
  bool row_column = false;
  /// All-to-all transposes one N x N transform pays: 1 transposed, 2 normal.
  int transposes() const { return transposed ? 1 : 2; }
};

/// The split FFTW chooses for an N x N grid on `comm` (collective); normal layout: krow0 = row0,
/// krows = rows (the spectrum's rows are ky indices).
SlabGrid slab_grid(int n, MPI_Comm comm, bool transposed = true);

/// One N x N complex transform over the slabs (collective plan and execution): forward =
/// spatial rows -> spectrum, backward = spectrum -> spatial rows; in the transposed layout with
/// FFTW_MPI_TRANSPOSED_OUT (forward) / FFTW_MPI_TRANSPOSED_IN (backward). FFTW's MPI algorithm
/// transforms the locally contiguous dimension first, with other kernels than the one-process
/// plan (a rounding difference of ~1e-7 per transform, docs/scale.md). Unnormalised, FFTW's sign
/// convention (fft.hpp).
/// Row-column form (SlabGrid::row_column, normal layout): the local rows (FftRows, in to out), an
/// all-to-all transpose (fftwf_mpi_plan_many_transpose, in place on out), the local rows again, the
/// transpose back: the arithmetic of Fft2D's row-column form (FFTW_ESTIMATE, N >= 256,
/// slab_row_column), so the result is the one-process transform bit for bit, at two transposes per
/// transform; `effort` is then not used.
class SlabFft {
 public:
  /// Plans on (in, out); measure/patient planning overwrites them (plan before filling).
  SlabFft(const SlabGrid& g, cfloat* in, cfloat* out, int sign, PlanEffort effort, MPI_Comm comm);
  ~SlabFft();
  SlabFft(const SlabFft&) = delete;
  SlabFft& operator=(const SlabFft&) = delete;
  /// Runs the plan on its buffers, or on others of the same size, alignment and placement.
  void execute() const;
  void execute(cfloat* in, cfloat* out) const;

 private:
  void* plan_ = nullptr;                     // FFTW's MPI plan, or the row-column form's transpose
  std::unique_ptr<FftRows> first_, second_;  // row-column form: the row stages
  cfloat *in_ = nullptr, *out_ = nullptr;    // row-column form: the planned buffers
};

/// True when Fft2D runs an N x N transform of this effort in row-column form (fft_row_column), i.e.
/// when slab transforms in row-column form give the one-process bits.
bool slab_row_column(int n, PlanEffort effort);

/// Bytes one rank sends in one all-to-all transpose of an N x N complex float slab (unit: bytes):
/// its rows x N values, all but the block it keeps, 8 rows (N - n_p) bytes (n_p: the columns it
/// keeps), which is 8 N^2/P (P-1)/P for an even split.
double slab_transpose_bytes(const SlabGrid& g);

}  // namespace huygens
#endif
