// Ship waves of paper 004 eq. 2: the kernels' rigid-translation identity, alpha -> 0,
// no waves from a stationary hull, step-size consistency, sub-cell positions, paths.
#include "huygens/spectral/ship_waves.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "huygens/common/scene.hpp"
#include "huygens/spectral/propagator.hpp"

using namespace huygens;
using cd = std::complex<double>;

namespace {

constexpr double kPi = std::numbers::pi;

// The exact integral over the step of the time derivative of a rigidly translating profile,
// int_0^1 e^{-i w (1-u)} d/du[e^{-i beta u}] du, by composite Simpson's rule.
cd integral_of_derivative(double beta, double w) {
  const int m = 20000;
  cd sum = 0;
  for (int j = 0; j <= m; ++j) {
    const double u = static_cast<double>(j) / m;
    const cd f = std::exp(cd(0, -w * (1 - u))) * cd(0, -beta) * std::exp(cd(0, -beta * u));
    sum += f * static_cast<double>(j == 0 || j == m ? 1 : (j % 2 ? 4 : 2));
  }
  return sum / (3.0 * m);
}

// A small periodic propagator for the tests: z <- IFFT[FFT[z] e^{-i omega dt}] / N^2.
struct Propagator {
  int n;
  AlignedBuffer<cfloat> buf;
  AlignedBuffer<cfloat> mult;
  Fft2D fwd, inv;
  Propagator(const Water& w, int n_, double length, double dt)
      : n(n_),
        buf(static_cast<std::size_t>(n_) * n_),
        mult(static_cast<std::size_t>(n_) * n_),
        fwd(n_, n_, buf.data(), buf.data(), Fft2D::forward, PlanEffort::estimate),
        inv(n_, n_, buf.data(), buf.data(), Fft2D::backward, PlanEffort::estimate) {
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const double kx = fft_wavenumber(c, n, length), ky = fft_wavenumber(r, n, length);
        mult[static_cast<std::size_t>(r) * n + c] =
            cfloat(std::exp(cd(0, -omega(w, std::hypot(kx, ky)) * dt)) / (double(n) * n));
      }
  }
  void step(std::vector<cfloat>& z) {
    std::copy(z.begin(), z.end(), buf.data());
    fwd.execute();
    for (std::size_t i = 0; i < z.size(); ++i) buf[i] *= mult[i];
    inv.execute();
    std::copy(buf.data(), buf.data() + z.size(), z.begin());
  }
};

double l2(const std::vector<cfloat>& a) {
  double s = 0;
  for (const cfloat& v : a) s += std::norm(std::complex<double>(v));
  return std::sqrt(s);
}
double l2_diff(const std::vector<cfloat>& a, const std::vector<cfloat>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += std::norm(std::complex<double>(a[i]) - std::complex<double>(b[i]));
  return std::sqrt(s);
}

Ship straight_ship(double y, double speed, double x0 = 4.0) {
  Ship s;
  // starts long before t = 0 so every step lies inside one segment
  s.path = ShipPath({{-100.0, x0 - 100.0 * speed, y}, {100.0, x0 + 100.0 * speed, y}});
  return s;
}

}  // namespace

TEST(ShipKernels, RigidTranslationIdentity) {
  // Phi1^ + Phi2^ e^{-i beta} = beta (e^{-i beta} - e^{-i w}) / (beta - w), and that is the exact
  // integral over the step of the time derivative of the profile (docs/design.md 3.3).
  const double cases[][2] = {{0.3, 1.1}, {-2.0, 0.7}, {5.0, 4.9999}, {1.0, 1.0}, {0.0, 2.0}, {3.0, 0.1}, {-0.2, 6.0}};
  for (const auto& c : cases) {
    const double beta = c[0], w = c[1];
    cd phi1, phi2;
    ship_kernels(beta, w, phi1, phi2);
    const cd lhs = phi1 + phi2 * std::exp(cd(0, -beta));
    const cd closed = ship_translation_factor(beta, w);
    EXPECT_LT(std::abs(lhs - closed), 1e-12) << "beta " << beta << " w " << w;
    EXPECT_LT(std::abs(closed - integral_of_derivative(beta, w)), 1e-9) << "beta " << beta << " w " << w;
  }
}

