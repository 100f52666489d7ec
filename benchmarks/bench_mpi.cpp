// huygens-bench mpi (issue 17, docs/scale.md "Strong scaling"): the Huygens slab solver
// (slab_solver.hpp) on 1 and 2 MPI ranks at 1024^2 and 2048^2 (--quick: 256^2 and 512^2):
// time per step, split into local work and all-to-all time, and the bytes each rank sends per
// step, the formula T x 8 N^2/P (P-1)/P against a count of what MPI was asked to send.
//
// Outside mpirun the section runs itself under it and prints the command:
//   OMP_NUM_THREADS=1 mpirun --oversubscribe [--allow-run-as-root] -np 2 huygens-bench mpi
// Under mpirun (OMPI_COMM_WORLD_SIZE set) it measures; rank 0 prints.
//
// Measured bytes: this program defines MPI_Alltoall, MPI_Alltoallv, MPI_Sendrecv, MPI_Send and
// MPI_Isend (the calls FFTW-MPI's transposes make), which count the bytes addressed to other
// ranks and forward to the PMPI_ entry points (the MPI profiling interface).
// All-to-all time: a separately planned fftwf_mpi transpose of the same N x N complex slab
// (the operation the transforms perform) timed over the same number of transposes as a step;
// local work = step time - that.
#include "bench.hpp"

#ifdef HUYGENS_HAVE_MPI
#include <fftw3-mpi.h>
#include <mpi.h>
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "huygens/common/scene.hpp"
#include "huygens/common/slab_fft.hpp"
#include "huygens/spectral/slab_solver.hpp"
#include "huygens/spectral/spectral_solver.hpp"

namespace {
// bytes addressed to other ranks by the intercepted calls (MPI profiling interface)
double g_sent = 0;
int type_bytes(MPI_Datatype t) {
  int s = 0;
  PMPI_Type_size(t, &s);
  return s;
}
int my_rank(MPI_Comm c) {
  int r = 0;
  PMPI_Comm_rank(c, &r);
  return r;
}
}  // namespace

extern "C" {
int MPI_Alltoall(const void* sb, int sc, MPI_Datatype st, void* rb, int rc, MPI_Datatype rt, MPI_Comm comm) {
  int p = 1;
  PMPI_Comm_size(comm, &p);
  g_sent += static_cast<double>(sc) * type_bytes(st) * (p - 1);
  return PMPI_Alltoall(sb, sc, st, rb, rc, rt, comm);
}
int MPI_Alltoallv(const void* sb, const int sc[], const int sd[], MPI_Datatype st, void* rb, const int rc[],
                  const int rd[], MPI_Datatype rt, MPI_Comm comm) {
  int p = 1;
  PMPI_Comm_size(comm, &p);
  const int me = my_rank(comm);
  for (int q = 0; q < p; ++q)
    if (q != me) g_sent += static_cast<double>(sc[q]) * type_bytes(st);
  return PMPI_Alltoallv(sb, sc, sd, st, rb, rc, rd, rt, comm);
}
int MPI_Sendrecv(const void* sb, int sc, MPI_Datatype st, int dest, int stag, void* rb, int rc, MPI_Datatype rt,
                 int src, int rtag, MPI_Comm comm, MPI_Status* status) {
  if (dest != my_rank(comm) && dest != MPI_PROC_NULL) g_sent += static_cast<double>(sc) * type_bytes(st);
  return PMPI_Sendrecv(sb, sc, st, dest, stag, rb, rc, rt, src, rtag, comm, status);
}
int MPI_Send(const void* b, int c, MPI_Datatype t, int dest, int tag, MPI_Comm comm) {
  if (dest != my_rank(comm) && dest != MPI_PROC_NULL) g_sent += static_cast<double>(c) * type_bytes(t);
  return PMPI_Send(b, c, t, dest, tag, comm);
}
int MPI_Isend(const void* b, int c, MPI_Datatype t, int dest, int tag, MPI_Comm comm, MPI_Request* req) {
  if (dest != my_rank(comm) && dest != MPI_PROC_NULL) g_sent += static_cast<double>(c) * type_bytes(t);
  return PMPI_Isend(b, c, t, dest, tag, comm, req);
}
}

