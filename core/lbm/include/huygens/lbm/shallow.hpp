#pragma once
// Lattice Boltzmann shallow-water solver, D2Q9 with BGK collision: paper 002 section 2 (eq. 1-4),
// after Zhou 2004 (LABSWE). Lattice units inside (dx = dt = e = 1); depths stay in metres, so g
// enters as g_lat = g dt^2 / dx^2 (unit 1/m). Links 0 rest, 1 E, 2 N, 3 W, 4 S, 5 NE, 6 NW, 7 SW,
// 8 SE; lambda_a = 1 on axis links, 1/4 on diagonals. Equilibrium (eq. 2, Zhou 2004 eq. 13):
//   f0 = h (1 - 5 g h / 6 - 2 u.u / 3),  fa = lambda_a h (g h / 6 + e_a.u / 3 + (e_a.u)^2 / 2 - u.u / 6)
// One step (eq. 1, pull form): f_a(x, t+1) = f*_a(x - e_a, t) + S_a; h = sum f, h u = sum e f
// (eq. 3-4); f*_a = f_a - (f_a - f_a^eq) / tau + lambda_a h (e_a . a_ext) / 3, tau = 1/2 + 3 nu dt/dx^2.
// Bed slope, well balanced (evaluated at the link midpoint):
//   S_a = -lambda_a g (h(x) + h(x - e_a)) (z_b(x) - z_b(x - e_a)) / 6
// Sides and obstacles are ghost cells a precomputed rule list fills before each step (bounce-back,
// mirror, periodic image, Zou-He inflow and outflow). Populations are stored minus the still-water
// equilibrium of the mean depth, unshifted once a cell is dry (or from the start).
// Wetting and drying (a pass of its own while a cell is dry): a cell with h < h_min is dry. The
// face between x and n = x - e_a carries the pair f*_a(n) + f*_abar(x). A face with a dry side
// (open only if the water stands above the dry bed: still water next to land stays still) or a
// wet cell above Froude 0.8 takes a finite-volume flux instead: MUSCL-Hancock HLL of the link's
// own 1D problem (mass M and momentum Pi along e_a, which a uniform equilibrium would stream), and
// every cell with such a face is updated as h += sum M_a, J += sum e_a Pi_a and set to the
// equilibrium of (h, J) (the D2Q9 BGK relaxation is not dissipative beyond Froude 1: it holds an
// expansion jump at the sonic point of a dry-bed dam break). Dry-dry faces exchange nothing, other
// faces stream with the bed term (wet-wet) or bounce back (closed). An outflow limiter scales each
// face's net flux by theta = min(1, h / outflow) of the cell it drains (every depth stays >= 0),
// speeds are capped at the Riemann bound max(|u| + 2 sqrt(g h)) of the initial state, and each
// cell's populations are made to sum to its mass balance accumulated in double (the face
// exchanges are exact negatives of each other), what the floats cannot hold carried to the cell's
// next step in a float plane (compensated storage, Kahan 1965; scenes that start with a dry cell).
// A negative depth stops the run (LbmDryError).
// Why each choice, and measurements: docs/lbm.md.
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "huygens/common/comm.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/common/finite.hpp"
#include "huygens/common/stats.hpp"

