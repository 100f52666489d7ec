#pragma once
// The "huygens" solver on MPI ranks (issue 17, docs/scale.md "Huygens on slabs"): HuygensSolver
// (spectral_solver.hpp; paper 004 section 3) on the row slab of this rank. Every stage is the
// one-process stage run on the slab's GridLayout (grid_layout.hpp); this file adds only the layout:
// FFTW's MPI transforms (slab_fft.hpp) behind GridTransform and one MPI_Allreduce per step behind
// GridLayout::sum_over_ranks (the non-finite records and the still-sea energy, stage_checks.hpp).
// The spectrum is kept transposed (rank p owns kx rows), so each transform pays one all-to-all
// transpose; with FFTW_ESTIMATE plans (N >= 256) the transforms run in Fft2D's row-column form
// instead, spectrum in the normal layout, and give the one-process spectrum bit for bit. The height
// couples k and -k, on different ranks: StokesHeight's split form (stokes_split.cpp), 2 transforms
// at first order, 4 at second.
#ifdef HUYGENS_HAVE_MPI
#include <mpi.h>

#include "huygens/common/slab_fft.hpp"
#include "huygens/spectral/spectral_solver.hpp"

namespace huygens {

/// Per-rank bytes of the slab solver of `scene` on `ranks` ranks (even split; formula, nothing allocated).
MemoryEstimate huygens_slab_memory(const HuygensScene& scene, int ranks);

/// How the slab solver transforms (slab_fft.hpp):
/// - one_process_bits: Fft2D's row-column form on the slabs, spectrum in the normal layout (two
///   all-to-all transposes per transform): the one-process solver's spectrum bit for bit, and its
///   height to the height's rounding (docs/scale.md). Needs FFTW_ESTIMATE plans and N >= 256.
/// - fftw_transposed: FFTW's MPI plans, spectrum transposed (one transpose per transform; the
///   fastest); fftw_normal: FFTW's MPI plans, normal layout.
/// - automatic: one_process_bits where it applies (`huygens run --fast-plans`, the tests), else
///   fftw_transposed.
enum class SlabTransforms { automatic, one_process_bits, fftw_transposed, fftw_normal };

/// The split of a scene's grid over the ranks of comm (collective), for `how`.
SlabGrid huygens_slab_grid(const HuygensParams& p, MPI_Comm comm, SlabTransforms how);
/// The GridLayout of a slab: SlabFft transforms of `effort`, sums by MPI_Allreduce on comm.
GridLayout slab_layout(const SlabGrid& g, MPI_Comm comm, PlanEffort effort);

namespace detail {
/// The slab, made before the solver it lays out (a base listed first).
struct SlabPart {
  SlabGrid slab_grid;
  MPI_Comm slab_comm;
};
}  // namespace detail

class HuygensSlabSolver : private detail::SlabPart, public HuygensSolver {
 public:
  /// Collective on comm: plans, tables and the initial state of the rows this rank owns.
  HuygensSlabSolver(const HuygensScene& scene, MPI_Comm comm, SlabTransforms how = SlabTransforms::automatic);

  /// The global grid (as HuygensSolver::meta) plus "mpi": ranks, layout, transposes per step.
  nlohmann::json meta() const override;
  MemoryEstimate memory() const override { return huygens_slab_memory(scene(), slab_grid.ranks); }
  /// The render description of the rows held (no commands, toggles or far sea on a slab).
  RenderInfo render_info() override { return Solver::render_info(); }

  const SlabGrid& grid() const { return slab_grid; }
  /// N x N transforms of a full step that takes the spatial round trip (each one all-to-all
  /// transpose or two); steps between two round trips (every K = round_trip_every) take 2 fewer.
  int round_trip_step_transforms() const;
  /// Bytes this rank sends in the transposes of a full step (unit: bytes, on average):
  /// transforms_per_step() x transposes per transform x slab_transpose_bytes() = T t 8 N^2/P (P-1)/P
  /// for an even split (the step's one reduction adds 17 doubles).
  double bytes_sent_per_step() const;
};

}  // namespace huygens
#endif
