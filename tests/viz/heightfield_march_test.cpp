// Tests of the CPU heightfield march (viz/cpu/heightfield_march.hpp, paper 001): the exact
// intersection of a ray with a bilinear bed against closed forms (a ramp, a step one cell wide),
// and the shader's march (its mirror, in double) against the exact one.
#include "heightfield_march.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

using namespace huygens;

namespace {

constexpr std::size_t kN = 64;
constexpr double kDx = 0.0625, kX0 = 1.0, kY0 = 2.0;  // heights and positions exact in float

struct Bed {
  std::vector<float> z;
  BedField field() const { return BedField{z, kN, kN, kDx, kX0, kY0}; }
};

// A bed that depends on x only: z(j) per grid column.
template <class F>
Bed bed_of_column(F f) {
  Bed b;
  b.z.resize(kN * kN);
  for (std::size_t i = 0; i < kN; ++i)
    for (std::size_t j = 0; j < kN; ++j) b.z[i * kN + j] = static_cast<float>(f(j));
  return b;
}

// A refracted ray: from P at the rest level over the region, down at angle theta from the
// vertical (tan theta <= 1.13, the steepest a refracted ray gets), heading phi.
void random_ray(std::mt19937& rng, glm::dvec3& P, glm::dvec3& t) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double w = kDx * (kN - 1);
  P = glm::dvec3(kX0 + w * (0.2 + 0.6 * u(rng)), kY0 + w * (0.2 + 0.6 * u(rng)), 0.0);
  const double theta = std::atan(1.13 * u(rng)), phi = 2.0 * 3.14159265358979 * u(rng);
  t = glm::dvec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta));
}

// The first s >= 0 where P + s t meets the line z = z0 + g (x - xa) over x in [xa, xb].
double hit_on_piece(const glm::dvec3& P, const glm::dvec3& t, double z0, double g, double xa, double xb) {
  const double den = t.z - g * t.x;
  if (den == 0.0) return std::numeric_limits<double>::infinity();
  const double s = (z0 + g * (P.x - xa) - P.z) / den, x = P.x + s * t.x;
  return s >= 0.0 && x >= xa - 1e-12 && x <= xb + 1e-12 ? s : std::numeric_limits<double>::infinity();
}

}  // namespace

// A ramp z = -1 + 0.5 (x - x0) is bilinear-exact: the ray meets it at
// s = (-1 + 0.5 (P_x - x0) - P_z) / (t_z - 0.5 t_x) (where that stays on the grid).
TEST(HeightfieldMarch, ExactHitOnARampIsTheClosedForm) {
  const Bed b = bed_of_column([](std::size_t j) { return -1.0 + 0.5 * kDx * static_cast<double>(j); });
  const BedField f = b.field();
  std::mt19937 rng(1);
  double worst = 0.0, worst_march = 0.0;
  for (int k = 0; k < 2000; ++k) {
    glm::dvec3 P, t;
    random_ray(rng, P, t);
    const double s = hit_on_piece(P, t, -1.0, 0.5, kX0, kX0 + kDx * (kN - 1));
    if (!std::isfinite(s)) continue;
    const glm::dvec3 want = P + s * t;
    worst = std::max(worst, glm::length(exact_bed_hit(f, P, t, 10.0) - want));
    worst_march = std::max(worst_march, glm::length(shader_bed_hit(f, P, t) - want));
  }
  std::printf("ramp: exact %.2e m, shader's march %.2e m (cell %.3f m)\n", worst, worst_march, kDx);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_march, 1e-6) << "a linear bed: the secant is exact";
}

