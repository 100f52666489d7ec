// The FFTW wrapper (common/fft.hpp): aligned buffers, the 2D plans' round trip and Parseval's
// identity in float, FFTW's sign convention, and the index-to-wavenumber helper.
#include "huygens/common/fft.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

using namespace huygens;
using cd = std::complex<double>;

namespace {

constexpr double kPi = std::numbers::pi;

void fill_random(AlignedBuffer<cfloat>& b, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = cfloat(g(rng), g(rng));
}

double sum_norm(const AlignedBuffer<cfloat>& b) {
  double s = 0;
  for (std::size_t i = 0; i < b.size(); ++i) s += std::norm(cd(b[i]));
  return s;
}

}  // namespace

TEST(AlignedBuffer, IsAlignedZeroedAndMovable) {
  AlignedBuffer<float> a(1001);
  ASSERT_EQ(a.size(), 1001u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % 64, 0u);
  for (float v : a.span()) EXPECT_EQ(v, 0.0f);
  a[7] = 3.0f;
  const float* p = a.data();
  AlignedBuffer<float> b(std::move(a));
  EXPECT_EQ(b.data(), p);
  EXPECT_EQ(b[7], 3.0f);
  EXPECT_EQ(a.size(), 0u);
  EXPECT_EQ(a.data(), nullptr);
  AlignedBuffer<float> c;
  c = std::move(b);
  EXPECT_EQ(c.data(), p);
  EXPECT_EQ(b.data(), nullptr);
}

// A buffer of 2 MiB or more starts on a 2 MiB boundary (so it can be backed by transparent huge
// pages), is zeroed to its last element and stays movable.
TEST(AlignedBuffer, LargeBufferIsAlignedToHugePages) {
  const std::size_t n = (std::size_t{5} << 20) / sizeof(float) + 3;  // 5 MiB and 12 B
  AlignedBuffer<float> a(n);
  ASSERT_EQ(a.size(), n);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % (std::uintptr_t{2} << 20), 0u);
  EXPECT_EQ(a[0], 0.0f);
  EXPECT_EQ(a[n - 1], 0.0f);
  a[n - 1] = 2.0f;
  AlignedBuffer<float> b(std::move(a));
  EXPECT_EQ(b[n - 1], 2.0f);
}

// Forward then backward multiplies by N^2 (FFTW's inverse is unnormalised): the float round
// trip returns the field to a few float epsilons (a radix-2 transform's error grows like
// eps log2 N, so 1e-6 relative rms holds with margin at 64 x 128).
TEST(Fft2D, RoundTripReturnsTheFieldTimesNSquared) {
  const int rows = 64, cols = 128;
  AlignedBuffer<cfloat> x(static_cast<std::size_t>(rows) * cols), y(x.size()), z(x.size());
  fill_random(x, 1);
  Fft2D fwd(rows, cols, x.data(), y.data(), Fft2D::forward, PlanEffort::estimate);
  Fft2D inv(rows, cols, y.data(), z.data(), Fft2D::backward, PlanEffort::estimate);
  EXPECT_EQ(fwd.rows(), rows);
  EXPECT_EQ(fwd.cols(), cols);
  fwd.execute();
  inv.execute();
  const double scale = 1.0 / (static_cast<double>(rows) * cols);
  double err = 0;
  for (std::size_t i = 0; i < x.size(); ++i) err += std::norm(cd(z[i]) * scale - cd(x[i]));
  EXPECT_LT(std::sqrt(err / sum_norm(x)), 1e-6);
}

// Parseval: sum |X|^2 = N^2 sum |x|^2 (relative 1e-6 in float, as the round trip).
TEST(Fft2D, ParsevalHolds) {
  const int n = 64;
  AlignedBuffer<cfloat> x(static_cast<std::size_t>(n) * n), y(x.size());
  fill_random(x, 2);
  Fft2D fwd(n, n, x.data(), y.data(), Fft2D::forward, PlanEffort::estimate);
  fwd.execute();
  EXPECT_NEAR(sum_norm(y) / (static_cast<double>(n) * n * sum_norm(x)), 1.0, 1e-6);
}

