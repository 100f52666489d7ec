#pragma once
// The Huygens propagator (paper 004 section 3, eq. 1; docs/design.md 3.2, docs/huygens.md).
// State: the spectrum Z^ of the complex wave field Z (velocity potential, m^2/s) on an N x N
// periodic grid of side L (m). One full step of dt (s), three N x N transforms (the round trip of
// propagate/spectrum only every K = round_trip_every steps, the steps in between rotate Z^ in place):
//   propagate  Z = IFFT[Z^ exp(-i omega(k) dt)] / N^2    (eq. 1: exact in phase, stable for any dt)
//   cutoff     Z(p, q) *= h(p) h(q),  h = 1 - (d/M - 1)^2 at d = min(p, N-1-p) < M cells, else 1
//   spectrum   Z^ = FFT[Z]                                (spatial sources such as ships go before)
//   sources    Z^ += -i omega/k E^ e^{-i omega tau}       (an elevation E (m) released tau (s) ago)
//   height     eta + i etadot = IFFT[i (alpha Z^(k) + beta conj Z^(-k))]   (m, m/s),
//              alpha = (k/omega + k)/2, beta = (k - k/omega)/2
// Without cutoff and spatial sources a step is the rotation and the height: one transform.
// exp(-i omega dt) is an exact-determinant lifting rotation of three shears, so |Z^| cannot
// drift in float (docs/huygens.md). Per-mode tables depend on |k| only: one quadrant each.
// Every stage runs on a GridLayout (grid_layout.hpp): the whole grid on one process, a row slab
// on an MPI rank (slab_solver.hpp); the packed height reads Z^(-k) and needs the whole grid.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "huygens/common/dispersion.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/common/stats.hpp"
#include "huygens/spectral/grid_layout.hpp"
#include "huygens/spectral/rotation.hpp"
#include "huygens/spectral/stage_checks.hpp"

