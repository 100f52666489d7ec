// The Kelvin-wake measurement (kelvin.hpp) on reference wakes: the steady linear wake of the
// ShipWaves source computed in the Fourier domain with a small Rayleigh damping. Deep gravity
// water must give the cusp half-angle arcsin(1/3) and the transverse wavelength 2 pi U^2 / g;
// finite depth (U = 0.8 sqrt(g h)) must give the wider angle the dispersion relation predicts
// (so the measurement follows the pattern, not a built-in number). Very near the critical
// speed (0.9 sqrt(g h), theory 34.6 deg) the method reads 28.8 deg on this grid: the long
// cusp waves need far larger distances; that regime is not claimed.
#include "huygens/validation/reference/kelvin.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

using namespace huygens;

namespace {

WakeMeasurement measure_reference(const Water& w, double froude, WakeGrid& g, WakeTrack& t, double search_deg = 30.0) {
  HullParams h;  // 1 m x 0.3 m x 0.05 m
  const double u = froude * std::sqrt(w.gravity_mps2 * h.length_m);
  const double lam = 2 * std::numbers::pi * u * u / w.gravity_mps2;
  g.rows = search_deg > 30 ? 1024 : 512;
  g.cols = 1024;
  g.dx_m = std::max(lam, h.length_m) / 16;
  t.speed_mps = u;
  t.heading_rad = 0.0;
  t.x_m = 0.85 * g.cols * g.dx_m;
  t.y_m = 0.5 * g.rows * g.dx_m;
  std::vector<float> eta(static_cast<std::size_t>(g.rows) * g.cols);
  steady_wake(w, h, g, t, 0.005 * w.gravity_mps2 / u, eta.data());
  WakeOptions o;
  o.s_max_m = 0.6 * g.cols * g.dx_m;
  o.search_angle_deg = search_deg;
  return measure_kelvin_wake(eta.data(), g, t, o);
}

}  // namespace

TEST(Kelvin, CuspAngleFromDispersion) {
  Water w;
  w.surface_tension_npm = 0;
  EXPECT_NEAR(kelvin_cusp_angle(w, 1.0), std::asin(1.0 / 3.0) * 180 / std::numbers::pi, 1e-3);
  EXPECT_NEAR(kelvin_transverse_wavelength(w, 1.3) / (2 * std::numbers::pi * 1.69 / 9.81), 1.0, 1e-9);
  w.depth_m = 1.0;
  EXPECT_GT(kelvin_cusp_angle(w, 0.9 * std::sqrt(9.81)), 25.0);
  Water cap;  // below the minimum phase speed nothing is stationary
  EXPECT_TRUE(std::isnan(kelvin_transverse_wavelength(cap, 0.2)));
}

TEST(Kelvin, MeasuresDeepWaterReferenceWakes) {
  Water w;
  w.surface_tension_npm = 0;
  for (double fr : {0.3, 0.4, 0.5}) {
    WakeGrid g;
    WakeTrack t;
    const WakeMeasurement m = measure_reference(w, fr, g, t);
    const double lam = kelvin_transverse_wavelength(w, t.speed_mps);
    std::printf(
        "Fr %.1f: envelope %.3f deg (19.471), max amplitude %.2f deg, transverse %.4f m (%.4f), %d profiles over "
        "%.1f-%.1f m\n",
        fr, m.envelope_angle_deg, m.max_amplitude_angle_deg, m.transverse_wavelength_m, lam, m.profiles, m.s_min_m,
        m.s_max_m);
    EXPECT_NEAR(m.envelope_angle_deg, 19.4712, 0.5) << "Fr " << fr;
    EXPECT_NEAR(m.transverse_wavelength_m / lam, 1.0, 0.02) << "Fr " << fr;
    EXPECT_GT(m.profiles, 100);
  }
}

TEST(Kelvin, FollowsTheWiderFiniteDepthWedge) {
  const double kDepthFroude = 0.8;
  // depth Froude number U / sqrt(g h) = 0.8: the cusp opens to 24.3 deg
  Water w;
  w.surface_tension_npm = 0;
  w.depth_m = 1.0;
  const double fr = kDepthFroude * std::sqrt(w.gravity_mps2 * w.depth_m) /
                    std::sqrt(w.gravity_mps2 * 1.0);  // hull Froude number of that speed
  WakeGrid g;
  WakeTrack t;
  const WakeMeasurement m = measure_reference(w, fr, g, t, 45.0);
  const double expect = kelvin_cusp_angle(w, t.speed_mps);
  std::printf("finite depth, U = 0.8 sqrt(g h): envelope %.3f deg, theory %.3f deg\n", m.envelope_angle_deg, expect);
  EXPECT_GT(expect, 23.0);
  EXPECT_NEAR(m.envelope_angle_deg, expect, 0.5);
}

