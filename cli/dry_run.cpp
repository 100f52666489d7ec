// huygens run SCENE --dry-run [--ranks P] [--rank-memory GIB]: the memory a scene needs on each of P
// MPI ranks, from the solvers' own estimates (memory.hpp) before anything is allocated, and the
// fewest ranks (powers of two) on which it fits a given memory per rank. Nothing runs.
//   LBM: lbm_memory(params, P) (its largest rank: ceil(rows / P) rows, halos, the whole scene
//        fields every rank parses; the mass carry plane when the scene starts dry).
//   Huygens: the slab solver's huygens_slab_memory(scene, P) (its slabs of
//        fftwf_mpi_local_size_2d); P = 1 the one-process solver's huygens_memory.
//   SPH: not distributed (docs/scale.md): one process holds it all, whatever P.
#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include "commands.hpp"
#include "huygens/common/comm.hpp"
#include "huygens/common/memory.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/huygens/slab_solver.hpp"
#include "huygens/huygens/solver.hpp"
#include "huygens/lbm/solver.hpp"
#include "huygens/sph/solver.hpp"

namespace huygens {

namespace {

// The estimate of the largest rank of `ranks`: the slab solver's own (what a run under mpirun
// checks) when MPI is built, else each part scaled to ceil(N / P) rows.
MemoryEstimate huygens_rank_memory(const HuygensScene& s, int ranks) {
  const MemoryEstimate whole = huygens_memory(s);
#ifdef HUYGENS_HAVE_MPI
  if (ranks > 1) return huygens_slab_memory(s, ranks);
#endif
  const std::uint64_t n = static_cast<std::uint64_t>(s.params.n);
  const std::uint64_t rows = (n + static_cast<std::uint64_t>(ranks) - 1) / static_cast<std::uint64_t>(ranks);
  MemoryEstimate m;
  m.size_key = whole.size_key;
  for (const MemoryEstimate::Part& part : whole.parts)
    m.add(part.name, part.name == "ship patches" ? part.bytes : (part.bytes * rows + n - 1) / n, part.key);
  return m;
}

struct Sizing {
  std::string solver, grid;
  int max_ranks = 1 << 16;  // LBM: 3 rows per rank at least
  bool distributed = true;
};

Sizing sizing(const Scene& scene) {
  Sizing z{scene.solver, "", 1 << 16, scene.solver != "sph"};
  const JsonIn root = scene.root();
  if (scene.solver == "lbm") {
    const JsonIn g = root.object("lbm").object("grid");
    const long long rows = g.integer("rows", 1, 16384), cols = g.integer("cols", 1, 16384);
    z.grid = std::to_string(rows) + " rows x " + std::to_string(cols) + " cols";
    z.max_ranks = static_cast<int>(std::max(1LL, rows / 3));
  } else if (scene.solver == "huygens") {
    const long long n = root.object("grid").integer("n", 16, 1 << 20);
    z.grid = std::to_string(n) + " x " + std::to_string(n);
    z.max_ranks = static_cast<int>(n);
  }
  return z;
}

// The estimate on P ranks as a function of P; the scene is parsed once.
std::function<MemoryEstimate(int)> rank_memory(const Scene& scene) {
  if (scene.solver == "lbm") {
    const bool carry = lbm_scene_may_start_dry(scene);
    return [&scene, carry](int p) { return lbm_scene_memory(scene, p, carry); };
  }
  const MemoryCheckOff sizing_only;  // parsed to be sized, not run
  if (scene.solver == "huygens") {
    auto hs = std::make_shared<const HuygensScene>(parse_huygens_scene(scene));
    return [hs](int p) { return huygens_rank_memory(*hs, p); };
  }
  if (scene.solver == "sph") {
    const MemoryEstimate m = sph_memory(parse_sph_scene(scene));
    return [m](int) { return m; };
  }
  throw SceneError("$.solver", "unknown solver \"" + scene.solver + "\"");
}

}  // namespace

int cmd_dry_run(const std::string& scene_file, int ranks, double rank_gib) {
  const Scene scene = open_scene(scene_file);
  const Sizing z = sizing(scene);
  const std::uint64_t limit =
      rank_gib > 0 ? static_cast<std::uint64_t>(rank_gib * 1024.0 * 1024.0 * 1024.0) : available_memory();
  const auto memory = rank_memory(scene);
  const MemoryEstimate m = memory(z.distributed ? std::min(ranks, z.max_ranks) : 1);
  if (!comm::root()) return kExitOk;
  std::printf("scene %s (solver %s%s%s): dry run, nothing allocated\n", scene_file.c_str(), z.solver.c_str(),
              z.grid.empty() ? "" : ", grid ", z.grid.c_str());
  const std::string where = rank_gib > 0 ? format_bytes(limit) + " per rank (--rank-memory)"
                                         : format_bytes(limit) + " (available here; --rank-memory GIB for other nodes)";
  if (!z.distributed) {
    std::printf("sph runs on one process (not distributed, docs/scale.md): %s; %s %s\n", m.summary().c_str(),
                m.total() <= limit ? "fits in" : "does not fit in", where.c_str());
    return kExitOk;
  }
  if (ranks > z.max_ranks)
    std::printf("%d ranks: refused (each rank needs 3 rows at least: at most %d ranks)\n", ranks, z.max_ranks);
  else
    std::printf("%d rank%s: %s per rank\n", ranks, ranks == 1 ? "" : "s", m.summary().c_str());
  Table t({"ranks", "per rank", "all ranks", rank_gib > 0 ? "fits --rank-memory" : "fits here"});
  int first_fit = 0;
  for (int p = 1; p <= z.max_ranks && p <= 256; p *= 2) {
    const std::uint64_t b = memory(p).total();
    if (!first_fit && b <= limit) first_fit = p;
    t.add({std::to_string(p), format_bytes(b), format_bytes(b * static_cast<std::uint64_t>(p)),
           b <= limit ? "yes" : "no"});
  }
  std::printf("%s", t.text().c_str());
  if (first_fit)
    std::printf("fits in %s from %d rank%s\n", where.c_str(), first_fit, first_fit == 1 ? "" : "s");
  else
    std::printf("does not fit in %s on up to 256 ranks\n", where.c_str());
  return kExitOk;
}

}  // namespace huygens
