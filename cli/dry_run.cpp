// huygens run SCENE --dry-run [--ranks P] [--rank-memory GIB]: the memory a scene needs on each of P
// MPI ranks, from the solvers' own estimates (huygens/solvers/sizing.hpp) before anything is
// allocated, and the fewest ranks (powers of two) on which it fits a given memory per rank. Nothing runs.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "huygens/common/comm.hpp"
#include "huygens/common/memory.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/solvers/sizing.hpp"

namespace huygens {

int cmd_dry_run(const std::string& scene_file, int ranks, double rank_gib) {
  const Scene scene = open_scene(scene_file);
  const SceneSizing z = scene_sizing(scene);
  const std::uint64_t limit =
      rank_gib > 0 ? static_cast<std::uint64_t>(rank_gib * 1024.0 * 1024.0 * 1024.0) : available_memory();
  const auto memory = scene_rank_memory(scene);
  const MemoryEstimate m = memory(z.distributed ? std::min(ranks, z.max_ranks) : 1);
  if (!comm::root()) return kExitOk;
  std::printf("scene %s (solver %s%s%s): dry run, nothing allocated\n", scene_file.c_str(), z.solver.c_str(),
              z.grid.empty() ? "" : ", grid ", z.grid.c_str());
  const std::string where = rank_gib > 0 ? format_bytes(limit) + " per rank (--rank-memory)"
                                         : format_bytes(limit) + " (available here; --rank-memory GIB for other nodes)";
  if (!z.distributed) {
    std::printf("%s runs on one process (not distributed, docs/scale.md): %s; %s %s\n", z.solver.c_str(),
                m.summary().c_str(), m.total() <= limit ? "fits in" : "does not fit in", where.c_str());
    return kExitOk;
  }
  if (ranks > z.max_ranks)
    std::printf("%d ranks: refused (%s: at most %d ranks)\n", ranks, z.split_rule.c_str(), z.max_ranks);
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
