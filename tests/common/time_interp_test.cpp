// Cubic Hermite time interpolation (paper 004 section 3): the paper's weights at s = 1/3
// exactly, exactness for cubics, and the dt^4 error law on a wind sea whose true states are
// evaluated analytically in the spectral domain (with the second-order Stokes height).
#include "huygens/common/time_interp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "huygens/spectral/stokes.hpp"
#include "huygens/spectral/wind.hpp"

using namespace huygens;

TEST(TimeInterp, PaperWeightsAtOneThirdExactly) {
  const HermiteWeights w = hermite_weights(1, 3);
  EXPECT_EQ(w.e0, 20.0 / 27.0);
  EXPECT_EQ(w.e1, 7.0 / 27.0);
  EXPECT_EQ(w.d0, 4.0 / 27.0);
  EXPECT_EQ(w.d1, -2.0 / 27.0);
  // and by symmetry at s = 2/3
  const HermiteWeights v = hermite_weights(2, 3);
  EXPECT_EQ(v.e0, 7.0 / 27.0);
  EXPECT_EQ(v.e1, 20.0 / 27.0);
  EXPECT_EQ(v.d0, 2.0 / 27.0);
  EXPECT_EQ(v.d1, -4.0 / 27.0);
  // the real-valued form agrees to rounding; end points reproduce the states
  const HermiteWeights d = hermite_weights(1.0 / 3.0);
  EXPECT_NEAR(d.e0, 20.0 / 27.0, 1e-15);
  EXPECT_NEAR(d.d1, -2.0 / 27.0, 1e-15);
  const HermiteWeights e = hermite_weights(0.0), f = hermite_weights(1.0);
  EXPECT_EQ(e.e0, 1.0);
  EXPECT_EQ(e.d0, 0.0);
  EXPECT_EQ(f.e1, 1.0);
  EXPECT_EQ(f.d1, 0.0);
}

TEST(TimeInterp, ExactForCubics) {
  // eta(t) = c0 + c1 t + c2 t^2 + c3 t^3 per element, any s in [0, 1]
  const std::size_t n = 1000;
  const double t0 = 0.3, dt = 0.05;
  std::vector<float> e0(n), d0(n), e1(n), d1(n), out(n);
  std::vector<double> c(4 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int j = 0; j < 4; ++j) c[4 * i + j] = std::sin(1.7 * double(i) + j) * (j + 1);
  auto eta = [&](std::size_t i, double t) {
    return c[4 * i] + t * (c[4 * i + 1] + t * (c[4 * i + 2] + t * c[4 * i + 3]));
  };
  auto etad = [&](std::size_t i, double t) { return c[4 * i + 1] + t * (2 * c[4 * i + 2] + 3 * t * c[4 * i + 3]); };
  for (std::size_t i = 0; i < n; ++i) {
    e0[i] = float(eta(i, t0));
    d0[i] = float(etad(i, t0));
    e1[i] = float(eta(i, t0 + dt));
    d1[i] = float(etad(i, t0 + dt));
  }
  for (double s : {0.0, 0.1, 1.0 / 3.0, 0.5, 0.77, 1.0}) {
    hermite_interpolate(e0.data(), d0.data(), e1.data(), d1.data(), n, hermite_weights(s), dt, out.data());
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::abs(out[i] - eta(i, t0 + s * dt)));
    EXPECT_LT(worst, 4e-6) << "s " << s;
  }
}

TEST(TimeInterp, WindSeaErrorFallsAsDtToTheFourth) {
  // True states: W^(t) = W^(0) e^{-i omega t} exactly, height by the second-order Stokes stage.
  // Interpolated frames at s = 1/3 and 2/3 against the true frames at those times.
  Water w;
  WindParams p;
  const int n = 64;
  const double L = 30.0;
  WindSea sea(p, w, n, L, 0.05);
  StokesHeight st(w, n, L, true, PlanEffort::estimate);
  const std::size_t nn = static_cast<std::size_t>(n) * n;
  std::vector<cfloat> spec(nn), zero(nn);
  auto state = [&](double t, std::vector<float>& eta, std::vector<float>& etad) {
    sea.spectrum_at(t, spec.data());
    st.compute(zero.data(), 0.0f, spec.data(), eta.data(), etad.data());
  };
  std::vector<float> e0(nn), d0(nn), e1(nn), d1(nn), et(nn), dt_(nn), out(nn);
  const double t0 = 1.234;
  state(t0, e0, d0);
  double rms = 0;
  for (float v : e0) rms += double(v) * v;
  rms = std::sqrt(rms / double(nn));
  std::vector<double> dts = {0.16, 0.08, 0.04, 0.02}, errs;
  for (double dt : dts) {
    state(t0 + dt, e1, d1);
    double e2 = 0;
    for (int j = 1; j <= 2; ++j) {
      state(t0 + j * dt / 3, et, dt_);
      hermite_interpolate(e0.data(), d0.data(), e1.data(), d1.data(), nn, hermite_weights(j, 3), dt, out.data());
      for (std::size_t i = 0; i < nn; ++i) e2 += double(out[i] - et[i]) * (out[i] - et[i]);
    }
    errs.push_back(std::sqrt(e2 / double(2 * nn)));
  }
  // least-squares slope of log error against log dt
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < dts.size(); ++i) {
    const double x = std::log(dts[i]), y = std::log(errs[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double m = double(dts.size());
  const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  std::printf("wind sea (U = 5 m/s, n = %d, L = %g m), rms height %.4g m\n", n, L, rms);
  for (std::size_t i = 0; i < dts.size(); ++i)
    std::printf("  dt %.4f s: rms interpolation error %.3g m (%.3g %% of rms height)\n", dts[i], errs[i],
                100 * errs[i] / rms);
  std::printf("  slope %.3f\n", slope);
  EXPECT_GT(slope, 3.5);
  EXPECT_LT(slope, 4.5);
  // at the default dt = 3 / 60 s the error is below 1 % of the rms height
  state(t0 + 0.05, e1, d1);
  double e2 = 0;
  state(t0 + 0.05 / 3, et, dt_);
  hermite_interpolate(e0.data(), d0.data(), e1.data(), d1.data(), nn, hermite_weights(1, 3), 0.05, out.data());
  for (std::size_t i = 0; i < nn; ++i) e2 += double(out[i] - et[i]) * (out[i] - et[i]);
  std::printf("  default dt 0.05 s: rms error %.3g %% of rms height\n", 100 * std::sqrt(e2 / double(nn)) / rms);
  EXPECT_LT(std::sqrt(e2 / double(nn)), 0.01 * rms);
}
