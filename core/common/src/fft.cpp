#include "huygens/common/fft.hpp"

#include <fftw3.h>
#include <omp.h>

#ifdef __linux__
#include <sys/mman.h>
#endif

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

namespace huygens {

namespace {
// FFTW's planner is not thread-safe: every plan creation and destruction goes through this.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}
void init_threads_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    fftwf_init_threads();
    fftwf_plan_with_nthreads(omp_get_max_threads());
  });
}
// 64-byte alignment (a cache line, an AVX-512 vector); size rounded up as aligned_alloc needs.
// A buffer of 2 MiB or more is aligned to 2 MiB and asked for transparent huge pages (Linux,
// where they are given on request only): a kernel that streams 21 planes at once (the LBM) then
// misses the TLB once per 2 MiB of a plane instead of once per 4 KiB (docs/lbm.md, "Speed"); the
// size is rounded up to 2 MiB (at most 2 MiB more memory per such buffer).
void* aligned_alloc64(std::size_t bytes) {
  constexpr std::size_t kHuge = std::size_t{2} << 20;
  if (bytes < kHuge) return std::aligned_alloc(64, (bytes + 63) / 64 * 64);
  const std::size_t size = (bytes + kHuge - 1) / kHuge * kHuge;
  void* p = std::aligned_alloc(kHuge, size);
#ifdef __linux__
  if (p) madvise(p, size, MADV_HUGEPAGE);  // advice only: without huge pages the buffer works the same
#endif
  return p;
}
unsigned flags_of(PlanEffort e) {
  switch (e) {
    case PlanEffort::estimate:
      return FFTW_ESTIMATE;
    case PlanEffort::measure:
      return FFTW_MEASURE;
    case PlanEffort::patient:
      return FFTW_PATIENT;
  }
  return FFTW_MEASURE;
}
}  // namespace

template <class T>
AlignedBuffer<T>::AlignedBuffer(std::size_t n) : n_(n) {
  if (n == 0) return;
  p_ = static_cast<T*>(aligned_alloc64(n * sizeof(T)));
  if (!p_) throw std::bad_alloc();
  for (std::size_t i = 0; i < n; ++i) new (p_ + i) T{};
}

template <class T>
AlignedBuffer<T>::~AlignedBuffer() {
  if (p_) std::free(p_);
}

template <class T>
AlignedBuffer<T>& AlignedBuffer<T>::operator=(AlignedBuffer&& o) noexcept {
  if (this != &o) {
    if (p_) std::free(p_);
    p_ = o.p_;
    n_ = o.n_;
    o.p_ = nullptr;
    o.n_ = 0;
  }
  return *this;
}

template class AlignedBuffer<float>;
template class AlignedBuffer<double>;
template class AlignedBuffer<cfloat>;
template class AlignedBuffer<unsigned char>;
template class AlignedBuffer<std::uint32_t>;

int fft_set_threads(int threads) {
  init_threads_once();
  std::lock_guard lock(planner_mutex());
  if (threads < 1) threads = 1;
  fftwf_plan_with_nthreads(threads);
  return threads;
}

const char* fft_version() { return fftwf_version; }

namespace {
// howmany row transforms of n points (rank 1, n points apart), from a to b.
fftwf_plan plan_rows(int n, int howmany, fftwf_complex* a, fftwf_complex* b, int sign) {
  fftw_iodim dim{n, 1, 1}, many{howmany, n, n};
  return fftwf_plan_guru_dft(1, &dim, 1, &many, a, b, sign, FFTW_ESTIMATE);
}
// In-place transpose of an N x N array in 16 x 16 blocks (two blocks of complex floats fit in L1;
// a block pair is swapped by one thread).
void transpose_square(cfloat* a, int n) {
  constexpr int B = 16;
  const int nb = (n + B - 1) / B;
#pragma omp parallel for schedule(dynamic, 4) if (n >= 512)
  for (int bi = 0; bi < nb; ++bi) {
    const int i1 = std::min(n, bi * B + B);
    for (int bj = bi; bj < nb; ++bj) {
      const int j1 = std::min(n, bj * B + B);
      for (int i = bi * B; i < i1; ++i) {
        cfloat* row = a + static_cast<std::size_t>(i) * n;
        for (int j = bj == bi ? i + 1 : bj * B; j < j1; ++j) std::swap(row[j], a[static_cast<std::size_t>(j) * n + i]);
      }
    }
  }
}
// Square grids from this size on take the row-column form under FFTW_ESTIMATE (fft.hpp).
constexpr int kRowColumnMin = 256;
}  // namespace