TEST(ShipKernels, StableAsAlphaGoesToZero) {
  const double w = 1.3;
  // exact limits at alpha = 0: (e^{-/+ i a} +/- i a - 1)/a^2 -> -1/2
  cd phi1, phi2;
  ship_kernels(w, w, phi1, phi2);
  EXPECT_LT(std::abs(phi1 - std::exp(cd(0, -w)) * (-1.0 - cd(0, w / 2))), 1e-15);
  EXPECT_LT(std::abs(phi2 - (1.0 - cd(0, w / 2))), 1e-15);
  // continuity across the series/direct switch and against long-double direct formulas
  for (double a : {1e-12, 1e-8, 1e-4, 0.1, 0.3, 0.4999999, 0.5000001, 0.8}) {
    ship_kernels(w + a, w, phi1, phi2);
    const long double A = a;
    const std::complex<long double> ea = std::exp(std::complex<long double>(0, -A));
    const std::complex<long double> g1 = (ea + std::complex<long double>(0, A) - 1.0L) / (A * A);
    const std::complex<long double> eb = std::exp(std::complex<long double>(0, A));
    const std::complex<long double> g2 = (eb - std::complex<long double>(0, A) - 1.0L) / (A * A);
    const cd ref1 = std::exp(cd(0, -w)) * (-1.0 + cd(0, w) * cd(g1));
    const cd ref2 = 1.0 + cd(0, w) * cd(g2);
    // long double loses ~eps_ld / a^2 to cancellation: compare only where that is small
    const double tol = std::max(1e-13, 1e-19 / (a * a) * 10);
    if (tol < 1e-6) {
      EXPECT_LT(std::abs(phi1 - ref1), tol) << "alpha " << a;
      EXPECT_LT(std::abs(phi2 - ref2), tol) << "alpha " << a;
    }
    EXPECT_TRUE(std::isfinite(phi1.real()) && std::isfinite(phi2.imag()));
  }
}

TEST(ShipKernels, HullSpectrumIsHalfEllipsoidVolume) {
  HullParams h;
  h.length_m = 2.0;
  h.beam_m = 0.5;
  h.draft_m = 0.1;
  // k = 0: the displaced volume (2/3) pi a b draft
  EXPECT_NEAR(hull_spectrum(h, 0, 0, 0.3), 2.0 / 3.0 * kPi * 1.0 * 0.25 * 0.1, 1e-14);
  // the spectrum rotates with the heading
  EXPECT_NEAR(hull_spectrum(h, 3.0, 0.0, 0.0), hull_spectrum(h, 0.0, 3.0, kPi / 2), 1e-14);
  // direct 2D quadrature of draft sqrt(1 - (x/a)^2 - (y/b)^2) e^{-i k x} (no blur)
  h.blur_m = 0.0;
  const double kx = 2.5;
  double sum = 0;
  const int m = 800;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const double x = -1.0 + 2.0 * (i + 0.5) / m, y = -0.25 + 0.5 * (j + 0.5) / m;
      const double r = 1 - x * x - y * y / 0.0625;
      if (r > 0) sum += 0.1 * std::sqrt(r) * std::cos(kx * x) * (2.0 / m) * (0.5 / m);
    }
  EXPECT_NEAR(hull_spectrum(h, kx, 0, 0), sum, 2e-5);
}

TEST(ShipPath, PositionVelocityHeading) {
  ShipPath p({{0, 0, 0}, {2, 4, 0}, {3, 4, 0}, {5, 4, 2}});
  double x, y, vx, vy;
  p.position(1.0, x, y);
  EXPECT_DOUBLE_EQ(x, 2.0);
  p.position(-1.0, x, y);
  EXPECT_DOUBLE_EQ(x, 0.0);
  p.position(9.0, x, y);
  EXPECT_DOUBLE_EQ(y, 2.0);
  p.velocity(1.0, vx, vy);
  EXPECT_DOUBLE_EQ(vx, 2.0);
  p.velocity(2.5, vx, vy);
  EXPECT_EQ(vx, 0.0);
  EXPECT_DOUBLE_EQ(p.heading(2.5), 0.0);      // resting segment keeps the last heading
  EXPECT_DOUBLE_EQ(p.heading(4.0), kPi / 2);  // turned towards +y
  EXPECT_DOUBLE_EQ(p.heading(10.0), kPi / 2);
  p.step_velocity(1.5, 1.0, vx, vy);  // spans the corner at t = 2: chord velocity
  EXPECT_DOUBLE_EQ(vx, 1.0);
  EXPECT_THROW(ShipPath({{1, 0, 0}, {0, 1, 0}}), std::invalid_argument);
  EXPECT_THROW(p.append({4.0, 0, 0}), std::invalid_argument);
}