namespace huygens {

/// Absorbing margin profile.
enum class Absorber {
  /// Paper 004's quadratic cutoff h(p) h(q), applied once per step.
  paper_quadratic,
  /// No cutoff at all: the grid is periodic (validation, energy conservation).
  off,
};

/// Parameters of the propagator (fixed at construction).
struct HuygensParams {
  /// Cells per side N (unit: cells); a power of two >= 16.
  int n = 512;
  /// Side length L of the full grid (unit: m).
  double length_m = 15.0;
  /// Width M of the absorbing margin on each side (unit: cells); 2M < N. The visible region is (N-2M)^2.
  int margin = 64;
  /// Time step of one full step (unit: s); any value > 0 is stable.
  double dt_s = 1.0 / 60.0;
  /// Water properties (dispersion).
  Water water;
  /// Margin absorber (paper_quadratic or off).
  Absorber absorber = Absorber::paper_quadratic;
  /// Time constant tau of the cutoff (unit: s). 0: paper 004's h(p) h(q) once per step. tau > 0:
  /// (h(p) h(q))^(dt/tau) per step, i.e. one paper cutoff per tau seconds whatever dt.
  double cutoff_time_s = 0.0;
  /// The spatial round trip (IFFT, cutoff, spatial sources, FFT) every K = this many steps (unit:
  /// steps, 1 to 64); the steps in between are the spectral rotation alone. The cutoff is then
  /// applied as (h(p) h(q))^(K dt / tau) (tau = dt with cutoff_time_s = 0): the same absorption per
  /// unit time. Spatial sources added k steps before the round trip must carry the phase of the
  /// k steps still ahead (ShipWaves::gather's delay, steps_to_round_trip()). 1 = every step.
  int round_trip_every = 1;
  /// How exp(-i omega dt) is applied (lifting keeps |Z^| exactly bounded in float).
  Rotation rotation = Rotation::lifting;
  /// FFTW planning effort (estimate for tests, measure for runs).
  PlanEffort effort = PlanEffort::measure;
  /// Check every stage's output for non-finite values every this many steps (unit: steps);
  /// the visible height is checked every step. 0 disables the per-stage checks.
  int check_every = 16;
  /// Allocate the tables for elevation sources added during a run (drops). Construction-time
  /// sources allocate them on demand.
  bool runtime_sources = false;
  /// Take the spatial round trip (IFFT, spatial stages, FFT) even with the absorber off; needed
  /// when spatial sources (ships) are added. Without cutoff and spatial sources the step is the
  /// spectral rotation alone plus the height transform (1 transform per step instead of 3).
  bool spatial = false;
  /// The caller makes the height from spectrum_view() (e.g. the StokesHeight stage): height(),
  /// eta() and etadot() are unavailable, and the packed-height plan, tables, visible buffers and
  /// "height" stage are not made (transforms_per_step() counts the propagation only).
  bool external_height = false;
};

/// Human-readable reason why `p` cannot be used, or empty when it can.
std::string huygens_params_error(const HuygensParams& p);

/// One axis of a Gaussian elevation's spectrum (separable): f[i] = scale exp(-k_i^2 sigma^2 / 2)
/// e^{-i k_i x0} for the N FFT wavenumbers k_i of a side L (m); at the Nyquist index only the real
/// part, so that the spectrum of the real elevation stays Hermitian.
void gaussian_axis_factors(cfloat* f, int n, double length_m, double x0_m, double sigma_m, double scale);

/// One spectrum row of a Gaussian source: E^ = row x col[c] (the separable factors), Z^ += -i (omega/k)
/// E^, turned by exp(-i omega age) when it was released age_s ago (age_s != 0). w_over_k and om:
/// the row's omega/k and omega (N values; unit: m/s, rad/s).
void add_gaussian_row(cfloat row, const cfloat* col, const float* w_over_k, const float* om, double age_s, cfloat* s,
                      int n);

class HuygensPropagator {
 public:
  /// Allocates every buffer and table and makes the three FFTW plans, on the whole grid. Throws
  /// std::invalid_argument with huygens_params_error() for bad parameters.
  explicit HuygensPropagator(const HuygensParams& p);
  /// The same on a layout (a slab needs external_height; its plans are collective).
  HuygensPropagator(const HuygensParams& p, GridLayout layout);
  ~HuygensPropagator();
  HuygensPropagator(const HuygensPropagator&) = delete;
  HuygensPropagator& operator=(const HuygensPropagator&) = delete;

  const HuygensParams& params() const { return p_; }
  const GridLayout& layout() const { return g_; }
  int n() const { return p_.n; }
  double dx() const { return p_.length_m / p_.n; }
  /// Wavenumber components of FFT index i along one axis (unit: rad/m), FFTW order.
  double wavenumber(int i) const;

  // ---- sources --------------------------------------------------------------------------------
  /// Adds an elevation E(x) = amplitude exp(-|x - x0|^2 / (2 sigma^2)) released from rest `age_s`
  /// seconds ago: Z^ += -i omega/k E^ e^{-i omega age} with the analytic periodised spectrum
  /// E^(k) = 2 pi sigma^2 amplitude / dx^2 exp(-k^2 sigma^2 / 2) e^{-i k.x0} (unit of x0: m).
  /// Allocates the source tables on first use unless reserve_sources() (or runtime_sources) ran
  /// before: inside a step, call reserve_sources() at construction.
  void add_gaussian(double x_m, double y_m, double sigma_m, double amplitude_m, double age_s = 0.0);
  /// Adds a progressive plane wave whose elevation is amplitude cos(k.x) at this time,
  /// travelling along direction_deg (0 = +x, 90 = +y): Z = -i omega(k)/k amplitude e^{i k.x}.
  /// Exactly one Fourier mode when the wave vector is on the grid. Uses one transform (and on a
  /// slab a scratch buffer): not for use inside a step.
  void add_plane_wave(double wavelength_m, double amplitude_m, double direction_deg);
  /// Allocates and fills the source tables (-omega/k and omega, 2 N^2 floats) if not yet done;
  /// returns their size (unit: bytes). Runs between steps, never inside one.
  std::uint64_t reserve_sources();
  /// Size of the source tables allocated so far (unit: bytes; 0 before the first source).
  std::uint64_t source_bytes() const { return (src_.size() + omega_.size()) * sizeof(float); }
  /// Sets a flat sea at rest: Z^ = Z = 0 and the heights 0 (time and steps unchanged).
  void clear();
  /// Replaces the state by the spatial field z (N*N values, rows = y) and recomputes the height
  /// (whole grid only).
  void set_field(std::span<const cfloat> z);

