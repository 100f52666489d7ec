// A scene sized for P MPI ranks (huygens/pipeline/sizing.hpp): each solver's own memory estimate.
#include "huygens/pipeline/sizing.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>

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

}  // namespace

SceneSizing scene_sizing(const Scene& scene) {
  SceneSizing z{scene.solver, "", 1 << 16, scene.solver != "sph"};
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

std::function<MemoryEstimate(int)> scene_rank_memory(const Scene& scene) {
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

}  // namespace huygens
