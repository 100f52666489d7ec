#pragma once
// Ship waves of paper 004 eq. 2 (docs/design.md 3.3, docs/ocean.md): the waves a hull adds
// while it moves at velocity v (m/s) during [t, t + dt], observed at t + dt,
//   dZ^(k) = C(k) [ Phi1^(k) E^_t(k) + Phi2^(k) E^_{t+dt}(k) ],   C(k) = -i omega(k) / k,
//   Phi1^ = e^{-i w} ( -1 + i w (e^{-i a} + i a - 1) / a^2 ),
//   Phi2^ =            1 + i w (e^{+i a} - i a - 1) / a^2,
//   a = alpha(k) = (k.v - omega(k)) dt,  w = omega(k) dt.
// E (m) is the hull's elevation draft * sqrt(1 - (2 x'/length)^2 - (2 y'/beam)^2) (x' along the
// heading), blurred by exp(-k^2 blur^2 / 2); for a rigid translation the bracket is
// E^_t beta (e^{-i beta} - e^{-i w}) / (beta - w), beta = k.v dt: a hull at rest makes no waves.
// The convolution runs on a P x P patch around each ship with its own small FFT, added to the
// spatial field (m^2/s) with periodic wrap at the grid edge.
#include <complex>
#include <cstdint>
#include <vector>

#include "huygens/common/dispersion.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/common/scene.hpp"

namespace huygens {

/// Shape of one hull.
struct HullParams {
  /// Hull length along the heading (unit: m).
  double length_m = 1.0;
  /// Hull beam, the width across the heading (unit: m).
  double beam_m = 0.3;
  /// Draft: the depth of the hull's deepest point (unit: m).
  double draft_m = 0.05;
  /// Standard deviation of the Gaussian blur of the profile (unit: m); negative means beam_m / 4.
  double blur_m = -1.0;

  /// Blur actually used (unit: m).
  double blur() const { return blur_m < 0.0 ? 0.25 * beam_m : blur_m; }
};

/// One point of a timed path.
struct PathPoint {
  /// Time at which the hull centre is here (unit: s).
  double t_s = 0.0;
  /// Position along the grid's columns (unit: m).
  double x_m = 0.0;
  /// Position along the grid's rows (unit: m).
  double y_m = 0.0;
};

/// A piecewise-linear timed path. Before the first point the hull rests at the first
/// point, after the last point it rests at the last one. The heading is the direction of
/// the segment containing t (right-continuous); on a segment without motion it keeps the
/// heading of the last moving segment before it (or the first one after it; else +x).
class ShipPath {
 public:
  ShipPath() = default;
  /// Throws std::invalid_argument when empty or when times decrease.
  explicit ShipPath(std::vector<PathPoint> points);
  /// Appends a point (interactive dragging); throws when t is before the last point's time.
  void append(const PathPoint& p);
  /// Ends the path at time t (a ship taken over by steering): the points after t are removed and,
  /// when any were, the position at t becomes the last point. Never grows the point storage
  /// beyond its size before the call (no allocation).
  void truncate_after(double t);
  const std::vector<PathPoint>& points() const { return pts_; }

  /// Hull centre at time t (unit: m).
  void position(double t, double& x, double& y) const;
  /// Velocity of the segment containing t (unit: m/s); zero outside the path.
  void velocity(double t, double& vx, double& vy) const;
  /// Mean velocity over [t, t + dt] (unit: m/s): the segment's own velocity when the step
  /// lies within one segment (bit-identical from step to step), else the chord velocity.
  void step_velocity(double t, double dt, double& vx, double& vy) const;
  /// Heading angle from +x towards +y (unit: rad).
  double heading(double t) const;

