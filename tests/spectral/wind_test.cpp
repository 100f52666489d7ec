// Wind sea: JONSWAP spectrum and its wavenumber-plane Jacobian, determinism by seed,
// a progressive (downwind only) sea, the realised variance, drift-free advancing, and the
// ambient sea's slopes (ambient_slopes.hpp).
#include "huygens/spectral/wind.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <vector>

#include "huygens/common/scene.hpp"
#include "huygens/spectral/ambient_slopes.hpp"
#include "huygens/spectral/stokes.hpp"

using namespace huygens;
using cd = std::complex<double>;

namespace {

constexpr double kPi = std::numbers::pi;

double integrate_omega(const WindParams& p, const Water& w) {
  // midpoint rule in log(omega) over a range holding all of the spectrum
  const double lo = std::log(0.05), hi = std::log(400.0);
  const int m = 200000;
  double s = 0;
  for (int i = 0; i < m; ++i) {
    const double om = std::exp(lo + (hi - lo) * (i + 0.5) / m);
    s += jonswap(p, w, om) * om;
  }
  return s * (hi - lo) / m;
}

// A 6 m/s wind sea towards 20 degrees on n x n points of L metres: its first-order height as the
// solver makes it (StokesHeight, first order, the wind as its only spectrum) and its ambient slopes.
struct FirstOrderSea {
  FirstOrderSea(int n_, double L_)
      : n(n_),
        L(L_),
        sea(wind(), Water{}, n, L, 0.05),
        height(Water{}, n, L, false, PlanEffort::estimate),
        slopes(wind(), Water{}, n, L),
        zero(n * n),
        W(n * n),
        eta(n * n),
        etadot(n * n) {}
  static WindParams wind() {
    WindParams p;
    p.speed_mps = 6.0;
    p.direction_deg = 20.0;
    return p;
  }
  // the height at time t into eta (unit: m)
  bool height_at(double t) {
    sea.spectrum_at(t, W.data());
    return height.compute(zero.data(), 1.0f, W.data(), eta.data(), etadot.data());
  }
  int n;
  double L;
  WindSea sea;
  StokesHeight height;
  AmbientSlopes slopes;
  std::vector<cfloat> zero, W;
  std::vector<float> eta, etadot;
};

}  // namespace

TEST(Wind, PiersonMoskowitzShapeIntegratesToClosedForm) {
  // gamma = 1: integral of alpha g^2 omega^-5 exp(-5/4 (omega_p/omega)^4) = alpha g^2 / (5 omega_p^4)
  Water w;
  WindParams p;
  p.gamma = 1.0;
  const double wp = jonswap_peak(p, w), alpha = jonswap_alpha(p, w);
  EXPECT_NEAR(integrate_omega(p, w) / (alpha * w.gravity_mps2 * w.gravity_mps2 / (5 * std::pow(wp, 4))), 1.0, 1e-6);
  // the fetch law caps at the developed sea, where omega_p is Pierson-Moskowitz's 0.855 g / U
  p.fetch_m = 1e7;
  EXPECT_NEAR(jonswap_peak(p, w) / (0.855 * w.gravity_mps2 / p.speed_mps), 1.0, 0.01);
}

TEST(Wind, WavenumberDensityHasTheRightJacobian) {
  // integral over the k-plane of F(kx, ky) equals integral S(omega) d omega, with capillarity
  Water w;
  WindParams p;
  p.speed_mps = 3.0;
  p.fetch_m = 2000.0;
  p.direction_deg = 40.0;
  const double s_omega = integrate_omega(p, w);
  // polar quadrature in log k and theta
  const double lo = std::log(0.01), hi = std::log(5000.0);
  const int mk = 6000, mt = 720;
  double s = 0;
  for (int i = 0; i < mk; ++i) {
    const double k = std::exp(lo + (hi - lo) * (i + 0.5) / mk);
    for (int j = 0; j < mt; ++j) {
      const double th = 2 * kPi * (j + 0.5) / mt;
      s += wind_density(p, w, k * std::cos(th), k * std::sin(th)) * k * k;
    }
  }
  s *= (hi - lo) / mk * 2 * kPi / mt;
  EXPECT_NEAR(s / s_omega, 1.0, 1e-3);
  // nothing travels upwind
  const double th = 40.0 * kPi / 180.0;
  EXPECT_EQ(wind_density(p, w, -std::cos(th), -std::sin(th)), 0.0);
  EXPECT_GT(wind_density(p, w, std::cos(th), std::sin(th)), 0.0);
}

