#pragma once
// The ranks of one run (docs/scale.md): with HUYGENS_MPI (HUYGENS_HAVE_MPI defined) and a program
// started by a launcher (mpirun, srun), MPI_COMM_WORLD; otherwise one rank and every call below is
// the identity, so a no-MPI build and a plain start run exactly as one process. A grid's rows are
// split into slabs (RowSlab), reductions agree on sums, maxima and "any" at step boundaries, and
// HaloExchange moves boundary rows between neighbour ranks without blocking.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#ifdef HUYGENS_HAVE_MPI
#include <mpi.h>
#endif

namespace huygens {

/// The rows [row0, row0 + rows) of a grid one rank holds.
struct RowSlab {
  std::size_t row0 = 0;
  std::size_t rows = 0;
};

/// Rows of rank `rank` when `n` rows are split over `ranks` ranks in order: the first n % ranks
/// ranks hold one row more than the others (n / ranks). ranks >= 1.
RowSlab row_slab(std::size_t n, int ranks, int rank);

namespace comm {

/// Starts MPI (MPI_Init_thread, MPI_THREAD_FUNNELED: only the thread that calls MPI, OpenMP
/// threads inside each rank never do) when built with MPI and started by a launcher (the
/// environment holds OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK or PMI_SIZE) or when
/// HUYGENS_MPI_INIT=1; a plain start stays one rank without MPI (a singleton MPI_Init would work
/// but costs about 0.5 s). Returns whether MPI was started. Call once, at the start of main.
bool init(int* argc, char*** argv);
/// Ends MPI after a clean end on every rank (a collective: all ranks call it).
void finalize();
/// What main returns after run_program(): when MPI is still running (an error escaped on this
/// rank, finalize() was not reached) and there are other ranks, MPI_Abort(code) ends them all
/// (the message is already printed); otherwise finalize() and `code`.
int exit_code(int code);
/// Whether MPI is running (init() started it, finalize() not yet called).
bool active();
int rank();
int size();
inline bool root() { return rank() == 0; }

/// Sums and maxima over all ranks (each rank passes its value, every rank gets the result).
double sum(double x);
std::int64_t sum(std::int64_t x);
double max(double x);
std::int64_t max(std::int64_t x);
std::int64_t min(std::int64_t x);
/// True on every rank when it is true on any rank (a non-finite value, a stop request, a failure).
bool any(bool x);
/// Element-wise sum / max over ranks, in place.
void sum(std::span<double> x);
void max(std::span<double> x);
void barrier();

#ifdef HUYGENS_HAVE_MPI
/// The communicator of the run (MPI_COMM_WORLD; MPI_COMM_SELF when MPI is not running).
MPI_Comm world();
#endif

}  // namespace comm

/// One round of non-blocking point-to-point messages of floats: post the receives and sends,
/// overlap work, then wait(). A peer < 0 (no neighbour) posts nothing. The buffers must stay
/// valid until wait(). Reserves room for `max_messages` requests up front (no allocation in a step).
class HaloExchange {
 public:
  explicit HaloExchange(std::size_t max_messages = 8);
  void recv(int peer, int tag, float* data, std::size_t n);
  void send(int peer, int tag, const float* data, std::size_t n);
  /// Completes every posted message.
  void wait();
  /// Bytes this rank sent since construction (unit: byte).
  std::uint64_t bytes_sent() const { return bytes_sent_; }
  /// Messages this rank sent since construction.
  std::uint64_t messages_sent() const { return messages_sent_; }

 private:
#ifdef HUYGENS_HAVE_MPI
  std::vector<MPI_Request> requests_;
#endif
  std::uint64_t bytes_sent_ = 0, messages_sent_ = 0;
};

}  // namespace huygens
