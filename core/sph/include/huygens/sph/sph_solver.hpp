#pragma once
// The "sph" block of a scene (docs/design.md section 6; every key in docs/sph.md) parsed into
// SphParams and the heightfield parameters of paper 000 eq. 5-6, and the factory of its Solver.
// Errors are SceneError naming the JSON path; an old key (viscosity_m2ps) names its new name.
// Example:
//   { "solver": "sph",
//     "sph": { "spacing_m": 0.01, "support_factor": 2.0, "rest_density_kgpm3": 1000,
//              "viscosity_m2s": 1e-6, "sound_speed_mps": null, "gravity_mps2": [0, 0, -9.81],
//              "container_m": [0.2, 0.2, 0.2],
//              "fluid": [ { "min_m": [0, 0, 0], "max_m": [0.2, 0.2, 0.075] } ],
//              "obstacles": [ { "type": "box", "min_m": [..], "max_m": [..] },
//                             { "type": "cylinder", "centre_m": [x, y], "radius_m": r, "z0_m": 0, "z1_m": z } ],
//              "time": { "cfl": 0.15, "force": 0.18, "viscous": 0.03, "dt_max_s": 0.001 },
//              "surface": { "cell_m": 0.01, "radius_factor": 2.0, "iso": null } } }
#include <memory>

#include "huygens/common/memory.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/render_info.hpp"
#include "huygens/sph/params.hpp"
#include "huygens/sph/surface.hpp"

namespace huygens {

struct SolverEntry;  // pipeline/solver_entry.hpp

class Solver;
struct RunOptions;

/// Everything an "sph" scene specifies.
struct SphScene {
  /// The particle system (units in SphParams).
  SphParams params;
  /// Heightfield extraction; iso defaults to sph_flat_iso(radius_m, spacing_m).
  SphSurfaceParams surface;
  /// The scene's optional "render" block (render_info.hpp), as the other solvers' scenes have it.
  RenderRequest render;
};

/// Parses and checks the scene's "sph" block (throws SceneError naming the JSON path).
SphScene parse_sph_scene(const Scene& scene);
/// The Solver of a parsed scene (throws std::invalid_argument for an unusable set-up).
/// The bytes the solver of `scene` allocates (particles, neighbour grid, heightfield), before any
/// is allocated; parse_sph_scene() refuses a scene that needs more than available_memory().
MemoryEstimate sph_memory(const SphScene& scene);
std::unique_ptr<Solver> make_sph_solver(const SphScene& scene);
/// parse_sph_scene() then make_sph_solver() (this solver uses no RunOptions); an unusable set-up
/// is a SceneError at "$.sph".
std::unique_ptr<Solver> make_sph_solver(const Scene& scene, const RunOptions& options);

/// The registry entry (pipeline/solver_entry.hpp, solvers/registry.hpp): name "sph", factory, sizing, memory, bench
/// scene.
SolverEntry sph_solver_entry();

}  // namespace huygens