TEST(ShipWaves, PatchSpectrumIsTheRigidTranslationFormula) {
  Water w;
  const int n = 128, P = 64;
  const double L = 16.0, dt = 0.05;
  ShipWaves sw(w, n, L, P, {straight_ship(7.3, 1.1)}, PlanEffort::estimate);
  std::vector<cfloat> spec(static_cast<std::size_t>(P) * P);
  int r0, c0;
  const double t = 0.37;
  sw.patch_spectrum(0, t, dt, spec.data(), r0, c0);
  const double dx = L / n;
  const double x0 = 4.0 + 1.1 * t, y0 = 7.3;
  const double dxs = x0 - c0 * dx, dys = y0 - r0 * dx;
  double err = 0, ref = 0;
  for (int r = 0; r < P; ++r)
    for (int c = 0; c < P; ++c) {
      const double kx = fft_wavenumber(c, P, P * dx), ky = fft_wavenumber(r, P, P * dx);
      const double k = std::hypot(kx, ky);
      if (k == 0) continue;
      const double om = omega(w, k);
      const cd expect = cd(0, -om / k) * ship_translation_factor(kx * 1.1 * dt, om * dt) *
                        hull_spectrum(HullParams{}, kx, ky, 0.0) * std::exp(cd(0, -(kx * dxs + ky * dys))) /
                        (dx * dx * P * P);
      err += std::norm(cd(spec[static_cast<std::size_t>(r) * P + c]) - expect);
      ref += std::norm(expect);
    }
  EXPECT_LT(std::sqrt(err / ref), 1e-5);
}

TEST(ShipWaves, StationaryHullMakesNoWaves) {
  Water w;
  const int n = 128, P = 64;
  const double L = 16.0, dt = 0.05;
  Ship still;
  still.path = ShipPath({{0.0, 8.03, 7.71}});
  ShipWaves rest(w, n, L, P, {still}, PlanEffort::estimate);
  ShipWaves moving(w, n, L, P, {straight_ship(7.71, 1.0)}, PlanEffort::estimate);
  std::vector<cfloat> z0(static_cast<std::size_t>(n) * n), z1(z0.size());
  Propagator prop(w, n, L, dt);
  for (int s = 0; s < 20; ++s) {
    prop.step(z0);
    rest.add(z0.data(), s * dt, dt);
    prop.step(z1);
    moving.add(z1.data(), s * dt, dt);
  }
  // float rounding of Phi1 + Phi2 = 0 is all that remains
  EXPECT_LT(l2(z0), 1e-5 * l2(z1));
  EXPECT_GT(l2(z1), 0.0);
}

TEST(ShipWaves, OneStepEqualsTwoHalfSteps) {
  // Steady motion: 8 steps of dt against 16 steps of dt/2 on the same grid, propagated
  // exactly in between; relative L2 difference under 1 %.
  Water w;
  const int n = 256, P = 128;
  const double L = 32.0, dt = 0.1;
  const std::vector<Ship> ships = {straight_ship(16.2, 1.2, 12.0)};
  ShipWaves a(w, n, L, P, ships, PlanEffort::estimate), b(w, n, L, P, ships, PlanEffort::estimate);
  std::vector<cfloat> za(static_cast<std::size_t>(n) * n), zb(za.size());
  Propagator pa(w, n, L, dt), pb(w, n, L, dt / 2);
  for (int s = 0; s < 8; ++s) {
    pa.step(za);
    a.add(za.data(), s * dt, dt);
    for (int h = 0; h < 2; ++h) {
      pb.step(zb);
      b.add(zb.data(), s * dt + h * dt / 2, dt / 2);
    }
  }
  const double rel = l2_diff(za, zb) / l2(za);
  std::printf("one step of dt vs two of dt/2 after 8 steps: relative L2 %.3g\n", rel);
  EXPECT_LT(rel, 0.01);
  EXPECT_EQ(a.kernel_rebuilds(), 1u);  // steady motion: built once
}

