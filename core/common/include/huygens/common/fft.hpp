#pragma once
// Thin RAII wrapper over FFTW single precision (fftw3f + fftw3f_omp): 64-byte aligned
// buffers and 2D complex-to-complex plans made once (docs/design.md 3.2). Execution never
// allocates. FFTW's convention: forward X_k = sum x_n e^{-2 pi i k n / N}, the inverse is
// unnormalised (the caller folds 1/N^2 into its spectral multiplier).
#include <complex>
#include <cstddef>
#include <numbers>
#include <span>

namespace huygens {

using cfloat = std::complex<float>;

/// Signed frequency of FFT index i (0 <= i < n, n even) in FFTW order: i below n/2, i - n from
/// n/2 on (the Nyquist index n/2 counts as -n/2).
constexpr int fft_signed_index(int i, int n) { return i < n / 2 ? i : i - n; }
/// Wavenumber of FFT index i on n points over a period of length_m (unit: rad/m):
///   k_i = 2 pi / L * fft_signed_index(i, n).
inline double fft_wavenumber(int i, int n, double length_m) {
  return 2.0 * std::numbers::pi / length_m * fft_signed_index(i, n);
}

/// A 64-byte aligned array, value-initialised, movable, not copyable.
template <class T>
class AlignedBuffer {
 public:
  AlignedBuffer() = default;
  explicit AlignedBuffer(std::size_t n);
  ~AlignedBuffer();
  AlignedBuffer(AlignedBuffer&& o) noexcept : p_(o.p_), n_(o.n_) {
    o.p_ = nullptr;
    o.n_ = 0;
  }
  AlignedBuffer& operator=(AlignedBuffer&& o) noexcept;
  AlignedBuffer(const AlignedBuffer&) = delete;
  AlignedBuffer& operator=(const AlignedBuffer&) = delete;

  T* data() { return p_; }
  const T* data() const { return p_; }
  std::size_t size() const { return n_; }
  T& operator[](std::size_t i) { return p_[i]; }
  const T& operator[](std::size_t i) const { return p_[i]; }
  std::span<T> span() { return {p_, n_}; }
  std::span<const T> span() const { return {p_, n_}; }

 private:
  T* p_ = nullptr;
  std::size_t n_ = 0;
};

/// How much time FFTW may spend choosing an algorithm when a plan is made.
enum class PlanEffort { estimate, measure, patient };

/// Process-wide FFTW set-up: thread count used by plans made after this call.
/// Plans made earlier keep their thread count. Returns the count in force.
int fft_set_threads(int threads);
/// FFTW's version string (for machine lines in benchmarks).
const char* fft_version();

/// True when Fft2D plans a rows x cols transform of this effort in row-column form (square, N >= 256,
/// estimate; unless this process holds a measured 2D plan in FFTW's wisdom, see Fft2D).
bool fft_row_column(int rows, int cols, PlanEffort effort);

/// The row stage of Fft2D's row-column form: `howmany` contiguous rows of n points each, transformed
/// from a to b (in place when a == b) by one FFTW_ESTIMATE plan. A row's arithmetic does not depend on
/// howmany or the placement (the same bits for slabs of 1/2 to 1/8 of a grid's rows, in and out of
/// place, N = 256 to 1024), so row slabs on MPI ranks (slab_fft.hpp) give Fft2D's bits.
class FftRows {
 public:
  FftRows(int n, int howmany, cfloat* a, cfloat* b, int sign);
  ~FftRows();
  FftRows(const FftRows&) = delete;
  FftRows& operator=(const FftRows&) = delete;
  /// Runs the plan on buffers of the same size, alignment and placement as the planned ones.
  void execute(cfloat* a, cfloat* b) const;

 private:
  void* plan_ = nullptr;
};

/// A 2D complex-to-complex transform of rows x cols, in place on the buffer given at
/// construction (or out of place from `in` to `out`). Plans are made once here. With
/// PlanEffort::estimate a square grid of N >= 256 runs in row-column form: the row transforms
/// (in to out), a transpose, the row transforms again (in place), a transpose back. FFTW_ESTIMATE's
/// own 2D plan transforms the columns at a stride of N points, which the cache serves badly at
/// these sizes (10 ms against 1.6 ms at 512^2 here, docs/performance.md); both forms are
/// deterministic, FFTW_MEASURE's choice is not (it times candidates). A 2D plan this process
/// measured before (FFTW's wisdom) is used instead, as FFTW_ESTIMATE itself does.
class Fft2D {
 public:
  Fft2D(int rows, int cols, cfloat* in, cfloat* out, int sign, PlanEffort effort = PlanEffort::measure);
  ~Fft2D();
  Fft2D(Fft2D&& o) noexcept
      : plan_(o.plan_), rows_plan_(o.rows_plan_), in_(o.in_), out_(o.out_), rows_(o.rows_), cols_(o.cols_) {
    o.plan_ = nullptr;
    o.rows_plan_ = nullptr;
  }
  Fft2D(const Fft2D&) = delete;
  Fft2D& operator=(const Fft2D&) = delete;
  Fft2D& operator=(Fft2D&&) = delete;

  /// Runs the planned transform on the planned buffers.
  void execute() const;
  /// Runs the plan on other buffers of the same size and alignment (fftwf_execute_dft).
  void execute(cfloat* in, cfloat* out) const;
  int rows() const { return rows_; }
  int cols() const { return cols_; }

  static constexpr int forward = -1;
  static constexpr int backward = +1;

 private:
  void* plan_ = nullptr;       // the 2D plan, or in row-column form the row pass from in to out
  void* rows_plan_ = nullptr;  // row-column form: the row pass in place on out (else nullptr)
  cfloat* in_ = nullptr;
  cfloat* out_ = nullptr;
  int rows_ = 0;
  int cols_ = 0;
};

}  // namespace huygens
