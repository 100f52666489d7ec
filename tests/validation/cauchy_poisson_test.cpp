// The exact Cauchy-Poisson solution and the adaptive quadrature behind it.
#include "huygens/validation/reference/cauchy_poisson.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace huygens;

TEST(Quadrature, KnownIntegrals) {
  const auto q = integrate_gk15([](double x) { return std::sin(x); }, 0.0, std::numbers::pi, 1e-13);
  EXPECT_NEAR(q.value, 2.0, 1e-13);
  // an oscillatory one: int_0^50 cos(x^2/2) ... use int_0^{20 pi} x sin(x) dx = -20 pi
  const auto r = integrate_gk15([](double x) { return x * std::sin(x); }, 0.0, 20 * std::numbers::pi, 1e-10, 1);
  EXPECT_NEAR(r.value, -20 * std::numbers::pi, 1e-9);
  EXPECT_GT(r.panels, 1);  // it had to adapt from a single panel
  EXPECT_LE(r.error, 1e-10);
}

TEST(Quadrature, BesselJ0MatchesStd) {
  for (double x = 0; x < 200; x += 0.37) EXPECT_NEAR(bessel_j0(x), std::cyl_bessel_j(0.0, x), 1e-13);
}

// At t = 0 the Hankel integral gives back the Gaussian.
TEST(CauchyPoisson, InitialConditionIsTheGaussian) {
  CauchyPoissonGaussian g;
  g.sigma_m = 0.1;
  g.amplitude_m = 0.01;
  for (double r : {0.0, 0.05, 0.1, 0.2, 0.3, 0.5})
    EXPECT_NEAR(cauchy_poisson_eta(g, r, 0.0), 0.01 * std::exp(-r * r / (2 * 0.01)), 1e-12) << r;
}

// Deep gravity water at the centre against the independent power series in q = sqrt(2) g t^2 / sigma.
TEST(CauchyPoisson, CentreMatchesGravitySeries) {
  CauchyPoissonGaussian g;
  g.water.surface_tension_npm = 0.0;
  g.sigma_m = 0.1;
  g.amplitude_m = 0.01;
  for (double t : {0.02, 0.05, 0.1, 0.15}) {
    const double series = cauchy_poisson_center_gravity_series(9.81, 0.1, 0.01, t);
    EXPECT_NEAR(cauchy_poisson_eta(g, 0.0, t), series, 1e-10) << t;
  }
  // and the hump has really moved (the test can fail): at t = 0.15 s the centre has dropped
  EXPECT_LT(cauchy_poisson_center_gravity_series(9.81, 0.1, 0.01, 0.15), 0.005);
}