// A step one cell wide: z = -2 up to column 31, -0.5 from column 32, linear between. The first hit
// is the first of the three pieces' closed forms along the ray.
TEST(HeightfieldMarch, ExactHitOnAStepIsTheClosedForm) {
  const Bed b = bed_of_column([](std::size_t j) { return j <= 31 ? -2.0 : -0.5; });
  const BedField f = b.field();
  const double xa = kX0 + 31 * kDx, xb = xa + kDx, far = kX0 + 10.0;
  std::mt19937 rng(2);
  double worst = 0.0, worst_march = 0.0, worst_flat = 0.0;
  for (int k = 0; k < 4000; ++k) {
    glm::dvec3 P, t;
    random_ray(rng, P, t);
    const double s = std::min({hit_on_piece(P, t, -2.0, 0.0, kX0 - 10.0, xa),
                               hit_on_piece(P, t, -2.0, 1.5 / kDx, xa, xb), hit_on_piece(P, t, -0.5, 0.0, xb, far)});
    const glm::dvec3 want = P + s * t;
    worst = std::max(worst, glm::length(exact_bed_hit(f, P, t, 10.0) - want));
    worst_march = std::max(worst_march, glm::length(glm::dvec2(shader_bed_hit(f, P, t) - want)));
    worst_flat = std::max(worst_flat, glm::length(glm::dvec2(flat_bed_hit(f, P, t) - want)));
  }
  std::printf("step: exact %.2e m; in xy the shader's march %.2e cells, the flat bed under P %.1f cells\n", worst,
              worst_march / kDx, worst_flat / kDx);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_march, 1e-9) << "the march samples the lip (a grid line) and solves each piece";
  EXPECT_GT(worst_flat, 2.0 * kDx) << "the flat rule misses the step";
}

// The shader's march against the exact hit on a rough bed (a step and two crossing waves with
// slopes up to 2.5): the largest distance in xy over 20000 rays, in cells. Both solve the same
// quadratics, the march finding its pieces by the grid traversal, the reference by sorting every
// grid line's crossing: they agree to rounding (the GPU's float and its filter: surface_pass_test).
TEST(HeightfieldMarch, ShaderMarchFollowsTheExactHitOnARoughBed) {
  Bed b;
  b.z.resize(kN * kN);
  for (std::size_t i = 0; i < kN; ++i)
    for (std::size_t j = 0; j < kN; ++j)
      b.z[i * kN + j] = static_cast<float>((j < 32 ? -2.0 : -0.8) + 0.3 * std::sin(0.9 * j) * std::cos(0.6 * i));
  const BedField f = b.field();
  std::mt19937 rng(3);
  std::vector<double> err;
  for (int k = 0; k < 20000; ++k) {
    glm::dvec3 P, t;
    random_ray(rng, P, t);
    err.push_back(glm::length(glm::dvec2(shader_bed_hit(f, P, t) - exact_bed_hit(f, P, t, 10.0))) / kDx);
  }
  std::sort(err.begin(), err.end());
  const double p99 = err[err.size() * 99 / 100], worst = err.back();
  std::printf("rough bed: shader's march vs exact, 99th percentile %.2e cells, largest %.2e cells\n", p99, worst);
  EXPECT_LT(worst, 1e-9);
}

// Past its cap of pieces the march takes the plane at the bed's height at its last sample: over the
// step bed a ray from the shallow side that passes the lip and goes on over the flat deep floor
// meets it there exactly when the cap falls beyond the lip, and on the shallow plane when it
// falls before it (where the march has not reached the lip).
TEST(HeightfieldMarch, ACappedMarchEndsOnThePlaneUnderItsLastSample) {
  const Bed b = bed_of_column([](std::size_t j) { return j <= 31 ? -2.0 : -0.5; });
  const BedField f = b.field();
  const glm::dvec3 P(kX0 + 33.5 * kDx, kY0 + 20.0 * kDx, 0.0);
  const double a = 50.0 * std::numbers::pi / 180.0;
  const glm::dvec3 t(-std::sin(a), 0.0, -std::cos(a));  // along -x, 1.19 m per m down
  const glm::dvec3 exact = exact_bed_hit(f, P, t, 10.0);
  ASSERT_NEAR(exact.z, -2.0, 1e-12) << "the ray passes the lip";
  EXPECT_LT(glm::length(shader_bed_hit(f, P, t, BedMarch{8}) - exact), 1e-12) << "the cap beyond the lip";
  const glm::dvec3 short_cap = shader_bed_hit(f, P, t, BedMarch{1});
  EXPECT_NEAR(short_cap.z, -0.5, 1e-12) << "the cap before the lip: the shallow plane";
}
