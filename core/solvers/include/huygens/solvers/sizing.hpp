#pragma once
// A scene sized for P MPI ranks before anything is allocated (docs/scale.md): the memory of the largest
// rank from the solver's own estimate (memory.hpp), and how far the scene can be split. Shared by
// `huygens run --dry-run` (cli/dry_run.cpp) and the Python package's memory_estimate(); each solver
// gives both through its registry entry (pipeline/solver_entry.hpp, registry.hpp):
//   LBM: lbm_memory(params, P) (its largest rank: ceil(rows / P) rows, halos, the whole scene
//        fields every rank parses; the mass carry plane when the scene starts dry).
//   Huygens: the slab solver's huygens_slab_memory(scene, P) (its slabs of
//        fftwf_mpi_local_size_2d) in an MPI build, else each part scaled to ceil(N / P) rows;
//        P = 1 the one-process solver's huygens_memory.
//   SPH: not distributed (docs/scale.md): one process holds it all, whatever P.
#include <functional>
#include <string>

#include "huygens/common/memory.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver_entry.hpp"

namespace huygens {

/// The sizing of a parsed scene. Throws SceneError (JSON path) for a bad grid.
SceneSizing scene_sizing(const Scene& scene);

/// The estimate of the largest of P ranks as a function of P (P >= 1; SPH: the same for every P). The
/// scene is parsed once, here, with the memory check off (nothing is allocated); `scene` must outlive
/// the function. Throws SceneError for a bad scene.
std::function<MemoryEstimate(int)> scene_rank_memory(const Scene& scene);

}  // namespace huygens