TEST(ShipWaves, SubCellPositionShiftsTheWaves) {
  // The centroid of |dZ|^2 follows the hull by sub-cell amounts, and the energy does not
  // depend on where inside a cell the hull sits (the phase shift is unitary).
  Water w;
  const int n = 128, P = 64;
  const double L = 16.0, dt = 0.05, dx = L / n;
  auto one_step = [&](double x) {
    Ship s = straight_ship(8.0, 1.0, x);
    ShipWaves sw(w, n, L, P, {s}, PlanEffort::estimate);
    std::vector<cfloat> z(static_cast<std::size_t>(n) * n);
    sw.add(z.data(), 0.0, dt);
    double e = 0, cx = 0;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const double v = std::norm(std::complex<double>(z[static_cast<std::size_t>(r) * n + c]));
        e += v;
        cx += v * c * dx;
      }
    return std::pair{e, cx / e};
  };
  const auto [e0, c0] = one_step(8.0);
  for (double f : {0.25, 0.5, 0.8}) {
    const auto [e, c] = one_step(8.0 + f * dx);
    EXPECT_NEAR(e / e0, 1.0, 1e-4) << f;
    EXPECT_NEAR((c - c0) / dx, f, 0.02) << f;
  }
}

TEST(ShipWaves, KernelsRebuiltOnlyWhenVelocityChanges) {
  Water w;
  Ship s;
  s.path = ShipPath({{0, 4, 8}, {1, 5, 8}, {2, 5, 9}});
  ShipWaves sw(w, 128, 16.0, 64, {s}, PlanEffort::estimate);
  std::vector<cfloat> z(128 * 128);
  const double dt = 0.1;
  for (int i = 0; i < 25; ++i) sw.add(z.data(), i * dt, dt);
  // segment 1 (10 steps, 1 build), the corner step is inside (t = 1 is a step boundary up to
  // rounding: at most one chord step), segment 2 (1 build), rest after the end (1 build)
  EXPECT_GE(sw.kernel_rebuilds(), 3u);
  EXPECT_LE(sw.kernel_rebuilds(), 5u);
}

TEST(ShipWaves, RefusesHullsAndStepsThatDoNotFitThePatch) {
  Water w;
  Ship big = straight_ship(8, 1);
  big.hull.length_m = 5.0;
  EXPECT_THROW(ShipWaves(w, 128, 16.0, 64, {big}, PlanEffort::estimate), std::invalid_argument);
  ShipWaves sw(w, 128, 16.0, 64, {straight_ship(8, 10.0)}, PlanEffort::estimate);
  EXPECT_NO_THROW(sw.check_step(0.05));
  EXPECT_THROW(sw.check_step(0.5), std::invalid_argument);
}

TEST(ShipWaves, SceneShipsWithErrorPaths) {
  const Scene ok = parse_scene_text(R"({"solver": "huygens", "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
      "path": [{"t_s": 0, "x_m": 2, "y_m": 7.5}, {"t_s": 10, "x_m": 13, "y_m": 7.5}]}]})");
  const std::vector<Ship> ships = parse_ships(ok.root());
  ASSERT_EQ(ships.size(), 1u);
  EXPECT_EQ(ships[0].path.points().size(), 2u);
  EXPECT_DOUBLE_EQ(ships[0].hull.blur(), 0.075);
  const Scene bad =
      parse_scene_text(R"({"solver": "huygens", "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
      "path": [{"t_s": 5, "x_m": 2, "y_m": 7.5}, {"t_s": 1, "x_m": 13, "y_m": 7.5}]}]})");
  try {
    parse_ships(bad.root());
    FAIL() << "decreasing path time accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.ships[0].path[1].t_s");
  }
}

// ---------------------------------------------------------------- steering (cmd::ShipTarget)