  // ---- the step ------------------------------------------------------------------------------
  /// One full step: propagate, cutoff, spectrum, height; time advances by dt.
  void step();
  // The same step, stage by stage, for pipelines that insert stages (ships before spectrum(),
  // spectral sources between spectrum() and height()). Call them in this order, then end_step().
  void propagate();
  void cutoff();
  void spectrum();
  void height();
  void end_step();

  // ---- state and outputs ---------------------------------------------------------------------
  /// Simulated time (unit: s) and full steps taken.
  double time() const { return t_; }
  std::int64_t steps() const { return steps_; }
  /// The spectrum Z^ (FFTW order, unnormalised) at time(): the layout's spectrum rows, N values each.
  std::span<const cfloat> spectrum_view() const { return {s_.data(), g_.spectrum_size()}; }
  std::span<cfloat> spectrum_data() { return {s_.data(), g_.spectrum_size()}; }
  /// The spatial field Z (the layout's rows); valid between cutoff() and spectrum() (spatial
  /// sources add here).
  std::span<cfloat> field() { return {z_.data(), g_.field_size()}; }
  /// First-order elevation and its rate on the visible region, (N-2M)^2 row-major (unit: m, m/s).
  std::span<const float> eta() const { return eta_.span(); }
  std::span<const float> etadot() const { return etadot_.span(); }
  /// The full-grid packed field eta + i etadot after height() (N*N values).
  std::span<const cfloat> packed_height() const { return h_.span(); }
  int visible_size() const { return p_.n - 2 * p_.margin; }
  /// Linear wave energy of the real field in double (unit: J):
  ///   E = rho/2 L^2/N^4 sum_k (g + sigma k^2 / rho) (|H_k|^2 + |D_k|^2 / omega_k^2)
  /// with H, D the spectra of eta and etadot (Hermitian parts of i k/omega Z^ and k Z^). Whole grid only.
  double energy() const;
  /// Cheap upper bound of energy() (one vectorised pass, no per-mode tables; unit: J). With
  /// energy() = rho/2 L^2/N^4 sum_k (k / tanh(k h)) |Z^_k|^2 (the dispersion relation folded
  /// in: (g + sigma k^2/rho) k^2/omega^2 = k/tanh(kh)) and x/tanh(x) <= 1 + x:
  ///   energy() <= rho/2 L^2/N^4 (k_max + 1/h) sum_k |Z^_k|^2,  k_max = sqrt(2) pi N / L
  /// (1/h = 0 in deep water). The k = 0 mode, which carries no energy, is included.
  double energy_bound() const { return energy_bound_of(spectrum_norm2()); }
  /// sum_k |Z^_k|^2 over this layout's spectrum rows (double; a slab sums it over the ranks).
  double spectrum_norm2() const;
  /// The bound above for a sum_k |Z^_k|^2 over the whole grid (unit: J).
  double energy_bound_of(double norm2) const;
  /// A non-finite height: the stage to blame, from the buffers that still hold each stage's
  /// output (Z after propagate/cutoff on a round trip, Z^ after spectrum or propagate); -1: the
  /// height itself.
  int height_blame() const;
  /// Non-finite checks of the step (deferred on a slab).
  StageChecks& checks() { return checks_; }
  StageStats& stats() { return stats_; }
  const StageStats& stats() const { return stats_; }
  /// True when the steps go through the spatial domain (cutoff on or `spatial` set), every
  /// round_trip_every() steps.
  bool spatial_round_trip() const { return spatial_; }
  /// K: the round trip runs at the end of steps K, 2K, 3K, ... (1-based).
  int round_trip_every() const { return every_; }
  /// Between propagate() and spectrum(): true when this step takes the round trip (field() holds
  /// Z and the cutoff and spectrum run).
  bool round_trip_now() const { return trip_now_; }
  /// Between propagate() and spectrum(): full steps after this one until the step that takes the
  /// round trip (0: this one). A spatial source of this step reaches the field that many steps
  /// late, so it must be propagated by that many dt first (ShipWaves::gather).
  int steps_to_round_trip() const { return spatial_ ? static_cast<int>((every_ - (steps_ + 1) % every_) % every_) : 0; }
  /// N x N transforms per full step, on average: 2/K for the round trip (0 without it) + 1 for
  /// the height (0 with external_height).
  double transforms_per_step() const { return (spatial_ ? 2.0 / every_ : 0.0) + (p_.external_height ? 0.0 : 1.0); }