 private:
  int segment(double t) const;  // index i with t in [t_i, t_{i+1}), -1 before, size-1 after
  std::vector<PathPoint> pts_;
};

/// Bounds of a ship's motion when it is steered interactively (cmd::ShipTarget).
struct SteeringParams {
  /// Top speed (unit: m/s); <= 0: sqrt(g length) (hull Froude number 1; 1 m/s without gravity). Always also limited to
  /// a quarter of the ship patch per step, the bound ShipWaves::check_step enforces for paths.
  double max_speed_mps = -1.0;
  /// Largest change of velocity per unit time (unit: m/s^2); <= 0: top speed / 2 s.
  double max_accel_mps2 = -1.0;
  /// Time constant of the approach to the target (unit: s); at least one step is used.
  double time_constant_s = 0.5;
};

/// One ship: its hull, its path and how it may be steered.
struct Ship {
  HullParams hull;
  ShipPath path;
  SteeringParams steering;
};

/// Where a ship is at one time, for the frame pipeline and the renderer.
struct ShipPoseNow {
  /// Hull centre (unit: m).
  double x_m = 0.0, y_m = 0.0;
  /// Heading from +x towards +y (unit: rad).
  double heading_rad = 0.0;
  /// Speed over the last step (unit: m/s).
  double speed_mps = 0.0;
};

/// Reads the scene's `ships` array (absent: none): length_m, beam_m, draft_m, optional blur_m,
/// `path`, an array of {t_s, x_m, y_m} with non-decreasing t_s, and an optional `steering` object
/// {max_speed_mps, max_accel_mps2, time_constant_s} (SteeringParams). Errors name the JSON path.
std::vector<Ship> parse_ships(const JsonIn& root);

/// Phi1^ and Phi2^ of paper 004 eq. 2 for one wave vector, with beta = k.v dt and
/// w = omega dt (alpha = beta - w); a series in alpha is used for |alpha| < 0.5 so the
/// kernels stay exact as alpha -> 0.
void ship_kernels(double beta, double w, std::complex<double>& phi1, std::complex<double>& phi2);
/// The rigid-translation closed form beta (e^{-i beta} - e^{-i w}) / (beta - w) (its limit
/// -i w e^{-i w} at beta = w), i.e. Phi1^ + Phi2^ e^{-i beta}.
std::complex<double> ship_translation_factor(double beta, double w);
/// Continuous Fourier transform of the blurred hull elevation draft * p(x) centred at the
/// origin with the given heading (unit: m^3): draft * 2 pi a b j1(q)/q * exp(-k^2 blur^2/2),
/// q^2 = (a k_along)^2 + (b k_across)^2, a = length/2, b = beam/2.
double hull_spectrum(const HullParams& hull, double kx, double ky, double heading);

/// The ship-wave stage: preallocated patch, one small plan, per-ship cached kernel spectra.
class ShipWaves {
 public:
  /// n x n grid of side length_m; patch P x P cells (even, <= n). Throws
  /// std::invalid_argument when a hull (with its blur) does not fit in half the patch.
  ShipWaves(const Water& water, int n, double length_m, int patch, std::vector<Ship> ships,
            PlanEffort effort = PlanEffort::measure);

  /// Throws std::invalid_argument (with the reason) when a ship moves more than a quarter of
  /// the patch in one step of dt along its path, so its waves would wrap around the patch.
  /// Steered ships cannot break it: their speed is clamped to steer_speed_limit(i, dt).
  void check_step(double dt) const;

