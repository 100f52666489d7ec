#include "huygens/common/slab_fft.hpp"

#ifdef HUYGENS_HAVE_MPI
#include <fftw3-mpi.h>
#include <omp.h>

#include <mutex>
#include <stdexcept>

namespace huygens {

void slab_fft_init() {
  static std::once_flag once;
  std::call_once(once, [] {
    // fftwf_init_threads() (inside fft_set_threads) must come before fftwf_mpi_init()
    fft_set_threads(omp_get_max_threads());
    fftwf_mpi_init();
  });
}

SlabGrid slab_grid(int n, MPI_Comm comm, bool transposed) {
  slab_fft_init();
  SlabGrid g;
  g.n = n;
  MPI_Comm_rank(comm, &g.rank);
  MPI_Comm_size(comm, &g.ranks);
  g.transposed = transposed;
  g.alloc = fftwf_mpi_local_size_2d_transposed(n, n, comm, &g.rows, &g.row0, &g.krows, &g.krow0);
  g.share = g.krows;
  if (!transposed) g.krows = g.rows, g.krow0 = g.row0;
  return g;
}

namespace {
unsigned effort_flags(PlanEffort e) {
  return e == PlanEffort::estimate ? FFTW_ESTIMATE : e == PlanEffort::measure ? FFTW_MEASURE : FFTW_PATIENT;
}
}  // namespace

bool slab_row_column(int n, PlanEffort effort) { return fft_row_column(n, n, effort); }

SlabFft::SlabFft(const SlabGrid& g, cfloat* in, cfloat* out, int sign, PlanEffort effort, MPI_Comm comm) {
  slab_fft_init();
  if (g.row_column) {
    if (g.transposed) throw std::logic_error("SlabFft: the row-column form needs the normal layout");
    first_ = std::make_unique<FftRows>(g.n, static_cast<int>(g.rows), in, out, sign);
    second_ = std::make_unique<FftRows>(g.n, static_cast<int>(g.share), out, out, sign);
    // an N x N array of complex values (2 floats) split by rows; square, so the transpose's rows
    // are split as the array's and one plan transposes there and back
    auto* o = reinterpret_cast<float*>(out);
    plan_ = fftwf_mpi_plan_many_transpose(g.n, g.n, 2, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, o, o, comm,
                                          FFTW_ESTIMATE);
    if (!plan_) throw std::runtime_error("fftwf_mpi_plan_many_transpose failed");
    in_ = in;
    out_ = out;
    return;
  }
  const unsigned layout = !g.transposed            ? 0u
                          : sign == Fft2D::forward ? FFTW_MPI_TRANSPOSED_OUT
                                                   : FFTW_MPI_TRANSPOSED_IN;
  plan_ = fftwf_mpi_plan_dft_2d(g.n, g.n, reinterpret_cast<fftwf_complex*>(in), reinterpret_cast<fftwf_complex*>(out),
                                comm, sign, effort_flags(effort) | layout);
  if (!plan_) throw std::runtime_error("fftwf_mpi_plan_dft_2d failed");
}

SlabFft::~SlabFft() {
  if (plan_) fftwf_destroy_plan(static_cast<fftwf_plan>(plan_));
}

void SlabFft::execute() const {
  if (first_) return execute(in_, out_);
  fftwf_execute(static_cast<fftwf_plan>(plan_));
}

void SlabFft::execute(cfloat* in, cfloat* out) const {
  if (first_) {  // rows, transpose, rows (the columns), transpose back: Fft2D's row-column form
    auto* o = reinterpret_cast<float*>(out);
    first_->execute(in, out);
    fftwf_mpi_execute_r2r(static_cast<fftwf_plan>(plan_), o, o);
    second_->execute(out, out);
    fftwf_mpi_execute_r2r(static_cast<fftwf_plan>(plan_), o, o);
    return;
  }
  fftwf_mpi_execute_dft(static_cast<fftwf_plan>(plan_), reinterpret_cast<fftwf_complex*>(in),
                        reinterpret_cast<fftwf_complex*>(out));
}

double slab_transpose_bytes(const SlabGrid& g) {
  // this rank's rows x N complex values leave, except the rows x n_p block it keeps (n_p: its
  // share of the other dimension, the same split)
  return 8.0 * static_cast<double>(g.rows) * static_cast<double>(g.n - g.share);
}

}  // namespace huygens
#endif
