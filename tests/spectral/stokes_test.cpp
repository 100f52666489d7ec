// Second-order Stokes height of paper 004 eq. 3 and its generalisation chi^2: the
// progressive Stokes profile, first-order symmetry, the documented behaviour on a
// standing pattern, and the packed transforms against separate reference transforms.
#include "huygens/spectral/stokes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

using namespace huygens;
using cd = std::complex<double>;

namespace {

constexpr double kPi = std::numbers::pi;

struct Grid {
  int n;
  double length;
  double k(int idx) const { return fft_wavenumber(idx, n, length); }
};

// Amplitude of the Fourier mode (mx, my) of a real field: |2 FFT / N^2|.
double mode_amplitude(const std::vector<float>& f, int n, int mx, int my) {
  cd s = 0;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      s += double(f[static_cast<std::size_t>(r) * n + c]) *
           std::exp(cd(0, -2 * kPi * (double(mx) * c + double(my) * r) / n));
  return 2.0 * std::abs(s) / (double(n) * n);
}

// Spectrum (unnormalised FFTW convention, zscale = 1/N^2) of a progressive plane wave of
// elevation A cos(k.x) travelling along k = (mx, my) 2 pi / L: Z = -i omega/k A e^{i k.x}.
std::vector<cfloat> plane_wave(const Water& w, const Grid& g, int mx, int my, double amp) {
  std::vector<cfloat> z(static_cast<std::size_t>(g.n) * g.n);
  const double kx = 2 * kPi / g.length * mx, ky = 2 * kPi / g.length * my, k = std::hypot(kx, ky);
  const int c = (mx + g.n) % g.n, r = (my + g.n) % g.n;
  z[static_cast<std::size_t>(r) * g.n + c] = cfloat(cd(0, -omega(w, k) / k) * amp * double(g.n) * double(g.n));
  return z;
}

Water deep_gravity() {
  Water w;
  w.surface_tension_npm = 0.0;
  return w;
}

}  // namespace

TEST(Stokes, ProgressiveWaveCrestTroughAndHarmonic) {
  // ka = 0.1 in deep water: crest a(1 + ka/2), trough a(1 - ka/2), second harmonic k a^2 / 2.
  const Water w = deep_gravity();
  const Grid g{64, 32.0};
  for (auto [mx, my] : {std::pair{4, 0}, std::pair{3, -2}}) {
    const double k = 2 * kPi / g.length * std::hypot(mx, my), a = 0.1 / k;
    const auto z = plane_wave(w, g, mx, my, a);
    StokesHeight st(w, g.n, g.length, true, PlanEffort::estimate);
    std::vector<float> eta(z.size()), etadot(z.size());
    st.compute(z.data(), 1.0f / (g.n * g.n), nullptr, eta.data(), etadot.data());
    const double crest = *std::max_element(eta.begin(), eta.end());
    const double trough = -*std::min_element(eta.begin(), eta.end());
    // the grid samples theta = k.x at multiples of 2 pi / (n / gcd): crest and trough are on it
    EXPECT_NEAR(crest / (a * (1 + 0.05)), 1.0, 0.02);
    EXPECT_NEAR(trough / (a * (1 - 0.05)), 1.0, 0.02);
    EXPECT_NEAR(mode_amplitude(eta, g.n, 2 * mx, 2 * my) / (k * a * a / 2), 1.0, 0.02);
    EXPECT_NEAR(mode_amplitude(eta, g.n, mx, my) / a, 1.0, 1e-4);
    // etadot = a omega sin(theta) + k a^2 omega sin(2 theta)
    const double om = omega(w, k);
    EXPECT_NEAR(mode_amplitude(etadot, g.n, mx, my) / (a * om), 1.0, 1e-4);
    EXPECT_NEAR(mode_amplitude(etadot, g.n, 2 * mx, 2 * my) / (k * a * a * om), 1.0, 1e-3);
  }
}

TEST(Stokes, FirstOrderIsSymmetric) {
  const Water w = deep_gravity();
  const Grid g{64, 32.0};
  const double k = 2 * kPi / g.length * 4, a = 0.1 / k;
  const auto z = plane_wave(w, g, 4, 0, a);
  StokesHeight st(w, g.n, g.length, false, PlanEffort::estimate);
  EXPECT_EQ(st.transforms_per_call(), 1);
  std::vector<float> eta(z.size()), etadot(z.size());
  st.compute(z.data(), 1.0f / (g.n * g.n), nullptr, eta.data(), etadot.data());
  const double crest = *std::max_element(eta.begin(), eta.end());
  const double trough = -*std::min_element(eta.begin(), eta.end());
  EXPECT_NEAR(crest / a, 1.0, 1e-5);
  EXPECT_NEAR(trough / a, 1.0, 1e-5);
  EXPECT_LT(mode_amplitude(eta, g.n, 8, 0), 1e-6 * a);
}