  // ---- interactive steering (cmd::ShipTarget; call between steps, never inside add()) ----
  /// Ship i leaves its path at time t (the path is truncated there: its later points are
  /// dropped) and from now on heads for the target point (x, y), which itself moves at
  /// (vx, vy) from t on and stops at the grid edge. Kinematics per step [t_k, t_k + dt], with
  /// a constant velocity v_k over the step (the straight-line motion eq. 2's kernels assume):
  ///   e_k   = p_T(t_k) - x_k,            p_T(t) = clamp(x_T + v_T (t - t_cmd), [0, L]^2)
  ///   v_des = v_T + e_k/|e_k| min(|e_k| / tau, sqrt(2 a_max |e_k|))   (0 when v_T = 0 and
  ///           |e_k| <= 0.05 dx: the ship stops there), then |v_des| <= v_max
  ///   v_k   = v_{k-1} + clamp_norm(v_des - v_{k-1}, a_max dt)   (a change below 1e-3 a_max dt
  ///           is dropped, so that rounding does not rebuild the kernels)
  ///   x_{k+1} = x_k + v_k dt,  heading_k = atan2(v_k) (kept when v_k = 0),
  /// tau = max(time_constant_s, dt), v_max = min(max_speed, steer_speed_limit), v_{-1} the
  /// velocity of the last step (or the path's at t). The hull turns over the step (eq. 2 with
  /// E_t at the old heading and E_{t+dt} at the new). A later target replaces the earlier one.
  /// Returns false (and changes nothing) for an invalid ship index, a non-finite value, or a
  /// target outside the grid [0, L]^2.
  bool steer(int i, double t, double x, double y, double vx, double vy);
  /// True once ship i follows a target instead of its path.
  bool steered(int i) const { return steer_[static_cast<std::size_t>(i)].active; }
  /// Top speed of steered ship i at step dt (unit: m/s): min(max_speed_mps, a quarter of the patch / dt).
  double steer_speed_limit(int i, double dt) const;
  /// Acceleration bound of steered ship i (unit: m/s^2).
  double steer_accel(int i) const;
  /// Pose of ship i at time t: its path's, or for a steered ship its state after the last step.
  ShipPoseNow pose(int i, double t) const;

  /// Adds the waves every ship generates during [t, t + dt], observed at t + dt, into the
  /// spatial wave field z (n x n, row-major, unit m^2/s). Call after the propagation of z
  /// to t + dt. One P x P inverse FFT per ship; no allocation. Every patch is checked for
  /// non-finite values before it is added (P x P values per ship, small against N x N): returns
  /// false, and leaves z without that ship's patch, when one is not finite.
  bool add(cfloat* z, double t, double dt);
  /// The same on a slab: z holds the global rows [row0, row0 + rows) of the n x n field, and
  /// only the patch rows that land there are added (every rank of a slab run calls it).
  bool add_rows(cfloat* z, int row0, int rows, double t, double dt);
  // ---- the round trip every K steps (HuygensPropagator::round_trip_every) ----------------------
  // Propagation is linear and diagonal in k (eq. 1), so a source dZ^ of the step ending at t + dt
  // that enters the field d steps later must arrive as dZ^ e^{-i omega d dt}. The factor is
  // applied on the patch's own wavenumbers before its inverse FFT: the same periodic-patch
  // approximation eq. 2's kernels already make within a step (Phi1 holds e^{-i omega dt}), now
  // over (d + 1) dt; exact while the waves of the step stay inside the patch for that time.
  /// Room for the patches of k steps per ship (call between steps; allocates).
  void reserve_gather(int k);
  /// The waves every ship generates during [t, t + dt], observed at t + (delay + 1) dt: each ship's
  /// patch spectrum turned by e^{-i omega delay dt}, inverse-transformed and kept until
  /// scatter_rows(). Returns false (the patch not kept) when one is not finite. No allocation
  /// within the reserved room; throws std::logic_error beyond it.
  bool gather(double t, double dt, int delay);
  /// Adds every patch gathered since the last call into the global rows [row0, row0 + rows) of
  /// the field z (periodic wrap) and forgets them.
  void scatter_rows(cfloat* z, int row0, int rows);
  /// Patches kept by gather() and not yet scattered.
  int gathered() const { return static_cast<int>(pending_.size()); }

  /// Test hook (tests only; no scene or command reaches it): the next add() writes one NaN
  /// into the first ship's patch before its check, as if the kernels had produced it.
  void poison_next_add_for_test() { poison_ = true; }