bool fft_row_column(int rows, int cols, PlanEffort effort) {
  return effort == PlanEffort::estimate && rows == cols && rows >= kRowColumnMin;
}

FftRows::FftRows(int n, int howmany, cfloat* a, cfloat* b, int sign) {
  if (howmany <= 0) return;  // a rank without rows: nothing to transform
  init_threads_once();
  std::lock_guard lock(planner_mutex());
  plan_ = plan_rows(n, howmany, reinterpret_cast<fftwf_complex*>(a), reinterpret_cast<fftwf_complex*>(b), sign);
  if (!plan_)
    throw std::runtime_error("FFTW could not plan " + std::to_string(howmany) + " rows of " + std::to_string(n));
}

FftRows::~FftRows() {
  std::lock_guard lock(planner_mutex());
  if (plan_) fftwf_destroy_plan(static_cast<fftwf_plan>(plan_));
}

void FftRows::execute(cfloat* a, cfloat* b) const {
  if (!plan_) return;
  fftwf_execute_dft(static_cast<fftwf_plan>(plan_), reinterpret_cast<fftwf_complex*>(a),
                    reinterpret_cast<fftwf_complex*>(b));
}

Fft2D::Fft2D(int rows, int cols, cfloat* in, cfloat* out, int sign, PlanEffort effort) : rows_(rows), cols_(cols) {
  init_threads_once();
  std::lock_guard lock(planner_mutex());
  auto* fin = reinterpret_cast<fftwf_complex*>(in);
  auto* fout = reinterpret_cast<fftwf_complex*>(out);
  // MEASURE/PATIENT overwrite the buffers while planning: plan on scratch copies.
  fftwf_plan p = nullptr;
  if (fft_row_column(rows, cols, effort)) {
    // a plan this process measured before (FFTW's wisdom) is taken as FFTW_ESTIMATE would
    p = fftwf_plan_dft_2d(rows, cols, fin, fout, sign, FFTW_ESTIMATE | FFTW_WISDOM_ONLY);
    if (!p) {
      p = plan_rows(rows, rows, fin, fout, sign);
      rows_plan_ = plan_rows(rows, rows, fout, fout, sign);
      if (p && !rows_plan_) fftwf_destroy_plan(p), p = nullptr;
    }
  } else if (effort == PlanEffort::estimate) {
    p = fftwf_plan_dft_2d(rows, cols, fin, fout, sign, flags_of(effort));
  } else {
    const std::size_t n = static_cast<std::size_t>(rows) * cols;
    auto* a = static_cast<fftwf_complex*>(aligned_alloc64(n * sizeof(fftwf_complex)));
    auto* b = in == out ? a : static_cast<fftwf_complex*>(aligned_alloc64(n * sizeof(fftwf_complex)));
    p = fftwf_plan_dft_2d(rows, cols, a, b, sign, flags_of(effort));
    if (b != a) std::free(b);
    std::free(a);
  }
  if (!p)
    throw std::runtime_error("FFTW could not plan a " + std::to_string(rows) + " x " + std::to_string(cols) +
                             " transform");
  plan_ = p;
  // Execution on the real buffers goes through fftwf_execute_dft (new-array execute),
  // which needs the same alignment as the planning buffers: all are 64-byte aligned.
  in_ = in;
  out_ = out;
}

Fft2D::~Fft2D() {
  std::lock_guard lock(planner_mutex());
  if (plan_) fftwf_destroy_plan(static_cast<fftwf_plan>(plan_));
  if (rows_plan_) fftwf_destroy_plan(static_cast<fftwf_plan>(rows_plan_));
}

void Fft2D::execute() const { execute(in_, out_); }

void Fft2D::execute(cfloat* in, cfloat* out) const {
  auto* fout = reinterpret_cast<fftwf_complex*>(out);
  fftwf_execute_dft(static_cast<fftwf_plan>(plan_), reinterpret_cast<fftwf_complex*>(in), fout);
  if (!rows_plan_) return;
  // row-column form: the columns as rows of the transpose
  transpose_square(out, rows_);
  fftwf_execute_dft(static_cast<fftwf_plan>(rows_plan_), fout, fout);
  transpose_square(out, rows_);
}

}  // namespace huygens