namespace huygens {

/// What a side of the rectangular domain does.
enum class LbmSide : std::uint8_t {
  wall,      ///< no-slip, halfway bounce-back
  slip,      ///< free-slip, specular reflection
  periodic,  ///< wraps to the opposite side (which must be periodic too)
  inflow,    ///< given discharge per unit width (left side only)
  outflow,   ///< given depth, or zero gradient when none is given (right side only)
};

/// How the bed slope enters the momentum equation.
enum class LbmBedForce : std::uint8_t {
  centred,  ///< well-balanced midpoint form (see the header comment)
  naive,    ///< -g h(x) times the central difference of z_b at x (not well balanced)
};

/// Parameters of a run, in physical units.
struct LbmParams {
  /// Cells along x (columns).
  int cols = 64;
  /// Cells along y (rows).
  int rows = 64;
  /// Cell size dx (unit: m).
  double cell_m = 0.1;
  /// Time step dt (unit: s); the lattice speed is e = cell_m / dt_s.
  double dt_s = 0.01;
  /// Gravitational acceleration (unit: m/s^2).
  double gravity_mps2 = 9.81;
  /// Kinematic (eddy) viscosity nu (unit: m^2/s); sets tau = 1/2 + 3 nu dt / dx^2.
  double viscosity_m2s = 1e-3;
  /// Uniform external acceleration, x and y (unit: m/s^2); enters as the force h a.
  std::array<double, 2> accel_mps2 = {0.0, 0.0};
  /// Bed-slope force form.
  LbmBedForce bed_force = LbmBedForce::centred;
  /// Sides: left (x = 0), right, bottom (y = 0), top.
  LbmSide left = LbmSide::wall, right = LbmSide::wall, bottom = LbmSide::wall, top = LbmSide::wall;
  /// Discharge per unit width through an inflow side, along +x (unit: m^2/s).
  double inflow_discharge_m2s = 0.0;
  /// Depth held at an outflow side (unit: m); 0 = zero-gradient outflow.
  double outflow_depth_m = 0.0;
  /// Depth below which a cell is dry (unit: m): it holds its water at rest and passes none on.
  double min_depth_m = 1e-4;
  /// Largest |u| + sqrt(g h) the flow is expected to reach beyond the initial state, e.g. from
  /// the Stoker solution of a dam (unit: m/s); 0 = use the initial state only.
  double expected_signal_speed_mps = 0.0;
  /// Largest Froude number |u| / sqrt(g h) the flow is expected to reach beyond the initial
  /// state, e.g. the Stoker middle state of a dam (dimensionless); 0 = initial state only.
  double expected_froude = 0.0;
  /// Accept an initial state above kLbmMaxFroude when a fluid cell starts dry: the wet/dry pass,
  /// which then runs while a cell is dry, takes the HLL flux on every cell above Froude 0.8 (once
  /// every cell is wet the all-wet pass runs, unchecked). For a run started from an analytic state
  /// (validation: Ritter from its exact fan); scenes cannot set it. Default: refused.
  bool allow_supercritical_start = false;
};

/// Largest Froude number accepted before the run: at u = c = sqrt(g h) the equilibrium against the
/// flow, h (c^2/2 - c/3) (lattice units), is negative unless c >= 2/3, which |u| + c < 0.8 forbids;
/// transcritical flows are refused with a margin (measured limit: docs/lbm.md).
inline constexpr double kLbmMaxFroude = 0.9;

/// Initial fields, row-major (rows, cols), physical units. Empty vectors mean zero.
struct LbmFields {
  /// Bed elevation z_b (unit: m).
  std::vector<float> bed_m;
  /// Water depth h (unit: m).
  std::vector<float> depth_m;
  /// Velocity along x (unit: m/s).
  std::vector<float> ux_mps;
  /// Velocity along y (unit: m/s).
  std::vector<float> uy_mps;
  /// 1 = obstacle (solid) cell.
  std::vector<std::uint8_t> solid;
};

/// Refusal of a parameter set before the run: names the parameter and suggests a fix.
class LbmRefused : public std::invalid_argument {
 public:
  LbmRefused(std::string parameter, const std::string& reason)
      : std::invalid_argument(parameter + ": " + reason), parameter_(std::move(parameter)) {}
  /// "viscosity_m2s", "dt_s", "cell_m", "depth_m", "left", ...
  const std::string& parameter() const { return parameter_; }