TEST(Stokes, StandingPatternGivesSpuriousMeanAndHalfHarmonic) {
  // A cos(kx) released from rest (+k and -k together): eta2 = (k A^2/4)(1 + cos 2kx) at t = 0,
  // i.e. a uniform mean of k A^2/4 (spurious: mass is not conserved) and a second harmonic of
  // k A^2/4, half the progressive value. This is what the chi^2 generalisation does.
  const Water w = deep_gravity();
  const Grid g{64, 32.0};
  const int m = 4;
  const double k = 2 * kPi / g.length * m, a = 0.1 / k;
  std::vector<cfloat> z(static_cast<std::size_t>(g.n) * g.n);
  // E^ of A cos(kx): A N^2 / 2 at +k and -k; Z^ = -i omega/k E^
  const cfloat v = cfloat(cd(0, -omega(w, k) / k) * a * 0.5 * double(g.n) * double(g.n));
  z[m] = v;
  z[g.n - m] = v;
  StokesHeight st(w, g.n, g.length, true, PlanEffort::estimate);
  std::vector<float> eta(z.size()), etadot(z.size());
  st.compute(z.data(), 1.0f / (g.n * g.n), nullptr, eta.data(), etadot.data());
  double mean = 0;
  for (float e : eta) mean += e;
  mean /= double(eta.size());
  EXPECT_NEAR(mean / (k * a * a / 4), 1.0, 1e-3);
  EXPECT_NEAR(mode_amplitude(eta, g.n, 2 * m, 0) / (k * a * a / 4), 1.0, 1e-3);
  EXPECT_NEAR(mode_amplitude(eta, g.n, m, 0) / a, 1.0, 1e-4);
}

TEST(Stokes, PackedTransformsMatchSeparateReferences) {
  // A random complex field: eta, etadot from the packed transforms equal separate double
  // precision evaluations of Re IFFT[i k/omega Z^] + Re(chi^2) and Re IFFT[k Z^] + Re(2 chi chidot).
  Water w;  // gravity-capillary
  const Grid g{32, 0.5};
  const int n = g.n;
  std::mt19937 rng(7);
  std::normal_distribution<double> nd;
  std::vector<cfloat> z(static_cast<std::size_t>(n) * n), extra(z.size());
  for (auto& v : z) v = cfloat(float(nd(rng)), float(nd(rng)));
  for (auto& v : extra) v = cfloat(float(0.01 * nd(rng)), float(0.01 * nd(rng)));
  const float zscale = 1e-3f;
  StokesHeight st(w, n, g.length, true, PlanEffort::estimate);
  EXPECT_EQ(st.transforms_per_call(), 3);
  std::vector<float> eta(z.size()), etadot(z.size());
  EXPECT_TRUE(st.compute(z.data(), zscale, extra.data(), eta.data(), etadot.data()));
  // direct double-precision inverse DFTs
  double err_e = 0, err_d = 0, ref_e = 0, ref_d = 0;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      cd e1 = 0, d1 = 0, chi = 0, chid = 0;
      for (int q = 0; q < n; ++q)
        for (int p = 0; p < n; ++p) {
          const double kx = g.k(p), ky = g.k(q), k = std::hypot(kx, ky);
          if (k == 0) continue;
          const double om = omega(w, k);
          const std::size_t m = static_cast<std::size_t>(q) * n + p;
          const cd y = cd(z[m]) * double(zscale) + cd(extra[m]);
          const cd ph = std::exp(cd(0, 2 * kPi * (double(p) * c + double(q) * r) / n));
          e1 += cd(0, k / om) * y * ph;
          d1 += k * y * ph;
          chi += cd(0, std::pow(k, 1.5) / (std::sqrt(2.0) * om)) * y * ph;
          chid += std::pow(k, 1.5) / std::sqrt(2.0) * y * ph;
        }
      const double e = e1.real() + (chi * chi).real(), d = d1.real() + (2.0 * chi * chid).real();
      const std::size_t m = static_cast<std::size_t>(r) * n + c;
      err_e += (eta[m] - e) * (eta[m] - e);
      err_d += (etadot[m] - d) * (etadot[m] - d);
      ref_e += e * e;
      ref_d += d * d;
    }
  EXPECT_LT(std::sqrt(err_e / ref_e), 1e-5);
  EXPECT_LT(std::sqrt(err_d / ref_d), 1e-5);
}

TEST(Stokes, ReportsNonFiniteOutput) {
  Water w;
  const int n = 16;
  std::vector<cfloat> z(static_cast<std::size_t>(n) * n);
  std::vector<float> eta(z.size()), etadot(z.size());
  for (bool second : {false, true}) {
    StokesHeight st(w, n, 1.0, second, PlanEffort::estimate);
    z[3] = cfloat(1.0f, 0.0f);
    EXPECT_TRUE(st.compute(z.data(), 1.0f, nullptr, eta.data(), etadot.data()));
    z[3] = cfloat(std::numeric_limits<float>::quiet_NaN(), 0.0f);
    EXPECT_FALSE(st.compute(z.data(), 1.0f, nullptr, eta.data(), etadot.data()));
  }
}