// FFTW's convention X_k = sum x_n e^{-2 pi i k n / N}: the plane wave e^{i (kx x + ky y)}
// with kx = fft_wavenumber(c0), ky = fft_wavenumber(r0) is the single coefficient N^2 at
// index (r0, c0), also for negative frequencies (c0 > N/2) and the Nyquist index. Plans run
// on other buffers of the same size and alignment through execute(in, out).
TEST(Fft2D, PlaneWaveLandsOnItsWavenumberIndex) {
  const int n = 32;
  const double len = 3.0, dx = len / n;
  AlignedBuffer<cfloat> plan_in(static_cast<std::size_t>(n) * n), plan_out(plan_in.size());
  Fft2D fwd(n, n, plan_in.data(), plan_out.data(), Fft2D::forward, PlanEffort::estimate);
  AlignedBuffer<cfloat> x(plan_in.size()), y(plan_in.size());
  for (const auto& [r0, c0] : {std::pair{3, 29}, std::pair{0, 16}, std::pair{17, 1}}) {
    const double kx = fft_wavenumber(c0, n, len), ky = fft_wavenumber(r0, n, len);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c)
        x[static_cast<std::size_t>(r) * n + c] = cfloat(std::polar(1.0, kx * c * dx + ky * r * dx));
    fwd.execute(x.data(), y.data());
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        const cd v = y[static_cast<std::size_t>(r) * n + c];
        const cd expected = (r == r0 && c == c0) ? cd(n * n, 0) : cd(0, 0);
        ASSERT_LT(std::abs(v - expected), 1e-4 * n * n) << r << ", " << c << " for " << r0 << ", " << c0;
      }
  }
}

// From 256^2 on, PlanEffort::estimate runs in row-column form (rows, transpose, rows, transpose
// back; fft.hpp). A separable field x(r, c) = a(r) b(c) has the transform A(k) B(l), with A and B
// 1D DFTs computed here directly in double: in place and out of place, both signs, one thread and
// two (the transposes run in parallel from 512^2), relative rms error 1e-6 as the round trip's.
TEST(Fft2D, RowColumnFormTransformsASeparableField) {
  for (const int n : {256, 512})
    for (const int sign : {Fft2D::forward, Fft2D::backward})
      for (const bool in_place : {true, false}) {
        omp_set_num_threads(n == 512 ? 2 : 1);
        std::mt19937 rng(static_cast<unsigned>(n + sign));
        std::normal_distribution<double> g(0.0, 1.0);
        std::vector<cd> a(n), b(n), fa(n), fb(n);
        for (int i = 0; i < n; ++i) a[i] = cd(g(rng), g(rng)), b[i] = cd(g(rng), g(rng));
        auto dft = [&](const std::vector<cd>& v, std::vector<cd>& out) {
          for (int k = 0; k < n; ++k) {
            cd sum = 0;
            for (int j = 0; j < n; ++j) sum += v[j] * std::polar(1.0, sign * 2.0 * kPi * double((k * j) % n) / n);
            out[k] = sum;
          }
        };
        dft(a, fa);
        dft(b, fb);
        AlignedBuffer<cfloat> x(static_cast<std::size_t>(n) * n), y(x.size());
        for (int r = 0; r < n; ++r)
          for (int c = 0; c < n; ++c) x[static_cast<std::size_t>(r) * n + c] = cfloat(a[r] * b[c]);
        AlignedBuffer<cfloat>& out = in_place ? x : y;
        Fft2D f(n, n, x.data(), out.data(), sign, PlanEffort::estimate);
        f.execute();
        double err = 0, norm = 0;
        for (int k = 0; k < n; ++k)
          for (int l = 0; l < n; ++l) {
            const cd e = fa[k] * fb[l];
            err += std::norm(cd(out[static_cast<std::size_t>(k) * n + l]) - e);
            norm += std::norm(e);
          }
        EXPECT_LT(std::sqrt(err / norm), 1e-6) << n << " sign " << sign << (in_place ? " in place" : " out of place");
      }
  omp_set_num_threads(1);
}

// The helper: signed index i (i < n/2), i - n (i >= n/2; the Nyquist index counts as -n/2),
// times 2 pi / L, bit for bit the expression it replaced.
TEST(FftWavenumber, SignedIndexAndWavenumber) {
  EXPECT_EQ(fft_signed_index(0, 8), 0);
  EXPECT_EQ(fft_signed_index(3, 8), 3);
  EXPECT_EQ(fft_signed_index(4, 8), -4);
  EXPECT_EQ(fft_signed_index(5, 8), -3);
  EXPECT_EQ(fft_signed_index(7, 8), -1);
  static_assert(fft_signed_index(1, 2) == -1);
  const double len = 15.0;
  for (int n : {16, 64, 512})
    for (int i = 0; i < n; ++i) {
      const double old = 2.0 * kPi / len * (i < n / 2 ? i : i - n);
      EXPECT_EQ(fft_wavenumber(i, n, len), old) << i;
    }
  EXPECT_DOUBLE_EQ(fft_wavenumber(1, 64, 2.0), kPi);
  EXPECT_DOUBLE_EQ(fft_wavenumber(63, 64, 2.0), -kPi);
}