 private:
  std::string parameter_;
};

/// A fluid cell's depth went negative during the run (the wet/dry rule could not keep it >= 0).
/// Stage "negative_depth"; what() reads "a negative depth: step N: cell (row r, col c) fell to ...".
class LbmDryError : public RunStopped {
 public:
  LbmDryError(std::int64_t step, const std::string& where)
      : RunStopped("negative_depth", step, "a negative depth: " + where) {}
};

/// Derived lattice quantities (dimensionless unless stated).
struct LbmLattice {
  /// BGK relaxation time.
  double tau = 1.0;
  /// g_lat = g dt^2 / dx^2 (unit: 1/m), so g_lat h is the squared lattice wave speed.
  double g_lat_pm = 0.0;
  /// Lattice speed e = dx / dt (unit: m/s).
  double speed_mps = 1.0;
  /// Largest (|u| + sqrt(g h)) / e of the initial state or the expected flow.
  double signal_ratio = 0.0;
  /// Largest (|u| + 2 sqrt(g h)) / e of the initial state: the Riemann-invariant bound on the
  /// speed water released from it can reach (the front of a dam break onto a dry bed, 2 sqrt(g h0)).
  double riemann_ratio = 0.0;
  /// Smallest f0 / h of the initial state (>= 0 required).
  double min_rest_fraction = 1.0;
};

/// The equilibrium of paper 002 eq. 2 in lattice units (e = 1): depth h (unit: m), lattice
/// velocity (ux, uy) (u dt/dx) and g_lat = g dt^2/dx^2 (unit: 1/m); feq in metres.
std::array<double, 9> lbm_equilibrium(double g_lat, double h, double ux, double uy);

/// Checks a parameter set and its initial fields; throws LbmRefused naming the parameter:
/// tau >= 0.55, (|u| + sqrt(g h)) dt/dx < 0.8, f0 >= 0 (g h < 1.2 in lattice units), Froude
/// number <= kLbmMaxFroude (over wet cells), no negative depth and at least one wet cell,
/// consistent sides. Returns the lattice quantities.
LbmLattice lbm_check(const LbmParams& p, const LbmFields& init);

/// True when a fluid cell of the initial fields is dry (depth < min_depth_m): the solver then keeps
/// a carry plane (one float per lattice cell) for the wet/dry pass's mass balance (docs/lbm.md).
bool lbm_starts_dry(const LbmParams& p, const LbmFields& init);

/// The instruction set the all-wet LBM kernel runs with: "build's", or, in an x86-64 build below
/// x86-64-v4 (GCC), "x86-64-v4 copy ..." when this CPU has AVX-512 (a second copy of the kernel,
/// chosen at run time; bitwise the same results).
const char* lbm_kernel_isa();
/// Lets the all-wet kernel use its AVX-512 copy when the CPU has one (default true); false runs
/// the build's copy (tests compare the two).
void lbm_allow_wide_kernel(bool allowed);

/// How a run is split over MPI ranks (comm.hpp, docs/scale.md): rank `rank` of `ranks` holds the
/// rows row_slab(rows, ranks, rank) and keeps halo rows of its neighbours (one row of populations,
/// two of depth; two of populations in a wet/dry step, for the MUSCL slopes) refreshed every step
/// with non-blocking messages; every decision that depends on
/// the whole domain (the wet/dry pass, the redo of a step, a bad cell) is agreed by a reduction, so
/// the fields are bitwise those of one process. Each rank needs at least 3 rows. Default: one rank.
struct LbmDecomposition {
  int ranks = 1;
  int rank = 0;
};

/// The solver state. Built from params and initial fields (after lbm_check); step() does no
/// allocation, logging or I/O.
class LbmShallow {
 public:
  LbmShallow(const LbmParams& p, const LbmFields& init, LbmDecomposition d = {});
  /// The global rows this rank holds (all rows with one rank).
  RowSlab slab() const { return {static_cast<std::size_t>(row0_), static_cast<std::size_t>(rows_)}; }

