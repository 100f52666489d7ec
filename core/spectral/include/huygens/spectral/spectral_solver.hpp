#pragma once
// The "huygens" solver (docs/design.md 6, docs/huygens.md, docs/ocean.md): the scene's keys
// parsed into HuygensScene, and the adapter of the Huygens propagator (paper 004 section 3) to
// the solver interface. Stages of a full step, each made only when the scene names its feature:
//   propagate -> cutoff -> ships (eq. 2, spatial) -> spectrum -> drops -> wind (spectral)
//   -> height (first order, or eq. 3's second-order Stokes height, the wind sea superposed)
// Displayed frames j = 1 .. D-1 of D per step are cubic Hermite interpolants of eta and etadot
// between the last two full steps (time_interp.hpp; no transform). A still sea (no ships or
// wind, energy below a threshold) is zeroed and skipped until a drop (HuygensScene::still_skip).
// Every stage is written once against a GridLayout (grid_layout.hpp): the whole grid here, a row
// slab of an MPI rank in HuygensSlabSolver (slab_solver.hpp), which adds only the slab's layout.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "huygens/common/memory.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/spectral/propagator.hpp"
#include "huygens/spectral/ship_waves.hpp"
#include "huygens/spectral/stokes.hpp"
#include "huygens/spectral/wind.hpp"

namespace huygens {

struct SolverEntry;  // pipeline/solver_entry.hpp

/// An elevation released from rest (initial "gaussian" or a timed drop).
struct GaussianSource {
  /// Release time (unit: s); 0 for initial conditions.
  double t_s = 0;
  /// Centre (unit: m), in the full grid's frame.
  double x_m = 0, y_m = 0;
  /// Standard deviation of the Gaussian (unit: m).
  double sigma_m = 0.1;
  /// Peak elevation (unit: m); a drop of depth d is a depression, amplitude -d.
  double amplitude_m = 0.01;
};

/// A progressive plane wave present at t = 0.
struct PlaneWaveSource {
  /// Wavelength (unit: m).
  double wavelength_m = 1.0;
  /// Elevation amplitude (unit: m).
  double amplitude_m = 0.01;
  /// Direction of travel, counter-clockwise from +x (unit: degrees).
  double direction_deg = 0.0;
};

/// Everything a Huygens scene specifies.
struct HuygensScene {
  HuygensParams params;
  /// Displayed frames per full step (unit: 1); used by the renderer's time interpolation.
  int display_per_step = 1;
  std::vector<GaussianSource> initial_gaussians;
  std::vector<PlaneWaveSource> initial_plane_waves;
  /// Timed drops, sorted by time.
  std::vector<GaussianSource> drops;
  /// Second-order Stokes height (paper 004 eq. 3); false = first order.
  bool stokes = false;
  /// Ships (paper 004 eq. 2); empty = none (no patch, no plan, no stage).
  std::vector<Ship> ships;
  /// Ship patch side P (unit: cells): 2M, enlarged until the hull fits a quarter of it.
  int ship_patch = 0;
  /// Ambient JONSWAP wind sea; absent = calm.
  bool has_wind = false;
  WindParams wind;
  /// What the "render" block asks a viewer for (RenderInfo::request); the solver ignores it.
  RenderRequest render;
  /// Still-sea skip: without ships and wind, when energy_bound() of the propagator
  /// falls below the energy of a plane wave of amplitude still_amplitude_m over the grid,
  ///   E_still = 1/2 rho (g + sigma k1^2/rho) a^2 L^2,  k1 = 2 pi / L,
  /// the state is set to a flat sea at rest (spectrum and heights zeroed) and steps only
  /// advance time (counted by the "still" stage) until a drop (timed or cmd::Drop) wakes it.
  /// Not a scene key: tests switch it off to compare.
  bool still_skip = true;
  /// Amplitude of the still threshold's plane wave (unit: m).
  double still_amplitude_m = 1e-7;
  /// Full steps between two still checks (unit: steps); each check is one pass over Z^.
  int still_check_every = 16;
};

/// Parses and checks a "huygens" scene; every error is a SceneError naming the JSON path.
HuygensScene parse_huygens_scene(const Scene& scene, const RunOptions& options = {});
/// The bytes the solver of `scene` allocates (grids, tables, patches), before any is allocated;
/// parse_huygens_scene() refuses a scene that needs more than available_memory().
MemoryEstimate huygens_memory(const HuygensScene& scene);
/// meta.json of a Huygens scene (the global grid; HuygensSolver::meta and the slab solver).
nlohmann::json huygens_meta(const HuygensScene& scene, double transforms_per_step, double still_energy_j);
/// The "huygens" solver of a scene (make_solver's factory for this solver); with MPI initialised
/// and more than one rank in MPI_COMM_WORLD, the slab solver (slab_solver.hpp).
std::unique_ptr<Solver> make_huygens_solver(const Scene& scene, const RunOptions& options);

class HuygensSolver : public Solver {
 public:
  explicit HuygensSolver(const HuygensScene& scene);
  /// The same solver on a layout (a slab: collective; no commands, set_field or energy there).
  HuygensSolver(const HuygensScene& scene, GridLayout layout);
  void step() override;
  double time() const override { return prop_.time(); }
  std::int64_t steps() const override { return prop_.steps(); }
  /// (steps() + k) dt, as HuygensPropagator computes the time (exact).
  double time_bound(int k) const override { return static_cast<double>(prop_.steps() + k) * prop_.params().dt_s; }
  std::vector<OutputField> outputs() override;
  nlohmann::json meta() const override;
  const StageStats& stats() const override { return prop_.stats(); }
  std::span<const float> height() override {
    refresh_height();
    return eta_view();
  }
  std::size_t height_rows() const override { return static_cast<std::size_t>(vis_.count); }
  std::size_t height_cols() const override { return static_cast<std::size_t>(prop_.visible_size()); }
  std::span<const float> height_rate() override {
    refresh_height();
    return etadot_view();
  }
  int display_per_step() const override { return scene_.display_per_step; }
  MemoryEstimate memory() const override { return huygens_memory(scene_); }
  /// Frame j (1 <= j < D) of the last step: the cubic Hermite interpolant at s = j / D between
  /// the previous full step and the current one (needs steps() >= 1); j = 0 gives outputs().
  std::vector<OutputField> display_outputs(int j) override;
  /// N x N transforms per full step for the scene's features, on average: the propagation (2/K
  /// with the round trip every K steps, 0 without) + the height (1 first order, 3 second order).
  double transforms_per_step() const;
  /// Wall time inside the N x N transforms of the step (propagation and height; unit: ns), summed.
  std::uint64_t fft_ns() const { return prop_.fft_ns() + (stokes_ ? stokes_->fft_ns() : 0); }
  /// Supports cmd::Drop (a Gaussian depression released now; the height is recomputed lazily:
  /// by the next step, or by the next height()/height_rate()/outputs() before it) and
  /// cmd::ShipTarget (ShipWaves::steer at time(): the ship leaves its path and heads for the
  /// target with bounded acceleration and speed; refused for an unknown ship, a non-finite
  /// value or a target outside the grid) and cmd::Toggle (toggle()).
  bool apply(const Command& c) override;
  /// cmd::Toggle between steps: "stokes" switches the height between eq. 3's second order and
  /// first order (a StokesHeight of the other order is made on the first switch and kept);
  /// "wind" stops or resumes superposing the wind sea (it keeps advancing, so it comes back
  /// where it would be), refused when the scene has none (nothing is allocated for it).
  bool toggle(const cmd::Toggle& t);
  /// The visible region, depth, hulls, display rate, toggles ("stokes"; "wind" with a wind sea)
  /// and the scene's render block (whole grid).
  RenderInfo render_info() override;
  /// The ships' poses at time() (ShipWaves::pose), at most out.size().
  std::size_t ship_poses(std::span<ShipState> out) const override;
  /// The ship stage (null without ships), for tests.
  const ShipWaves* ship_waves() const { return ships_.get(); }