TEST(Kelvin, PropagatorWakeAtFroude04) {
  // The full pipeline (HuygensPropagator + ShipWaves, paper cutoff) on a cheap grid: a 1 m hull
  // at Fr 0.4 started from rest, n = 256 with 8 cells per transverse wavelength, measured over
  // 3 wavelengths to half the distance travelled. Issue 3 validation 1 at reduced size.
  KelvinCase c;
  c.water.surface_tension_npm = 0.0;
  c.speed_mps = 0.4 * std::sqrt(c.water.gravity_mps2 * c.hull.length_m);
  const double lam = kelvin_transverse_wavelength(c.water, c.speed_mps);
  c.n = 256;
  c.dx_m = lam / 8;
  c.margin = 25;
  c.dt_s = 0.05;
  const KelvinRunResult r = run_kelvin_case(c);
  std::printf(
      "propagator, Fr 0.4, n 256: envelope %.3f deg, max amplitude %.2f deg, transverse %.4f m (%.4f), "
      "%d steps, %.1f m travelled, measured %.1f-%.1f m\n",
      r.wake.envelope_angle_deg, r.wake.max_amplitude_angle_deg, r.wake.transverse_wavelength_m, lam, r.steps,
      r.travelled_m, r.wake.s_min_m, r.wake.s_max_m);
  EXPECT_NEAR(r.wake.envelope_angle_deg, 19.4712, 0.5);
  EXPECT_NEAR(r.wake.transverse_wavelength_m / lam, 1.0, 0.02);
}

TEST(Kelvin, LowPassRecoversTheEnvelopeAtHighFroude) {
  // The steady reference wake at Fr 2 (lambda = 25 m) on 2048 x 4096 cells of 0.4 m (819 m x
  // 1638 m), measured between 5 and 20 wavelengths behind the hull. The short divergent waves near
  // the track (k >> g/U^2) carry the largest amplitude there: on the full field the outermost
  // strong lobe is not the cusp (13.4 deg). Low-passed at 3 g/U^2 (WakeOptions::lowpass_k0) the
  // envelope reads arcsin(1/3) again (19.25 deg). Nearer, at 1.6-3.2 wavelengths (the range the
  // froude_trend validation can afford), the same reference reads 18.6 deg: that is the method's
  // own bias at short range, printed here and reported with the validation.
  Water w;
  w.surface_tension_npm = 0;
  HullParams h;
  WakeGrid g;
  WakeTrack t;
  const double u = 2.0 * std::sqrt(w.gravity_mps2 * h.length_m);
  const double lam = kelvin_transverse_wavelength(w, u);
  g.rows = 2048;
  g.cols = 4096;
  g.dx_m = 0.4;
  t.speed_mps = u;
  t.x_m = 0.95 * g.cols * g.dx_m;
  t.y_m = 0.5 * g.rows * g.dx_m;
  std::vector<float> eta(static_cast<std::size_t>(g.rows) * g.cols);
  steady_wake(w, h, g, t, 0.005 * w.gravity_mps2 / u, eta.data());
  WakeOptions o;
  o.s_min_m = 5 * lam;
  o.s_max_m = 20 * lam;
  const WakeMeasurement full = measure_kelvin_wake(eta.data(), g, t, o);
  o.lowpass_k0 = 3.0;
  const WakeMeasurement low = measure_kelvin_wake(eta.data(), g, t, o);
  o.s_min_m = 1.6 * lam;
  o.s_max_m = 3.2 * lam;
  const WakeMeasurement near = measure_kelvin_wake(eta.data(), g, t, o);
  std::printf(
      "Fr 2 reference, 5-20 lambda: envelope %.3f deg full field, %.3f deg low-passed (1.6-3.2 lambda: %.3f); "
      "max amplitude %.2f / %.2f deg; transverse %.3f / %.3f m (%.3f)\n",
      full.envelope_angle_deg, low.envelope_angle_deg, near.envelope_angle_deg, full.max_amplitude_angle_deg,
      low.max_amplitude_angle_deg, full.transverse_wavelength_m, low.transverse_wavelength_m, lam);
  EXPECT_NEAR(low.envelope_angle_deg, 19.4712, 0.5);
  EXPECT_NEAR(low.transverse_wavelength_m / lam, 1.0, 0.02);
  EXPECT_GT(std::abs(full.envelope_angle_deg - 19.4712), 3.0) << "the full field hides the cusp (why the low-pass)";
  EXPECT_EQ(low.max_amplitude_angle_deg, full.max_amplitude_angle_deg);  // read on the full field either way
  EXPECT_LT(low.max_amplitude_angle_deg, 10.0);                          // inside the wedge (Rabaud-Moisy regime)
}