  /// Wall time spent inside FFTW executions by the step's stages, summed (unit: ns).
  std::uint64_t fft_ns() const { return fft_ns_; }

  // ---- test hook (tests only; no scene, command or option reaches it) ------------------------
  /// Makes the named stage (any stage registered in stats(), e.g. "propagate", "cutoff",
  /// "spectrum", "height", or the solver's "drops", "ships") write one NaN into its output at
  /// step `step` (1-based, the step being computed), before that stage's own check: it then
  /// behaves as if the stage had produced it. Throws std::invalid_argument for an unknown stage.
  void inject_nonfinite_for_test(const std::string& stage, std::int64_t step);
  /// True when the hook asks `stage` (an index in stats()) to inject during the current step.
  bool inject_due_for_test(int stage) const { return stage == inject_stage_ && steps_ + 1 == inject_step_; }
  /// True when the current step runs the per-stage checks (every check_every steps).
  bool check_step() const { return check_now_; }

  // ---- raw FFT access for the benchmark (the same plans the step executes) -------------------
  void raw_transforms();

 private:
  void build_tables();
  void allocate();
  void make_plans();
  void register_stages();
  void check_stage(int stage, std::span<const cfloat> v);
  /// Runs a transform of the step for `stage`: times it and counts it and its bytes sent.
  void run_transform(const GridTransform& t, int stage);
  /// Cell (N/2, N/2) of the whole grid (the middle of the layout's rows): inside the visible
  /// region (test hook).
  std::size_t mid_index() const { return static_cast<std::size_t>(g_.rows / 2) * p_.n + p_.n / 2; }

  HuygensParams p_;
  GridLayout g_;
  StageChecks checks_;
  double t_ = 0.0;
  std::int64_t steps_ = 0;
  AlignedBuffer<cfloat> z_, s_, h_;  // spatial field, spectrum, packed height
  // per-mode tables on one quadrant (N/2+1)^2: they depend on |k_x| and |k_y| only
  AlignedBuffer<float> rot_a_, rot_b_, rot_c_;  // lifting t, s, sign/N^2 (or cos, sin / N^2)
  AlignedBuffer<float> alpha_, beta_;           // height packing (with 1/N^2)
  AlignedBuffer<float> src_, omega_;            // -omega/k (source factor) and omega, on demand
  AlignedBuffer<float> cut_;                    // h(p), N values, each twice (re, im)
  AlignedBuffer<cfloat> src_x_, src_y_;         // per-source separable factors, N values each
  AlignedBuffer<float> eta_, etadot_;           // visible outputs
  std::unique_ptr<GridTransform> inv_prop_;     // Z -> Z in place, backward
  std::unique_ptr<GridTransform> fwd_;          // Z -> S, forward
  std::unique_ptr<GridTransform> inv_height_;   // H -> H in place, backward
  StageStats stats_;
  int st_propagate_ = -1, st_cutoff_ = -1, st_spectrum_ = -1, st_height_ = -1;
  bool check_now_ = false;
  int inject_stage_ = -1;          // test hook only
  std::int64_t inject_step_ = -1;  // test hook only
  bool spatial_ = true;
  int every_ = 1;          // K: round trip every K steps
  bool trip_now_ = false;  // the current step takes the round trip
  std::uint64_t fft_ns_ = 0;
};

}  // namespace huygens