TEST(Wind, SameSeedSameSea) {
  Water w;
  WindParams p;
  const int n = 64;
  WindSea a(p, w, n, 20.0, 0.05), b(p, w, n, 20.0, 0.05);
  EXPECT_EQ(std::memcmp(a.spectrum(), b.spectrum(), sizeof(cfloat) * n * n), 0);
  p.seed = 2;
  WindSea c(p, w, n, 20.0, 0.05);
  EXPECT_NE(std::memcmp(a.spectrum(), c.spectrum(), sizeof(cfloat) * n * n), 0);
  // the same physical mode gets the same random number on a grid twice as fine
  p.seed = 1;
  WindSea d(p, w, 2 * n, 20.0, 0.05);
  EXPECT_EQ(a.spectrum()[3 * n + 5], d.spectrum()[3 * 2 * n + 5]);
}

TEST(Wind, ProgressiveSeaWithTheExpectedVariance) {
  Water w;
  WindParams p;
  p.direction_deg = 30.0;
  const int n = 128;
  const double L = 40.0, dk = 2 * kPi / L;
  WindSea sea(p, w, n, L, 0.05);
  const cfloat* W = sea.spectrum();
  const double th = 30.0 * kPi / 180.0;
  // elevation of each mode from its Z^ (a = |i k/omega Z^|), realised variance sum a^2/2,
  // its expectation sum F dk^2 and the statistical spread sqrt(sum (F dk^2)^2)
  double realised = 0, sd2 = 0, ex = 0, ey = 0, mx = 0, my = 0, sx2 = 0, sy2 = 0;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const double kx = dk * fft_signed_index(c, n), ky = dk * fft_signed_index(r, n), k = std::hypot(kx, ky);
      const cd z = W[static_cast<std::size_t>(r) * n + c];
      if (z == 0.0) continue;
      EXPECT_GT(kx * std::cos(th) + ky * std::sin(th), 0.0) << "mode travels upwind";
      const double a = std::abs(z) * k / omega(w, k);
      realised += a * a / 2;
      ex += a * a * kx / k;
      ey += a * a * ky / k;
      const double v = wind_density(p, w, kx, ky) * dk * dk;
      sd2 += v * v;
      // expectation and spread of the direction sums (a^2 = 2 v |c|^2, Var |c|^2 = 1)
      mx += 2 * v * kx / k;
      my += 2 * v * ky / k;
      sx2 += 4 * v * v * kx * kx / (k * k);
      sy2 += 4 * v * v * ky * ky / (k * k);
    }
  EXPECT_GT(sea.grid_variance(), 0.0);
  EXPECT_NEAR(realised, sea.grid_variance(), 4 * std::sqrt(sd2));
  // energy-weighted direction: the grid's expected mean direction is the wind's, and the
  // realised one scatters around it within 4 standard deviations
  EXPECT_NEAR(std::atan2(my, mx) * 180 / kPi, 30.0, 1.0);
  EXPECT_NEAR(ex, mx, 4 * std::sqrt(sx2));
  EXPECT_NEAR(ey, my, 4 * std::sqrt(sy2));
  std::printf("expected direction %.2f deg, realised %.2f deg; variance %.4g (expected %.4g +- %.2g) m^2\n",
              std::atan2(my, mx) * 180 / kPi, std::atan2(ey, ex) * 180 / kPi, realised, sea.grid_variance(),
              std::sqrt(sd2));
}

TEST(Wind, AdvancingStaysOnTheExactPhase) {
  Water w;
  WindParams p;
  const int n = 32;
  WindSea sea(p, w, n, 10.0, 0.05);
  for (int i = 0; i < 300; ++i) sea.advance();  // crosses the exact resync at 256
  std::vector<cfloat> exact(static_cast<std::size_t>(n) * n);
  sea.spectrum_at(sea.time(), exact.data());
  double err = 0, ref = 0;
  for (std::size_t m = 0; m < exact.size(); ++m) {
    err += std::norm(cd(sea.spectrum()[m]) - cd(exact[m]));
    ref += std::norm(cd(exact[m]));
  }
  EXPECT_LT(std::sqrt(err / ref), 1e-5);
}

TEST(Wind, SceneBlockErrorsNameThePath) {
  const Scene s = parse_scene_text(
      R"({"solver": "huygens", "wind": {"speed_mps": 5, "direction_deg": 30, "seed": 3, "fetch_m": 500}})");
  const WindParams p = parse_wind(s.root().object("wind"));
  EXPECT_EQ(p.seed, 3u);
  EXPECT_EQ(p.fetch_m, 500.0);
  const Scene bad =
      parse_scene_text(R"({"solver": "huygens", "wind": {"speed_mps": -5, "direction_deg": 30, "seed": 3}})");
  try {
    parse_wind(bad.root().object("wind"));
    FAIL() << "negative speed accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.wind.speed_mps");
  }
}