namespace {

/// One ship resting at (x0, y0) on a 16 m grid (n = 128, P = 64), with the given steering bounds.
ShipWaves resting_ship(double x0, double y0, double vmax, double amax, double tau) {
  Ship s;
  s.path = ShipPath({{0.0, x0, y0}});
  s.steering.max_speed_mps = vmax;
  s.steering.max_accel_mps2 = amax;
  s.steering.time_constant_s = tau;
  return ShipWaves(Water{}, 128, 16.0, 64, {s}, PlanEffort::estimate);
}

}  // namespace

// The steering law of ShipWaves::steer on a straight run from rest towards a target 6 m away:
// (1) acceleration-limited: v_k = (k+1) a dt, so x_k = x0 + a dt^2 k (k+1) / 2 while (k+1) a dt <= v_max;
// (2) cruise at v_max: x advances v_max dt per step and the kernels are not rebuilt;
// (3) the approach |e|/tau with braking ends at rest at the target (within 0.05 dx) without
//     overshooting it by more than one step's a dt^2.
TEST(ShipSteering, StraightRunFollowsTheClosedForm) {
  const double x0 = 3.0, y0 = 8.0, vmax = 1.0, a = 2.0, tau = 0.5, dt = 0.05, dx = 16.0 / 128;
  ShipWaves sw = resting_ship(x0, y0, vmax, a, tau);
  std::vector<cfloat> z(128 * 128);
  EXPECT_FALSE(sw.steered(0));
  ASSERT_TRUE(sw.steer(0, 0.0, x0 + 6.0, y0, 0.0, 0.0));
  EXPECT_TRUE(sw.steered(0));
  EXPECT_DOUBLE_EQ(sw.steer_speed_limit(0, dt), vmax);
  EXPECT_DOUBLE_EQ(sw.steer_accel(0), a);
  int k = 0;
  double t = 0.0;
  auto step = [&] {
    ASSERT_TRUE(sw.add(z.data(), t, dt));
    t += dt;
    ++k;
  };
  // (1) 10 steps: v = 0.1, 0.2, ..., 1.0 = v_max
  for (int i = 0; i < 10; ++i) {
    step();
    const ShipPoseNow p = sw.pose(0, t);
    EXPECT_NEAR(p.x_m, x0 + a * dt * dt * k * (k + 1) / 2.0, 1e-12) << "step " << k;
    EXPECT_EQ(p.y_m, y0);
    EXPECT_NEAR(p.speed_mps, k * a * dt, 1e-12);
    EXPECT_EQ(p.heading_rad, 0.0);
  }
  const double x10 = x0 + a * dt * dt * 55.0;  // 0.275 m
  // (2) cruise: 40 more steps at v_max (the target is still 3.7 m > tau v_max away), no rebuild
  const std::uint64_t builds = sw.kernel_rebuilds();
  for (int i = 0; i < 40; ++i) step();
  EXPECT_NEAR(sw.pose(0, t).x_m, x10 + 40 * vmax * dt, 1e-9);
  EXPECT_NEAR(sw.pose(0, t).speed_mps, vmax, 1e-12);
  EXPECT_EQ(sw.kernel_rebuilds(), builds) << "constant velocity: kernels kept";
  // (3) arrive and stop
  double xmax = 0;
  for (int i = 0; i < 300; ++i) {
    step();
    xmax = std::max(xmax, sw.pose(0, t).x_m);
  }
  const ShipPoseNow end = sw.pose(0, t);
  EXPECT_NEAR(end.x_m, x0 + 6.0, 0.05 * dx);
  EXPECT_EQ(end.speed_mps, 0.0);
  EXPECT_LE(xmax, x0 + 6.0 + a * dt * dt);
  const std::uint64_t at_rest = sw.kernel_rebuilds();
  for (int i = 0; i < 10; ++i) step();
  EXPECT_EQ(sw.kernel_rebuilds(), at_rest) << "at rest: kernels kept";
}