  /// The patch spectrum of ship i for the step [t, t + dt] (P x P, FFTW order, already
  /// normalised: an unnormalised inverse FFT gives the samples of dZ), and the big-grid
  /// cell (row0, col0) on which patch sample (0, 0) lands. Used by add() and by tests.
  void patch_spectrum(int i, double t, double dt, cfloat* out, int& row0, int& col0);

  int n() const { return n_; }
  int patch() const { return p_; }
  int ships() const { return static_cast<int>(ships_.size()); }
  /// The path of ship i (truncated when steering takes over).
  ShipPath& path(int i) { return ships_[static_cast<std::size_t>(i)].path; }
  /// How often a kernel spectrum was rebuilt (velocity, heading or dt changed).
  std::uint64_t kernel_rebuilds() const { return rebuilds_; }
  /// Bytes of buffers owned by the stage.
  std::size_t bytes() const;

 private:
  struct Cache {
    double vx = 0, vy = 0, h0 = 0, h1 = 0, dt = -1;
    AlignedBuffer<cfloat> g1, g2;  // C Phi1 E^(h0) / (dx^2 P^2) and C Phi2 E^(h1) / (dx^2 P^2)
  };
  /// The straight-line motion of one ship over one step.
  struct Motion {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0, vx = 0, vy = 0, h0 = 0, h1 = 0;
  };
  /// Steering state of one ship (active after the first ShipTarget).
  struct Steer {
    bool active = false;
    double x = 0, y = 0, vx = 0, vy = 0, h = 0;       // state after the last step
    double tx = 0, ty = 0, tvx = 0, tvy = 0, tt = 0;  // target, its velocity, command time
  };
  /// Velocity and heading of the last step of each ship (to start steering without a jump).
  struct Last {
    bool valid = false;
    double t1 = 0, vx = 0, vy = 0, h1 = 0;
  };
  Motion motion(int i, double t, double dt) const;
  /// Velocity of ship i at time t: its last step's when that step ended at t, else its path's.
  void velocity_at(int i, double t, double& vx, double& vy) const;
  void rebuild(const Ship& s, Cache& c, double vx, double vy, double h0, double h1, double dt);
  /// Ship i's patch of [t, t + dt] turned by e^{-i omega delay dt}, inverse-transformed into buf_
  /// and checked; on success the motion is committed. False when not finite.
  bool make_patch(int i, double t, double dt, int delay, int& row0, int& col0);
  /// Adds a P x P spatial patch landing on big-grid cell (r0, c0) into rows [row0, row0 + rows).
  void scatter_patch(const cfloat* src, int r0, int c0, cfloat* z, int row0, int rows);
  /// Fills delay_ with e^{-i omega d dt}, d = 1 .. slots - 1, for this dt.
  void build_delays(double dt);

  Water water_;
  int n_ = 0;
  int p_ = 0;
  double dx_ = 0;
  std::vector<Ship> ships_;
  std::vector<Cache> cache_;
  std::vector<Steer> steer_;
  std::vector<Last> last_;
  std::vector<Motion> motion_;      // the motion patch_spectrum used last, per ship
  std::vector<double> kx_, omega_;  // patch wavenumbers (per index) and omega per mode
  AlignedBuffer<cfloat> buf_;
  bool poison_ = false;       // test hook: see poison_next_add_for_test()
  AlignedBuffer<cfloat> ph_;  // 4 P phase vectors: e^{-i kx dx0}, e^{-i ky dy0}, and for t + dt
  std::vector<int> cols_;
  struct Pending {
    std::size_t slot;
    int r0, c0;
  };
  std::vector<Pending> pending_;  // gathered patches awaiting scatter_rows()
  AlignedBuffer<cfloat> store_;   // their samples: slots_ x P x P
  int slots_ = 0;                 // patches store_ holds (K x ships)
  int max_delay_ = 0;             // K - 1: the delays delay_ holds
  AlignedBuffer<cfloat> delay_;   // e^{-i omega d dt} on the patch modes, d = 1 .. K - 1
  double delay_dt_ = -1;          // the dt delay_ was made for
  Fft2D inverse_;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace huygens
