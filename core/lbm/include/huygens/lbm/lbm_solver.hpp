#pragma once
// The "lbm" block of a scene (docs/design.md section 6; every key in docs/lbm.md) parsed into the
// parameters and initial fields of the D2Q9 shallow-water solver (shallow.hpp, paper 002 section 2),
// and the factory of its Solver. Positions are metres from the corner of cell (0, 0); cell (r, c)
// has its centre at ((c + 1/2) dx, (r + 1/2) dx). A dam's time step and transcritical refusal use
// its Stoker (1957) middle state (stoker.hpp). Errors are SceneError naming the JSON path; a
// parameter lbm_check() refuses is named by the scene key that set it.
#include <memory>
#include <vector>

#include "huygens/common/memory.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/lbm/shallow.hpp"
#include "huygens/pipeline/render_info.hpp"

namespace huygens {

struct SolverEntry;  // pipeline/solver_entry.hpp

class Solver;
struct RunOptions;

/// Everything an "lbm" scene specifies, accepted by lbm_check().
struct LbmScene {
  /// Lattice parameters, the time step resolved from dt_s or cfl (units in LbmParams).
  LbmParams params;
  /// Initial bed, depth, velocity and obstacle cells, row-major (rows, cols) (units in LbmFields).
  LbmFields fields;
  /// What the scene's "render" block asks a viewer for (RenderInfo::request).
  RenderRequest render;
  /// The obstacles as shapes for a viewer: cylinders (circles) and boxes (rects) through the
  /// whole water column (z from -infinity to +infinity; unit: m).
  std::vector<RenderObstacle> obstacles;
};

/// Parses the scene's "lbm" block and checks it with lbm_check(); throws SceneError naming the
/// JSON path.
LbmScene parse_lbm_scene(const Scene& scene);
/// The bytes the solver of a grid allocates on the largest of `ranks` MPI ranks (lattice, scene
/// and output fields, halo buffers), before any is allocated; parse_lbm_scene() refuses a scene
/// that needs more than available_memory() on a rank of this run. `carry`: the scene starts with a
/// dry cell, so the solver also keeps its mass carry plane (lbm_starts_dry, 4 B per lattice cell).
MemoryEstimate lbm_memory(const LbmParams& params, int ranks = 1, bool carry = false);
/// True when an "lbm" scene starts with a dry cell (lbm_starts_dry: its solver keeps the mass
/// carry plane). The scene is parsed without the memory check when its fields take at most half
/// of available_memory(); a larger one is not built and counts as starting dry (an upper bound).
bool lbm_scene_may_start_dry(const Scene& scene);
/// The estimate of an "lbm" scene on `ranks` ranks from its grid block (huygens run --dry-run:
/// nothing is refused), with the carry plane when `carry` (lbm_scene_may_start_dry). Throws
/// SceneError for a bad grid block.
MemoryEstimate lbm_scene_memory(const Scene& scene, int ranks, bool carry);
/// The Solver of a parsed scene.
std::unique_ptr<Solver> make_lbm_solver(const LbmScene& scene);
/// parse_lbm_scene() then make_lbm_solver() (this solver uses no RunOptions).
std::unique_ptr<Solver> make_lbm_solver(const Scene& scene, const RunOptions& options);

/// The registry entry (pipeline/solver_entry.hpp, solvers/registry.hpp): name "lbm", factory, sizing, memory, bench
/// scene.
SolverEntry lbm_solver_entry();

}  // namespace huygens
