#pragma once
// The "huygens" solver on MPI ranks (issue 17, docs/scale.md "Huygens on slabs"): the same
// step as HuygensSolver (solver.hpp; paper 004 section 3) on row slabs of the N x N grid with
// FFTW's MPI transforms (slab_fft.hpp). The spectrum is kept transposed (rank p owns kx rows), so
// the three propagation/height transforms each pay one all-to-all transpose; with FFTW_ESTIMATE
// plans (N >= 256) the transforms run in Fft2D's row-column form instead, spectrum in the normal
// layout, and give the one-process spectrum bit for bit (SlabTransforms). Stages:
//   propagate (rotation on the local kx rows, backward TRANSPOSED_IN) -> cutoff (local y rows)
//   -> ships (each rank adds the rows of every P x P patch it owns) -> spectrum (forward
//   TRANSPOSED_OUT) -> drops (analytic spectrum on the local kx rows) -> wind (quadrant phase)
//   -> height. The height eta + i etadot = IFFT[i (alpha Y(k) + beta conj Y(-k))] couples k and
//   -k, which sit on different ranks; beta depends on |k| only, so
//     IFFT[beta conj Y(-k)](x) = conj(IFFT[beta Y](x)),
//   and the height is i A + i conj(B) with A = IFFT[alpha Y], B = IFFT[beta Y]; as alpha - beta = m
//   = k/omega and alpha + beta = k, that is eta = -Im IFFT[m Y], etadot = Re IFFT[k Y] (the form
//   computed: no difference of the two large k/2 terms). A second transform (one more
//   transpose, 8 N^2/P (P-1)/P bytes) instead of exchanging the mirrored slab (8 N^2/P bytes,
//   nearly all of it off-rank): fewer bytes and no communication of our own.
//   Second order adds chi and chidot (stokes.hpp): 4 height transforms instead of 3.
// Non-finite checks and the still-sea energy are summed in ONE MPI_Allreduce per step; a stage
// that fails on any rank is named on every rank (the first in step order).
#ifdef HUYGENS_HAVE_MPI
#include <mpi.h>

#include <array>
#include <memory>

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

class HuygensSlabSolver : public Solver {
 public:
  /// Collective on comm: plans, tables and the initial state of the rows this rank owns.
  HuygensSlabSolver(const HuygensScene& scene, MPI_Comm comm, SlabTransforms how = SlabTransforms::automatic);
  ~HuygensSlabSolver() override;
  HuygensSlabSolver(const HuygensSlabSolver&) = delete;
  HuygensSlabSolver& operator=(const HuygensSlabSolver&) = delete;

  /// One full step (collective). Throws NonFiniteError on every rank when a stage failed on any.
  void step() override;
  double time() const override { return static_cast<double>(steps_) * scene_.params.dt_s; }
  std::int64_t steps() const override { return steps_; }
  /// (steps() + k) dt, as time() (exact).
  double time_bound(int k) const override { return static_cast<double>(steps_ + k) * scene_.params.dt_s; }
  /// This rank's rows of the visible eta: shape {rows, v}, global_shape {v, v}, row0.
  std::vector<OutputField> outputs() override;
  /// The global grid (as HuygensSolver::meta) plus "mpi": ranks, layout, transposes per step.
  nlohmann::json meta() const override;
  const StageStats& stats() const override { return stats_; }
  std::span<const float> height() override { return eta_.span(); }
  std::size_t height_rows() const override { return static_cast<std::size_t>(vis_rows_); }
  std::size_t height_cols() const override { return static_cast<std::size_t>(v_); }
  std::span<const float> height_rate() override { return etadot_.span(); }
  int display_per_step() const override { return scene_.display_per_step; }
  MemoryEstimate memory() const override { return huygens_slab_memory(scene_, g_.ranks); }
  std::vector<OutputField> display_outputs(int j) override;
  std::size_t ship_poses(std::span<ShipState> out) const override;