namespace huygens::bench {

namespace {

// the default scene's physics at n x n (first order, cutoff, 3 Gaussians; margin n/8), no still skip
HuygensScene mpi_scene(int n) {
  auto j = nlohmann::json::parse(shipped_scene("default.json"));
  j["grid"]["n"] = n;
  j["grid"]["margin"] = n / 8;
  j["initial"].erase(3);  // the plane wave's wavelength is a grid-size choice; keep the humps
  j["time"]["display_per_step"] = 1;
  RunOptions o;
  o.measure_plans = false;  // FFTW_ESTIMATE: MPI measure planning at 2048^2 takes minutes here
  HuygensScene s = parse_huygens_scene(parse_scene_text(j.dump(), "mpi bench"), o);
  s.still_skip = false;
  return s;
}

struct Timing {
  double step_s = 0;   // mean wall time per step (the slowest rank)
  double bytes = 0;    // measured bytes sent per step by this rank
  double formula = 0;  // HuygensSlabSolver::bytes_sent_per_step()
  int transposes = 0;  // per step
};

Timing time_solver(const HuygensScene& sc, MPI_Comm comm, int steps, SlabTransforms how) {
  HuygensSlabSolver s(sc, comm, how);
  s.step();  // warm-up
  MPI_Barrier(comm);
  const double sent0 = g_sent, t0 = MPI_Wtime();
  for (int i = 0; i < steps; ++i) s.step();
  double dt = (MPI_Wtime() - t0) / steps;
  const double bytes = (g_sent - sent0) / steps;
  MPI_Allreduce(MPI_IN_PLACE, &dt, 1, MPI_DOUBLE, MPI_MAX, comm);
  return Timing{dt, bytes, s.bytes_sent_per_step(), s.round_trip_step_transforms() * s.grid().transposes()};
}

// mean wall time of one fftwf_mpi transpose of the N x N complex slab (the slowest rank)
double time_transpose(int n, MPI_Comm comm, int reps) {
  ptrdiff_t rows, r0, cols, c0;
  const ptrdiff_t alloc = fftwf_mpi_local_size_2d_transposed(n, n, comm, &rows, &r0, &cols, &c0);
  float* a = fftwf_alloc_real(2 * static_cast<size_t>(alloc));
  for (ptrdiff_t i = 0; i < 2 * alloc; ++i) a[i] = 0.0f;
  fftwf_plan p =
      fftwf_mpi_plan_many_transpose(n, n, 2, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, a, a, comm, FFTW_ESTIMATE);
  fftwf_execute(p);
  MPI_Barrier(comm);
  const double t0 = MPI_Wtime();
  for (int i = 0; i < reps; ++i) fftwf_execute(p);
  double dt = (MPI_Wtime() - t0) / reps;
  MPI_Allreduce(MPI_IN_PLACE, &dt, 1, MPI_DOUBLE, MPI_MAX, comm);
  fftwf_destroy_plan(p);
  fftwf_free(a);
  return dt;
}

// rank 0 measures alone (the others wait without spinning a core)
Timing time_one_rank(const HuygensScene& sc, int steps, int rank, SlabTransforms how) {
  Timing t;
  if (rank == 0) t = time_solver(sc, MPI_COMM_SELF, steps, how);
  MPI_Request req;
  MPI_Ibarrier(MPI_COMM_WORLD, &req);
  for (int done = 0; !done;) {
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    if (!done) usleep(2000);
  }
  return t;
}

void run_under_mpi(Context& ctx) {
  int init = 0, rank = 0, ranks = 1;
  MPI_Initialized(&init);
  if (!init) MPI_Init(nullptr, nullptr);  // finalised at exit by the atexit below
  if (!init) std::atexit([] { MPI_Finalize(); });
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (rank != 0 && !std::freopen("/dev/null", "w", stdout)) std::perror("freopen");  // rank 0 prints
  Table t({"N", "transforms", "ranks", "ms/step", "all-to-all ms", "local ms", "speedup", "transposes",
           "bytes/rank/step formula", "measured", "ratio"});
  const std::pair<SlabTransforms, const char*> forms[] = {{SlabTransforms::fftw_transposed, "FFTW transposed"},
                                                          {SlabTransforms::one_process_bits, "one-process bits"}};
  for (int n : ctx.quick ? std::vector<int>{256, 512} : std::vector<int>{1024, 2048})
    for (const auto& [how, name] : forms) {
      const HuygensScene sc = mpi_scene(n);
      const int steps = n >= 2048 ? 8 : n >= 1024 ? 16 : 32;
      const Timing one = time_one_rank(sc, steps, rank, how);
      const Timing many = time_solver(sc, MPI_COMM_WORLD, steps, how);
      const double tr = time_transpose(n, MPI_COMM_WORLD, 2 * steps) * many.transposes;
      if (rank != 0) continue;
      t.add({fmt("%d", n), name, "1", fmt("%.1f", 1e3 * one.step_s), "0", fmt("%.1f", 1e3 * one.step_s), "1.00",
             fmt("%d", one.transposes), "0", fmt("%.0f", one.bytes), "-"});
      t.add({fmt("%d", n), name, fmt("%d", ranks), fmt("%.1f", 1e3 * many.step_s), fmt("%.1f", 1e3 * tr),
             fmt("%.1f", 1e3 * (many.step_s - tr)), fmt("%.2f", one.step_s / many.step_s), fmt("%d", many.transposes),
             fmt("%.0f", many.formula), fmt("%.0f", many.bytes), fmt("%.4f", many.bytes / many.formula)});
      ctx.expect(std::abs(many.bytes / many.formula - 1.0) < 0.01,
                 fmt("mpi: measured bytes match the formula at N=%d (%s)", n, name));
    }
  if (rank == 0)
    ctx.report("mpi",
               fmt("Huygens slab solver, strong scaling 1 -> %d ranks (first order + cutoff, FFTW_ESTIMATE, "
                   "OpenMP threads per rank %d; formula T x 8 N^2/P (P-1)/P)",
                   ranks, omp_get_max_threads()),
               t);
}

std::string self_path() {
  char buf[4096];
  const ssize_t k = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  return k > 0 ? std::string(buf, static_cast<std::size_t>(k)) : "huygens-bench";
}

}  // namespace

void bench_mpi(Context& ctx) {
  if (std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_RANK")) return run_under_mpi(ctx);
  const std::string cmd = std::string("OMP_NUM_THREADS=1 mpirun --oversubscribe ") +
                          (geteuid() == 0 ? "--allow-run-as-root " : "") + "-np 2 " + self_path() + " mpi" +
                          (ctx.quick ? " --quick" : "");
  std::printf("\n== mpi: running under MPI ==\n%s\n", cmd.c_str());
  std::fflush(stdout);
  const int rc = std::system(cmd.c_str());
  ctx.expect(rc == 0, "mpi: the mpirun child succeeded");
}

}  // namespace huygens::bench

#else
namespace huygens::bench {
void bench_mpi(Context&) { std::printf("\n== mpi: not built (HUYGENS_MPI off or MPI/fftw3f_mpi not found) ==\n"); }
}  // namespace huygens::bench
#endif