  /// One step: boundary fill, then one fused stream-collide pass (OpenMP over rows).
  /// Throws NonFiniteError("stream_collide", step) or LbmDryError.
  void step();
  void run(std::int64_t n) {
    for (std::int64_t i = 0; i < n; ++i) step();
  }

  const LbmParams& params() const { return p_; }
  const LbmLattice& lattice() const { return lat_; }
  std::int64_t steps() const { return steps_; }
  /// Simulated time (unit: s).
  double time_s() const { return static_cast<double>(steps_) * p_.dt_s; }
  const StageStats& stats() const { return stats_; }

  /// Total water volume over this rank's fluid cells, accumulated in double (unit: m^3 per metre
  /// of width for a 1-row channel: sum h dx^2).
  double volume_m3() const;
  /// Depth h of this rank's rows, row-major (slab().rows, cols); 0 in obstacle cells (unit: m).
  void depth(std::span<float> out) const;
  /// Velocity (slab().rows, cols, 2) = (u_x, u_y); 0 in obstacle cells (unit: m/s).
  void velocity(std::span<float> out) const;
  /// Bed elevation (slab().rows, cols) (unit: m).
  void bed(std::span<float> out) const;
  /// Depth of one cell of this rank's rows (global row; unit: m).
  float depth_at(int row, int col) const;
  /// Velocity of one cell (unit: m/s).
  std::array<float, 2> velocity_at(int row, int col) const;
  bool solid_at(int row, int col) const { return solid_[idx(row, col)] != 0; }
  /// Post-collision population of link a (0..8) at a cell (unit: m), for tests.
  float population(int row, int col, int a) const {
    return static_cast<float>(fa_[static_cast<std::size_t>(a) * plane_ + idx(row, col)] + shift_[a]);
  }

  /// Bytes the stream-collide pass reads and writes per fluid cell.
  int bytes_per_cell() const;
  /// Fluid cells with depth below min_depth_m after the last step (or initially), over all ranks.
  std::size_t dry_cells() const { return dry_; }
  /// Steps the all-wet pass handed over to the wet/dry pass and redid (a cell fell below min_depth_m
  /// or went negative in it), since construction, over all ranks (every rank counts the same steps).
  std::int64_t redone_steps() const { return redone_; }
  /// True when the run keeps the mass carry plane (the scene started with a dry cell).
  bool has_mass_carry() const { return carry_.size() != 0; }
  /// Bytes this rank sent to its neighbours so far (halo rows; unit: byte).
  std::uint64_t bytes_sent() const { return xchg_.bytes_sent(); }

 private:
  struct Rule {
    std::uint32_t dst;  // population index written (plane a, ghost s)
    std::uint32_t src;  // population index read (COPY), or the fluid cell x (INFLOW/OUTFLOW)
    std::uint32_t x;    // fluid cell receiving the population
    std::uint32_t s;    // ghost / obstacle cell
    std::uint32_t up;   // true upstream cell (periodic image) or kNone
    std::uint8_t a;     // link
    std::uint8_t kind;  // 0 copy, 1 inflow, 2 outflow with depth
  };
  struct Span {
    std::uint32_t begin, end;  // cell indices [begin, end) of one row
  };