// Taking over a moving ship: the path is truncated at the command time, the first steered step
// starts from the path's velocity (its change is bounded by a dt), the ship turns towards the
// target, and a moving target is tracked at its own velocity.
TEST(ShipSteering, TakesOverFromThePathWithoutAJump) {
  Water w;
  Ship s;
  s.path = ShipPath({{0.0, 2.0, 8.0}, {10.0, 12.0, 8.0}});  // 1 m/s along +x
  s.steering = SteeringParams{2.0, 1.0, 0.5};
  ShipWaves sw(w, 128, 16.0, 64, {s}, PlanEffort::estimate);
  std::vector<cfloat> z(128 * 128);
  const double dt = 0.05;
  double t = 0;
  for (int i = 0; i < 20; ++i, t += dt) ASSERT_TRUE(sw.add(z.data(), t, dt));
  const ShipPoseNow before = sw.pose(0, t);
  EXPECT_NEAR(before.x_m, 3.0, 1e-9);
  EXPECT_NEAR(before.speed_mps, 1.0, 1e-12);
  // target 3 m to the ship's left, moving at 0.3 m/s along +y
  ASSERT_TRUE(sw.steer(0, t, 3.0, 11.0, 0.0, 0.3));
  ASSERT_EQ(sw.path(0).points().size(), 2u);
  EXPECT_NEAR(sw.path(0).points().back().t_s, t, 1e-12) << "future scripted points dropped";
  EXPECT_NEAR(sw.path(0).points().back().x_m, 3.0, 1e-9);
  ASSERT_TRUE(sw.add(z.data(), t, dt));
  t += dt;
  const ShipPoseNow p1 = sw.pose(0, t);
  // first step: v = (1, 0) + a dt towards v_des = (0, 0.3) + e/|e| min(...) (clamped to 2 m/s)
  const double vx = (p1.x_m - 3.0) / dt, vy = (p1.y_m - 8.0) / dt;
  EXPECT_NEAR(std::hypot(vx - 1.0, vy), 1.0 * dt, 1e-9) << "velocity change bounded by a dt";
  EXPECT_GT(vy, 0.0);
  EXPECT_GT(p1.heading_rad, 0.0);  // turning towards +y
  // long after: tracking the moving target (clamped at the grid edge y = 16: not reached yet)
  for (int i = 0; i < 160; ++i, t += dt) ASSERT_TRUE(sw.add(z.data(), t, dt));
  const ShipPoseNow p = sw.pose(0, t);
  const double ty = 11.0 + 0.3 * (t - 1.0);
  EXPECT_NEAR(p.x_m, 3.0, 0.01);
  EXPECT_NEAR(p.y_m, ty, 0.01);
  EXPECT_NEAR(p.speed_mps, 0.3, 0.01);
  EXPECT_NEAR(p.heading_rad, kPi / 2, 0.02);
}

TEST(ShipSteering, RefusesInvalidTargets) {
  ShipWaves sw = resting_ship(4.0, 4.0, 1.0, 1.0, 0.5);
  const double nan = std::nan(""), inf = INFINITY;
  EXPECT_FALSE(sw.steer(-1, 0.0, 5.0, 5.0, 0, 0));
  EXPECT_FALSE(sw.steer(1, 0.0, 5.0, 5.0, 0, 0));
  EXPECT_FALSE(sw.steer(0, 0.0, nan, 5.0, 0, 0));
  EXPECT_FALSE(sw.steer(0, 0.0, 5.0, 5.0, inf, 0));
  EXPECT_FALSE(sw.steer(0, 0.0, 5.0, 5.0, 0, nan));
  EXPECT_FALSE(sw.steer(0, 0.0, -0.1, 5.0, 0, 0));
  EXPECT_FALSE(sw.steer(0, 0.0, 5.0, 16.5, 0, 0));
  EXPECT_FALSE(sw.steered(0));
  EXPECT_TRUE(sw.steer(0, 0.0, 16.0, 0.0, 0, 0));
}

// The steering speed never exceeds check_step's bound (a quarter of the patch per step), whatever
// the scene's max_speed_mps: the clamp, not a refusal, keeps a steered ship's patch valid.
TEST(ShipSteering, SpeedIsClampedToThePatchBound) {
  ShipWaves sw = resting_ship(2.0, 8.0, 1000.0, 1e6, 0.01);
  const double dt = 0.05, limit = 0.25 * 64 * (16.0 / 128) / dt;  // 40 m/s
  EXPECT_DOUBLE_EQ(sw.steer_speed_limit(0, dt), limit);
  ASSERT_TRUE(sw.steer(0, 0.0, 14.0, 8.0, 0, 0));
  std::vector<cfloat> z(128 * 128);
  ASSERT_TRUE(sw.add(z.data(), 0.0, dt));
  EXPECT_LE(sw.pose(0, dt).speed_mps, limit);
  EXPECT_LE(sw.pose(0, dt).x_m - 2.0, 0.25 * 64 * (16.0 / 128) + 1e-12);
}