// AmbientSlopes against the first-order height the solver makes of the same sea (StokesHeight,
// first order, the wind as its only spectrum), differentiated here by a direct DFT in double:
// d eta/dx = sum_k i kx E(k) e^{i k.x}, E = the DFT of eta / n^2 (the Nyquist modes carry no wave).
// At t = 0 and after 1000 s (the phase omega t in double), on a 32^2 grid of 100 m.
TEST(Wind, AmbientSlopesAreTheDerivativesOfTheFirstOrderHeight) {
  const int n = 32;
  const double L = 100.0;
  FirstOrderSea f(n, L);
  const std::vector<float>& eta = f.eta;
  for (const double t : {0.0, 1000.0}) {
    ASSERT_TRUE(f.height_at(t));
    const std::span<const float> s = f.slopes.compute(t);
    // E(kx, ky) = sum eta e^{-i k.x} / n^2, separably: rows first
    std::vector<cd> row(n * n), E(n * n);
    const auto e = [&](int a, int b) { return std::polar(1.0, -2 * kPi * a * b / n); };
    for (int r = 0; r < n; ++r)
      for (int kc = 0; kc < n; ++kc)
        for (int c = 0; c < n; ++c) row[r * n + kc] += double(eta[r * n + c]) * e(kc, c);
    for (int kr = 0; kr < n; ++kr)
      for (int kc = 0; kc < n; ++kc)
        for (int r = 0; r < n; ++r) E[kr * n + kc] += row[r * n + kc] * e(kr, r) / double(n * n);
    double worst = 0, largest = 0;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        cd sx = 0, sy = 0;
        for (int kr = 0; kr < n; ++kr)
          for (int kc = 0; kc < n; ++kc) {
            if (2 * kr == n || 2 * kc == n) continue;
            const cd v = E[kr * n + kc] * std::conj(e(kc, c) * e(kr, r)) * cd(0, 1);
            sx += v * fft_wavenumber(kc, n, L);
            sy += v * fft_wavenumber(kr, n, L);
          }
        worst =
            std::max({worst, std::abs(sx.real() - s[2 * (r * n + c)]), std::abs(sy.real() - s[2 * (r * n + c) + 1])});
        largest = std::max({largest, std::abs(sx.real()), std::abs(sy.real())});
      }
    EXPECT_GT(largest, 0.02) << "a sea with slopes";
    EXPECT_LT(worst, 1e-4 * largest) << "t = " << t << " s";
    std::printf("t = %g s: largest slope %.4f, largest difference %.2e\n", t, largest, worst);
  }
}

// AmbientSlopes::mean_square_slope by Parseval against the fields themselves: the spectral one is
// the mean of the computed slopes' squares, the central-difference one the mean square of
// (eta(x + dx) - eta(x - dx)) / (2 dx) (and likewise y) of the first-order height the solver makes
// of the same sea (periodic grid), at t = 0 and after 1000 s; on 64^2 points of 25 m the central
// differences resolve visibly less of a 6 m/s sea's slopes.
TEST(Wind, AmbientMeanSquareSlopeIsTheFieldsOwn) {
  const int n = 64;
  const double L = 25.0, dx = L / n;
  FirstOrderSea f(n, L);
  const AmbientSlopes& slopes = f.slopes;
  for (const double t : {0.0, 1000.0}) {
    double spectral = 0, central = 0;
    for (const float v : f.slopes.compute(t)) spectral += double(v) * v / (n * n);
    ASSERT_TRUE(f.height_at(t));
    const auto h = [&](int r, int c) { return double(f.eta[((r + n) % n) * n + (c + n) % n]); };
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c)
        central +=
            (std::pow(h(r, c + 1) - h(r, c - 1), 2) + std::pow(h(r + 1, c) - h(r - 1, c), 2)) / (4 * dx * dx * n * n);
    EXPECT_NEAR(slopes.mean_square_slope(t, false), spectral, 1e-5 * spectral) << "t = " << t << " s";
    EXPECT_NEAR(slopes.mean_square_slope(t, true), central, 1e-4 * central) << "t = " << t << " s";
    EXPECT_LT(central, 0.9 * spectral);
    std::printf("t = %g s: mean square slope %.5f spectral, %.5f central differences\n", t, spectral, central);
  }
}