  const SlabGrid& grid() const { return g_; }
  /// Row of the global visible region where this rank's height rows start.
  std::size_t visible_row0() const { return static_cast<std::size_t>(vis_row0_); }
  /// N x N transforms of a full step that takes the spatial round trip (each one all-to-all
  /// transpose); steps between two round trips (every K = round_trip_every) take 2 fewer.
  int transforms_per_step() const;
  /// N x N transforms per full step on average: the round trip's 2 every K steps + the height.
  double mean_transforms_per_step() const;
  /// Bytes this rank sends in the transposes of a full step (unit: bytes, on average): mean_transforms_per_step()
  /// x transposes per transform x slab_transpose_bytes() = T t 8 N^2/P (P-1)/P for an even split
  /// (the step's one reduction adds 17 doubles).
  double bytes_sent_per_step() const;
  /// Wall time inside the N x N transforms (local FFTs and transposes; unit: ns), summed.
  std::uint64_t fft_ns() const { return fft_ns_; }
  bool still() const { return still_; }
  /// This rank's rows of the spectrum Z^ (krows x N, the grid's layout; unnormalised).
  std::span<const cfloat> spectrum_view() const { return {s_.data(), static_cast<std::size_t>(g_.krows) * g_.n}; }

 private:
  void allocate();
  void build_tables();
  void build_cutoff();
  void reserve_sources();
  void make_plans();
  void initial_state();
  void add_gaussian(double x_m, double y_m, double sigma_m, double amplitude_m, double age_s);
  void add_plane_wave(double wavelength_m, double amplitude_m, double direction_deg);
  void propagate();
  void rotate(const float* s, float* z, float scale);
  void cutoff();
  void add_ships(double t0);
  void spectrum();
  void release_drops();
  void make_height();
  void pack_height(const float* s, float zscale);
  bool extract_height();
  void check(int stage, std::span<const cfloat> v);
  /// The step's one reduction: non-finite flags and (when due) the still-sea energy.
  void reduce_step(bool energy_due);
  void keep_previous_step();
  bool drop_due() const;

  HuygensScene scene_;
  MPI_Comm comm_;
  SlabGrid g_;
  int v_ = 0;  // visible side N - 2M
  std::ptrdiff_t vis_row0_ = 0, vis_rows_ = 0, vis_first_ = 0;
  std::int64_t steps_ = 0;
  bool spatial_ = true, second_ = false, wind_on_ = true;
  int every_ = 1;          // K: the round trip every K steps (HuygensParams::round_trip_every)
  bool trip_now_ = false;  // the current step takes it
  AlignedBuffer<cfloat> z_, s_, a_, b_, chi_, chid_;
  AlignedBuffer<float> rot_a_, rot_b_, rot_c_, kw_, kk_, sq_, cut_, src_, omega_;
  AlignedBuffer<cfloat> src_x_, src_y_;
  AlignedBuffer<float> eta_, etadot_, eta0_, etadot0_, frame_;
  std::unique_ptr<SlabFft> inv_prop_, fwd_, inv_height_;
  std::unique_ptr<ShipWaves> ships_;
  std::unique_ptr<WindSea> wind_;
  StageStats stats_;
  int st_propagate_ = -1, st_cutoff_ = -1, st_ships_ = -1, st_spectrum_ = -1, st_drops_ = -1, st_wind_ = -1,
      st_height_ = -1, st_still_ = -1;
  static constexpr int kMaxStages = 16;
  std::array<double, kMaxStages + 1> flags_{};  // per stage: non-finite hits this step; last: energy sum
  bool check_now_ = false;
  std::size_t next_drop_ = 0;
  double still_energy_ = 0.0;
  bool still_ = false;
  std::uint64_t fft_ns_ = 0;
  std::uint64_t sent_per_transform_ = 0;  // bytes this rank sends in one N x N transform
};

}  // namespace huygens
#endif