  // Index of cell (global row, col) in this rank's lattice: rows row0_ - halo_ .. row0_ + rows_ +
  // halo_ - 1, then the periodic image row (y-periodic sides on several ranks).
  std::size_t idx(int row, int col) const {
    int lr = row - row0_;
    if (lr < -halo_ || lr >= rows_ + halo_) lr = rows_ + halo_;  // the image row
    return static_cast<std::size_t>(lr + halo_) * stride_ + kPad + static_cast<std::size_t>(col);
  }
  void init_lattice(const LbmFields& in);
  void build_rules(const LbmFields& in);
  std::vector<Rule> make_rules(int r0, int r1, int s0, int s1, const std::vector<std::uint8_t>& solid) const;
  // decomposition (halo.cpp)
  void set_slab(LbmDecomposition d);
  // Calls fn(global row) for every row of this rank's lattice (its rows, halo rows, image row).
  template <class Fn>
  void for_lattice_rows(Fn fn) const {
    for (int r = row0_ - halo_; r < row0_ + rows_ + halo_; ++r) fn(r);
    if (image_row_ >= 0) fn(image_row_);
  }
  void exchange_halos();
  void start_halos();
  void finish_halos();
  void all_wet_kernel(int& flagged);
  void all_wet_overlapped(int& flagged);
  void exchange_theta();
  void exchange_second_rows();
  void agree(int& flagged, int& bad);
  void fill_ghosts(bool wet_dry);
  void set_ghost_depths();
  template <int Mode, bool Force>
  void stream_collide(int& flagged);
  struct WetDryView;
  WetDryView wet_dry_view(const float* flags) const;
  void flag_supercritical();
  void outflow_limiter();
  float wet_dry_cell(const WetDryView& view, std::ptrdiff_t c, float* dst, float* carry) const;
  void stream_collide_wet_dry(int& dry, int& bad);
  void unshift();
  void throw_bad_cell() const;
  void throw_periodic_wet_dry() const;

  static constexpr std::size_t kPad = 16;  // interior column 0 starts 64-byte aligned
  static constexpr std::uint32_t kNone = 0xffffffffu;

  LbmParams p_;
  LbmLattice lat_;
  std::size_t stride_ = 0, plane_ = 0;
  AlignedBuffer<float> fa_, fb_;  // 9 planes each: post-collision populations
  AlignedBuffer<float> ha_, hb_;  // depth at the current and next step
  AlignedBuffer<float> z_;        // bed
  AlignedBuffer<float> theta_;    // outflow limiter of the wet/dry pass
  // what a cell's floats could not hold of its mass balance, added back at its next wet/dry step
  // (m; allocated only when the scene starts with a dry cell)
  AlignedBuffer<float> carry_;
  std::vector<std::uint8_t> solid_;  // per lattice cell: 1 = not fluid (ghost or obstacle)
  std::vector<Span> spans_;
  std::vector<Rule> rules_;
  float omega_ = 1.0f, g_ = 0.0f, ax_ = 0.0f, ay_ = 0.0f, hmin_ = 0.0f, href_ = 0.0f, umax_ = 1.0f;
  std::array<double, 9> shift_{};  // f_a = stored_a + shift_a = equilibrium of (href, u = 0)
  std::array<float, 9> shift_f_{};
  bool has_bed_ = false;
  std::size_t ncells_ = 0;  // fluid cells
  std::size_t dry_ = 0;     // fluid cells with h < h_min (the wet/dry pass runs while > 0)
  std::int64_t steps_ = 0;
  std::int64_t redone_ = 0;  // steps redone by the wet/dry pass (step())
  StageStats stats_;
  int st_fill_ = 0, st_kernel_ = 0;
  // decomposition over ranks (halo.cpp): this rank's rows [row0_, row0_ + rows_), halo rows each side
  int ranks_ = 1, rank_ = 0, row0_ = 0, rows_ = 0, halo_ = 1;
  int image_row_ = -1;             // global row of the periodic image row, -1 without
  std::vector<Rule> depth_rules_;  // several ranks: rules of own and halo cells that set ghost depths
  std::vector<Span> halo_spans_;   // fluid cells of the first halo rows and the image row
  // the all-wet pass on several ranks: rows and rules that read no halo (inner) and the edge rows'
  std::vector<Span> inner_spans_, edge_spans_;
  std::vector<Rule> inner_rules_, edge_rules_;
  std::vector<float> send_[3], recv_[3];  // halo messages: to/from below, above, periodic image
  HaloExchange xchg_{12};
  int st_halo_ = -1, st_reduce_ = -1;
};

}  // namespace huygens
