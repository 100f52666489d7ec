#pragma once
// The interface every solver (Huygens, SPH, LBM) offers to the programs, the runner and
// the renderer: step, time, output fields, per-stage statistics. Solvers are built from
// a scene by make_solver() (solvers/registry.hpp); each solver's factory lives with the solver.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "huygens/common/finite.hpp"
#include "huygens/common/memory.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/common/stats.hpp"
#include "huygens/pipeline/command.hpp"
#include "huygens/pipeline/frame.hpp"
#include "huygens/pipeline/render_info.hpp"

namespace huygens {

/// A named output array for dumps: `name` is the file prefix (eta, h, u, pos), `shape`
/// its C-order shape, `data` a view valid until the next step. On MPI ranks (comm.hpp) a rank
/// holds rows [row0, row0 + shape[0]) of the field's `global_shape` (the dump writes them at
/// their place in one file); empty `global_shape` means the rank holds it all (one process).
/// A grid field has shape (rows, cols) or (rows, cols, k) on the visible grid; a `per_particle`
/// field has shape (n) or (n, k), row i the particle of id i ("pos" holds their positions).
struct OutputField {
  std::string name;
  std::vector<std::size_t> shape;
  std::span<const float> data;
  std::vector<std::size_t> global_shape = {};
  std::size_t row0 = 0;
  bool per_particle = false;

  /// The shape of the whole field (global_shape, or shape when it is empty).
  const std::vector<std::size_t>& full_shape() const { return global_shape.empty() ? shape : global_shape; }
};

/// Options that come from the command line rather than the scene.
struct RunOptions {
  /// FFTW planning effort: false = FFTW_ESTIMATE (fast start), true = FFTW_MEASURE.
  bool measure_plans = true;
};

class Solver {
 public:
  virtual ~Solver() = default;
  /// Advances one full step. Throws NonFiniteError naming the stage on a non-finite value.
  virtual void step() = 0;
  /// Simulated time (unit: s).
  virtual double time() const = 0;
  /// Full steps taken so far.
  virtual std::int64_t steps() const = 0;
  /// An upper bound of time() after `steps` more steps (unit: s): the exact time when the step is
  /// fixed (computed as time() is), t + steps dt_max when it is adaptive but bounded (rounding up
  /// is monotone, so the sum bounds the sum of the smaller steps), +infinity when the solver cannot
  /// tell (the default). The manual-clock runner does not publish a frame it knows will not be shown.
  virtual double time_bound(int steps) const {
    (void)steps;
    return std::numeric_limits<double>::infinity();
  }
  /// The fields a dump writes for the current state (may allocate: not called inside a step).
  virtual std::vector<OutputField> outputs() = 0;
  /// Grid, spacing, time step and visible region for meta.json.
  virtual nlohmann::json meta() const = 0;
  virtual const StageStats& stats() const = 0;
  /// Heightfield of the visible region (rows = y, cols = x; unit: m) for the renderer.
  virtual std::span<const float> height() = 0;
  virtual std::size_t height_rows() const = 0;
  virtual std::size_t height_cols() const = 0;
  /// Time derivative of height() (unit: m/s), same shape, for the renderer's cubic time
  /// interpolation; empty when the solver has none (the default).
  virtual std::span<const float> height_rate() { return {}; }
  /// A particle solver's particles for the viewer's particle view: x, y, z (unit: m) and speed
  /// |v| (unit: m/s), 4 floats per particle, in storage the solver sized at construction (filled
  /// on each call, valid until the next step; the same size every call). Empty for grid solvers.
  virtual std::span<const float> particles() { return {}; }
  /// Depth-averaged velocity (u_x, u_y) on height()'s grid, interleaved (rows, cols, 2) (unit: m/s),
  /// in storage the solver sized at construction (filled on each call, valid until the next step);
  /// empty when the solver has none (the default). The runner calls it for every frame: no allocation.
  virtual std::span<const float> velocity() { return {}; }
  /// Applies a UI command (drop, ship target, parameter, feature) between steps, never inside
  /// step(); returns false when the solver does not support it (the default: none).
  virtual bool apply(const Command&) { return false; }
  /// Fills `out` with the poses of the solver's ships at time() (where they are, including a
  /// ship steered by cmd::ShipTarget) and returns how many it wrote (at most out.size()); the
  /// default has no ships. Called by the runner for every frame: no allocation.
  virtual std::size_t ship_poses(std::span<ShipState> out) const {
    (void)out;
    return 0;
  }
  /// The bytes the solver allocated, by part, as estimated from the scene before allocating (the
  /// estimate the scene was checked against; memory.hpp).
  virtual MemoryEstimate memory() const { return {}; }
  /// Displayed frames per full step D (unit: 1); 1 when the solver does not interpolate.
  virtual int display_per_step() const { return 1; }
  /// What a viewer needs besides the frames (render_info.hpp), from the parsed scene. May make the
  /// height (rest level): call it on the owning thread before the first step. The default places
  /// height() at the origin with 1 m spacing and offers no toggle.
  virtual RenderInfo render_info() {
    RenderInfo r;
    r.grid.rows = height_rows();
    r.grid.cols = height_cols();
    r.display_per_step = display_per_step();
    return r;
  }
  /// The fields of displayed frame j of D of the last full step (time (steps() - 1 + j/D) dt for
  /// j >= 1, interpolated; j = 0 is outputs()). May allocate: not called inside a step.
  virtual std::vector<OutputField> display_outputs(int j) { return j == 0 ? outputs() : std::vector<OutputField>{}; }
};

// make_solver() (huygens/solvers/registry.hpp) builds the solver a scene names; each solver's
// factory is in its adapter (huygens/<solver>/<solver>_solver.hpp).

}  // namespace huygens
