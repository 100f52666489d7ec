// Dispersion relation of paper 004 section 3 against its closed-form limits.
#include "huygens/common/dispersion.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace huygens;

TEST(Dispersion, DeepGravityLimit) {
  Water w;
  w.surface_tension_npm = 0;
  for (double k : {0.01, 0.1, 1.0, 10.0}) EXPECT_NEAR(omega(w, k), std::sqrt(9.81 * k), 1e-12 * std::sqrt(9.81 * k));
  // deep-water gravity waves: group speed is half the phase speed
  EXPECT_NEAR(group_speed(w, 2.0), 0.5 * phase_speed(w, 2.0), 1e-12);
}

TEST(Dispersion, CapillaryLimit) {
  Water w;
  w.gravity_mps2 = 0;
  const double k = 5000.0;
  EXPECT_NEAR(omega(w, k), std::sqrt(0.072 / 1000.0 * k * k * k), 1e-9 * omega(w, k));
  // capillary waves: group speed is 3/2 of the phase speed
  EXPECT_NEAR(group_speed(w, k), 1.5 * phase_speed(w, k), 1e-9 * phase_speed(w, k));
}

TEST(Dispersion, MinimumPhaseSpeed) {
  Water w;
  // (4 g sigma / rho)^(1/4) = 0.2306 m/s at lambda = 2 pi sqrt(sigma / (rho g)) = 1.702 cm
  // for sigma = 0.072 N/m (docs/design.md rounds these to 0.231 m/s and 1.71 cm).
  EXPECT_NEAR(min_phase_speed(w), 0.23055, 1e-5);
  const double km = min_phase_speed_wavenumber(w);
  EXPECT_NEAR(2 * M_PI / km, 0.017022, 1e-6);
  // a brute-force scan of c(k) finds the same minimum
  double best_k = 0, best_c = 1e9;
  for (double k = 100; k < 1000; k += 0.01)
    if (phase_speed(w, k) < best_c) best_c = phase_speed(w, k), best_k = k;
  EXPECT_NEAR(best_k, km, 0.02);
  EXPECT_NEAR(best_c, min_phase_speed(w), 1e-9);
  // c(k) has its minimum there, and c(km) = c_min; at the minimum c_g = c.
  EXPECT_NEAR(phase_speed(w, km), min_phase_speed(w), 1e-12);
  EXPECT_LT(phase_speed(w, km), phase_speed(w, 0.9 * km));
  EXPECT_LT(phase_speed(w, km), phase_speed(w, 1.1 * km));
  EXPECT_NEAR(group_speed(w, km), phase_speed(w, km), 1e-9);
}

TEST(Dispersion, FiniteDepth) {
  Water w;
  w.surface_tension_npm = 0;
  w.depth_m = 2.0;
  // shallow limit: c -> sqrt(g h)
  EXPECT_NEAR(phase_speed(w, 1e-4), std::sqrt(9.81 * 2.0), 1e-6);
  EXPECT_NEAR(group_speed(w, 1e-4), std::sqrt(9.81 * 2.0), 1e-5);
  // kh = 0.5: omega^2 = g k tanh(kh)
  const double k = 0.25;
  EXPECT_NEAR(omega(w, k), std::sqrt(9.81 * k * std::tanh(0.5)), 1e-12);
  // group speed equals a centred difference of omega
  const double h = 1e-5;
  EXPECT_NEAR(group_speed(w, k), (omega(w, k + h) - omega(w, k - h)) / (2 * h), 1e-7);
  Water wc;  // with capillarity, finite depth
  wc.depth_m = 0.01;
  EXPECT_NEAR(group_speed(wc, 300.0), (omega(wc, 300.0 + h) - omega(wc, 300.0 - h)) / (2 * h), 1e-6);
}