TEST(ShipSteering, SceneSteeringBlock) {
  const Scene sc = parse_scene_text(R"({"solver": "huygens", "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
      "path": [{"t_s": 0, "x_m": 2, "y_m": 7.5}], "steering": {"max_speed_mps": 2.5, "max_accel_mps2": 3, "time_constant_s": 0.2}}]})");
  const std::vector<Ship> ships = parse_ships(sc.root());
  ASSERT_EQ(ships.size(), 1u);
  EXPECT_EQ(ships[0].steering.max_speed_mps, 2.5);
  EXPECT_EQ(ships[0].steering.max_accel_mps2, 3.0);
  EXPECT_EQ(ships[0].steering.time_constant_s, 0.2);
  const Scene bad =
      parse_scene_text(R"({"solver": "huygens", "ships": [{"length_m": 1.0, "beam_m": 0.3, "draft_m": 0.05,
      "path": [{"t_s": 0, "x_m": 2, "y_m": 7.5}], "steering": {"top_speed": 2}}]})");
  try {
    parse_ships(bad.root());
    FAIL() << "unknown steering key accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.ships[0].steering.top_speed");
  }
}

// The round trip every K steps (HuygensPropagator::round_trip_every): a ship's patch of the step
// k steps before the round trip is turned by e^{-i omega k dt} on the patch (ShipWaves::gather).
// With the patch as large as the grid the patch's periodicity is the grid's, so the gathered
// sources must give the every-step field to float rounding (no cutoff: nothing else differs).
TEST(ShipWaves, GatheredOverKStepsEqualsEveryStepInjection) {
  const int n = 64, k_every = 4, steps = 3 * k_every;
  const double dt = 0.05;
  Ship s;
  s.path = ShipPath({{0.0, 2.0, 3.2}, {10.0, 12.0, 3.2}});  // 1 m/s along +x
  auto params = [&](int k) {
    HuygensParams p;
    p.n = n;
    p.length_m = 6.4;
    p.margin = 0;
    p.absorber = Absorber::off;
    p.spatial = true;
    p.dt_s = dt;
    p.effort = PlanEffort::estimate;
    p.round_trip_every = k;
    return p;
  };
  HuygensPropagator every(params(1)), gathered(params(k_every));
  ShipWaves a(Water{}, n, 6.4, n, {s}, PlanEffort::estimate), b(Water{}, n, 6.4, n, {s}, PlanEffort::estimate);
  b.reserve_gather(k_every);
  for (int i = 0; i < steps; ++i) {
    every.propagate();
    ASSERT_TRUE(a.add(every.field().data(), i * dt, dt));
    every.spectrum();
    every.height();
    every.end_step();
    gathered.propagate();
    EXPECT_EQ(gathered.steps_to_round_trip(), (k_every - 1 - i % k_every));
    ASSERT_TRUE(b.gather(i * dt, dt, gathered.steps_to_round_trip()));
    if (gathered.round_trip_now()) b.scatter_rows(gathered.field().data(), 0, n);
    gathered.spectrum();
    gathered.height();
    gathered.end_step();
  }
  EXPECT_EQ(b.gathered(), 0);
  double num = 0, den = 0;
  const auto x = every.eta(), y = gathered.eta();
  for (std::size_t i = 0; i < x.size(); ++i) {
    num += std::pow(double(x[i]) - y[i], 2);
    den += std::pow(double(x[i]), 2);
  }
  ASSERT_GT(den, 0);
  EXPECT_LT(std::sqrt(num / den), 2e-6) << "relative L2 of eta after " << steps << " steps";
  EXPECT_EQ(gathered.stats()[gathered.stats().find("spectrum")].transforms,
            static_cast<std::uint64_t>(steps / k_every));
}