  /// True while the still-sea skip holds (see HuygensScene::still_skip).
  bool still() const { return still_; }
  /// Energy threshold of the still-sea skip (unit: J); 0 when the skip is off or impossible.
  double still_energy() const { return still_energy_; }
  /// Test hook (tests only; not reachable from a scene): HuygensPropagator::inject_nonfinite_for_test.
  void inject_nonfinite_for_test(const std::string& stage, std::int64_t step) {
    prop_.inject_nonfinite_for_test(stage, step);
  }

  HuygensPropagator& propagator() { return prop_; }
  const HuygensPropagator& propagator() const { return prop_; }
  const HuygensScene& scene() const { return scene_; }

 private:
  std::span<const float> eta_view() const { return stokes_ ? std::span<const float>(eta_.span()) : prop_.eta(); }
  std::span<const float> etadot_view() const {
    return stokes_ ? std::span<const float>(etadot_.span()) : prop_.etadot();
  }
  /// The height of the current state (prop_.height() or the StokesHeight stage).
  void make_height(std::int64_t step);
  /// Makes the height now if a command changed the state since it was last made.
  void refresh_height() {
    if (height_dirty_) {
      make_height(prop_.steps());
      height_dirty_ = false;
    }
  }
  /// A timed drop falls into the coming step (t, t + dt].
  bool drop_due() const;
  /// Before a step with D > 1: the current height becomes the previous full step (eta0_, etadot0_).
  void keep_previous_step();
  /// The ship stage: every ship's waves of [t0, t0 + dt] into the spatial field, checked.
  void add_ships(double t0);
  /// The drops stage: timed drops due in the coming step enter the spectrum with their phase.
  void release_drops();
  /// Construction: the sources of t <= 0, the stages, the still threshold, the first height.
  void initial_state();
  /// The end of a step's stages: one reduction of the non-finite records and the still-sea energy
  /// over the ranks (a slab), the first failing stage thrown, the still state entered when due.
  void settle_step(bool energy_due);

  HuygensScene scene_;
  HuygensPropagator prop_;
  std::unique_ptr<ShipWaves> ships_;             // only with ships
  std::unique_ptr<WindSea> wind_;                // only with wind
  VisibleRows vis_;                              // the visible rows this layout holds
  std::unique_ptr<StokesHeight> stokes_;         // with stokes, wind or on a slab (else the propagator's packed height)
  std::unique_ptr<StokesHeight> stokes_spare_;   // the other order, once "stokes" was toggled
  bool wind_on_ = true;                          // "wind" toggle: the sea is superposed
  AlignedBuffer<float> eta_, etadot_;            // StokesHeight outputs (only with stokes_)
  AlignedBuffer<float> eta0_, etadot0_, frame_;  // previous full step + one displayed frame (only D > 1)
  std::size_t next_drop_ = 0;
  int st_drops_ = -1, st_ships_ = -1, st_wind_ = -1, st_stokes_ = -1, st_still_ = -1;
  bool height_standin_ = false;      // a slab's first-order height stage stands in for the propagator's
  std::array<int, 8> step_order_{};  // stage indices in step order (StageChecks::settle)
  double still_energy_ = 0.0;
  bool still_ = false, height_dirty_ = false;
};

/// The registry entry (pipeline/solver_entry.hpp, solvers/registry.hpp): name "huygens", factory, sizing, memory, bench
/// scene.
SolverEntry huygens_solver_entry();

}  // namespace huygens
