#pragma once
// Measuring a Kelvin wake (the ship waves of paper 004 eq. 2) from a heightfield.
// (1) Analytic signal: every wave of a steady wake has k.v = omega(k) > 0 (v the ship's velocity),
//     so the field's FFT kept on the half-plane k.d > 0 (doubled) gives a(x): |a| is the local
//     amplitude envelope without carrier, arg a the local wave phase.
// (2) Outer envelope half-angle psi: near the wedge edge the wake is an Airy caustic,
//     eta ~ Ai(-x) cos(phase). On each lateral profile at distance s behind the ship, the point on
//     the outer flank of the outermost lobe of |a| where |a| falls to Ai(0)/max Ai = 0.6628 of the
//     lobe lies on the caustic line; the fit n_c(s) = s tan(psi) + b gives psi.
// (3) Angle of maximum amplitude: median over the profiles of atan(n_max / s), sides averaged.
// (4) Transverse wavelength: lambda = 2 pi / |slope| of the unwrapped phase of a along the track.
// (5) Optional low-pass for (2) and (4) at high Froude numbers (WakeOptions::lowpass_k0).
#include <cmath>
#include <limits>
#include <vector>

#include "huygens/common/dispersion.hpp"
#include "huygens/spectral/ship_waves.hpp"

namespace huygens {

/// Placement of a heightfield: rows x cols, row-major, cell (r, c) at (x0 + c dx, y0 + r dx).
struct WakeGrid {
  /// Rows (along y) and columns (along x) (unit: cells).
  int rows = 0, cols = 0;
  /// Cell size (unit: m).
  double dx_m = 1.0;
  /// Position of cell (0, 0) (unit: m).
  double x0_m = 0.0, y0_m = 0.0;
};

/// The ship at the moment the heightfield was taken.
struct WakeTrack {
  /// Hull centre (unit: m).
  double x_m = 0.0, y_m = 0.0;
  /// Direction of motion from +x towards +y (unit: rad).
  double heading_rad = 0.0;
  /// Speed (unit: m/s).
  double speed_mps = 1.0;
};

/// How measure_kelvin_wake reads the field (method steps in the header comment).
struct WakeOptions {
  /// Nearest distance behind the hull centre that is measured (unit: m); < 0: 3 transverse wavelengths.
  double s_min_m = -1.0;
  /// Farthest distance behind the hull centre (unit: m); < 0: as far as the wedge stays on the grid.
  /// For a ship started from rest a distance D ago, use at most D / 2: the cusp waves recede
  /// from the hull at 2/3 U along the track and the transverse ones at U / 2, so the pattern is
  /// steady only closer than that (at 0.6 D the start transient already tilts the fit by 1.5 deg).
  double s_max_m = -1.0;
  /// Envelope level that marks the caustic line, relative to the Airy lobe (unit: 1).
  double level = 0.66277;
  /// Smallest Airy lobe accepted, relative to the profile's maximum (unit: 1).
  double lobe_fraction = 0.15;
  /// Lateral profiles extend to this angle from the track (unit: degrees).
  double search_angle_deg = 30.0;
  /// Gravity for the default distances and the low-pass (unit: m/s^2).
  double gravity_mps2 = 9.81;
  /// Low-pass for the envelope and the transverse wavelength (unit: 1): when > 0, the field is
  /// weighted by 1 / (1 + (k / (lowpass_k0 k0))^8), k0 = g / U^2, before those two are measured
  /// (the max-amplitude angle always uses the full field). The cusp waves (k = 1.5 k0) and the
  /// transverse ones (k0) pass; at high Froude numbers the short divergent waves near the track
  /// (k >> k0, ray angles < 16 deg for k > 3 k0), which carry the largest amplitude and hide
  /// the cusp lobe, are removed. 0: off.
  double lowpass_k0 = 0.0;
};

/// What measure_kelvin_wake found; NaN where too few profiles were usable.
struct WakeMeasurement {
  /// Outer envelope (caustic) half-angle (unit: degrees).
  double envelope_angle_deg = std::numeric_limits<double>::quiet_NaN();
  /// Angle of maximum amplitude seen from the hull (unit: degrees).
  double max_amplitude_angle_deg = std::numeric_limits<double>::quiet_NaN();
  /// Wavelength along the track (unit: m).
  double transverse_wavelength_m = std::numeric_limits<double>::quiet_NaN();
  /// Lateral profiles used per side (unit: 1).
  int profiles = 0;
  /// Distance range actually measured (unit: m).
  double s_min_m = 0.0, s_max_m = 0.0;
};

/// Measures the wake in eta (rows x cols). Allocates and plans its own FFT (not for a step).
WakeMeasurement measure_kelvin_wake(const float* eta, const WakeGrid& grid, const WakeTrack& track,
                                    const WakeOptions& opt = {});

/// Wavelength of the steady transverse wave, 2 pi / k with omega(k) = k U on the gravity
/// branch (2 pi U^2 / g in deep gravity water) (unit: m); NaN below the minimum phase speed.
double kelvin_transverse_wavelength(const Water& water, double speed_mps);

/// Half-angle of the cusp line (unit: degrees): the largest ray angle behind a source moving at
/// U, tan psi = n tan(theta) / (1 - n + tan^2 theta), n = c_g/c at the gravity-branch k with
/// c(k) = U cos(theta), maximised over theta. Deep gravity water: arcsin(1/3) = 19.47 deg at
/// any speed; finite depth widens it towards 90 deg as U -> sqrt(g h).
double kelvin_cusp_angle(const Water& water, double speed_mps);

/// A reference wake: the steady state, with Rayleigh damping mu (unit: 1/s), of ShipWaves'
/// source (eta_tt + omega^2 eta = E_tt for the hull elevation E moving at the track's velocity),
///   eta^ = -(k.v + i mu)^2 E^ / (omega^2 - (k.v + i mu)^2),
/// on a periodic rows x cols grid. Its far field is also that of a pressure patch holding a
/// depression `draft` (up to sign). For tests and validation references.
void steady_wake(const Water& water, const HullParams& hull, const WakeGrid& grid, const WakeTrack& track, double mu,
                 float* eta);

/// A Kelvin validation run: one hull started on calm water (optionally with a smooth
/// acceleration over ramp_s), moving along +x through the middle of an n x n grid of cell dx
/// with the paper's cutoff margin, through HuygensPropagator + ShipWaves, then measured.
struct KelvinCase {
  /// Dispersion of the water.
  Water water;
  /// The hull (sizes in m).
  HullParams hull;
  /// Hull speed (unit: m/s).
  double speed_mps = 1.0;
  /// Cells per side (unit: cells) and cell size (unit: m).
  int n = 512;
  double dx_m = 0.1;
  /// Absorbing margin M (unit: cells); the ship patch is the smallest even size >= 2M that fits the hull.
  int margin = 51;
  /// Full step (unit: s); at most max_cells_per_step cells of hull motion per step is used if larger.
  double dt_s = 0.05;
  /// Largest hull motion per step (unit: cells); the step is shortened to it. The ship kernels are
  /// exact for steady motion at any step (one step of dt = two of dt/2), so this only bounds the
  /// patch travel (ShipWaves::check_step allows a quarter of the patch).
  double max_cells_per_step = 1.0;
  /// Duration of a linear speed ramp from rest (unit: s); 0 starts at full speed.
  double ramp_s = 0.0;
  /// Radius around the hull outside which the far field is taken (unit: m).
  double far_radius_m = 0.03;
  /// The spatial round trip (cutoff, ship patches) every this many steps (HuygensParams::
  /// round_trip_every); 0 = auto_round_trip_every, what a scene of this grid and step gets.
  int round_trip_every = 0;
};

/// The outcome of run_kelvin_case: the measurement, the final field and where it lies.
struct KelvinRunResult {
  /// The wake measured on the final field.
  WakeMeasurement wake;
  /// Largest |eta| farther than far_radius_m from the hull, and nearer (unit: m).
  double far_max_m = 0.0, near_max_m = 0.0;
  /// Steps run (unit: 1) and distance travelled (unit: m).
  int steps = 0;
  double travelled_m = 0.0;
  /// Final first-order height on the visible region and where it lies.
  std::vector<float> eta;
  /// Where eta lies, and the ship when it was taken.
  WakeGrid grid;
  WakeTrack track;
};

/// Runs the case (allocates; seconds at n = 512) and measures the wake with s_max = D / 2.
KelvinRunResult run_kelvin_case(const KelvinCase& c, const WakeOptions& opt = {});

}  // namespace huygens
