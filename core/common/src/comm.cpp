#include "huygens/common/comm.hpp"

#include <climits>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace huygens {

RowSlab row_slab(std::size_t n, int ranks, int rank) {
  if (ranks < 1 || rank < 0 || rank >= ranks) throw std::invalid_argument("row_slab: rank outside [0, ranks)");
  const std::size_t p = static_cast<std::size_t>(ranks), r = static_cast<std::size_t>(rank);
  const std::size_t base = n / p, extra = n % p;
  return {r * base + (r < extra ? r : extra), base + (r < extra ? 1 : 0)};
}

namespace comm {

namespace {
bool g_active = false;

// Started by a launcher: Open MPI's mpirun, PMIx (Slurm's srun, prterun) or a PMI-1/2 launcher
// (MPICH's hydra), or asked for explicitly.
bool launched() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  const char* force = std::getenv("HUYGENS_MPI_INIT");
  return force && std::string(force) == "1";
}
}  // namespace

#ifdef HUYGENS_HAVE_MPI

bool init(int* argc, char*** argv) {
  if (g_active || !launched()) return g_active;
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw std::runtime_error("MPI_Init_thread failed");
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw std::runtime_error("this MPI does not provide MPI_THREAD_FUNNELED (OpenMP threads inside a rank)");
  }
  g_active = true;
  return true;
}

void finalize() {
  if (!g_active) return;
  g_active = false;
  MPI_Finalize();
}

int exit_code(int code) {
  if (g_active && size() > 1 && code != 0) MPI_Abort(MPI_COMM_WORLD, code);
  finalize();
  return code;
}

MPI_Comm world() { return g_active ? MPI_COMM_WORLD : MPI_COMM_SELF; }

int rank() {
  int r = 0;
  if (g_active) MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int size() {
  int s = 1;
  if (g_active) MPI_Comm_size(MPI_COMM_WORLD, &s);
  return s;
}

namespace {
template <class T>
T reduce(T x, MPI_Datatype type, MPI_Op op) {
  if (!g_active) return x;
  T out{};
  MPI_Allreduce(&x, &out, 1, type, op, MPI_COMM_WORLD);
  return out;
}
void reduce_span(std::span<double> x, MPI_Op op) {
  if (g_active && !x.empty())
    MPI_Allreduce(MPI_IN_PLACE, x.data(), static_cast<int>(x.size()), MPI_DOUBLE, op, MPI_COMM_WORLD);
}
}  // namespace

double sum(double x) { return reduce(x, MPI_DOUBLE, MPI_SUM); }
std::int64_t sum(std::int64_t x) { return reduce(x, MPI_INT64_T, MPI_SUM); }
double max(double x) { return reduce(x, MPI_DOUBLE, MPI_MAX); }
std::int64_t max(std::int64_t x) { return reduce(x, MPI_INT64_T, MPI_MAX); }
std::int64_t min(std::int64_t x) { return reduce(x, MPI_INT64_T, MPI_MIN); }
bool any(bool x) { return reduce(x ? 1 : 0, MPI_INT, MPI_MAX) != 0; }
void sum(std::span<double> x) { reduce_span(x, MPI_SUM); }
void max(std::span<double> x) { reduce_span(x, MPI_MAX); }
void barrier() {
  if (g_active) MPI_Barrier(MPI_COMM_WORLD);
}

#else  // one rank, no MPI

bool init(int*, char***) { return false; }
void finalize() {}
int exit_code(int code) { return code; }
int rank() { return 0; }
int size() { return 1; }
double sum(double x) { return x; }
std::int64_t sum(std::int64_t x) { return x; }
double max(double x) { return x; }
std::int64_t max(std::int64_t x) { return x; }
std::int64_t min(std::int64_t x) { return x; }
bool any(bool x) { return x; }
void sum(std::span<double>) {}
void max(std::span<double>) {}
void barrier() {}

#endif

bool active() { return g_active; }

}  // namespace comm

HaloExchange::HaloExchange(std::size_t max_messages) {
#ifdef HUYGENS_HAVE_MPI
  requests_.reserve(max_messages);
#else
  (void)max_messages;
#endif
}

namespace {
int checked_count(std::size_t n) {
  if (n > static_cast<std::size_t>(INT_MAX))
    throw std::length_error("HaloExchange: message longer than INT_MAX floats");
  return static_cast<int>(n);
}
[[noreturn]] void no_peer() { throw std::logic_error("HaloExchange: a peer rank in a run of one rank"); }
}  // namespace

void HaloExchange::recv(int peer, int tag, float* data, std::size_t n) {
  if (peer < 0) return;
#ifdef HUYGENS_HAVE_MPI
  if (!comm::active()) no_peer();
  requests_.emplace_back();
  MPI_Irecv(data, checked_count(n), MPI_FLOAT, peer, tag, MPI_COMM_WORLD, &requests_.back());
#else
  (void)tag, (void)data, (void)n;
  no_peer();
#endif
}

void HaloExchange::send(int peer, int tag, const float* data, std::size_t n) {
  if (peer < 0) return;
#ifdef HUYGENS_HAVE_MPI
  if (!comm::active()) no_peer();
  requests_.emplace_back();
  MPI_Isend(data, checked_count(n), MPI_FLOAT, peer, tag, MPI_COMM_WORLD, &requests_.back());
  bytes_sent_ += n * sizeof(float);
  ++messages_sent_;
#else
  (void)tag, (void)data, (void)n;
  no_peer();
#endif
}

void HaloExchange::wait() {
#ifdef HUYGENS_HAVE_MPI
  if (requests_.empty()) return;
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  requests_.clear();
#endif
}

}  // namespace huygens
