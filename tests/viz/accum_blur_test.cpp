// Accumulation-buffer blur emulation of paper 004 section 6: the GPU passes against the
// CPU integer reference (bit for bit) and against the exactly rounded blur.
#include "accum_blur.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "caustics_cpu.hpp"  // blur121_f32
#include "gl/gl.hpp"

using namespace huygens;

namespace {

gl::HeadlessContext& context() {
  static gl::HeadlessContext ctx;
  ctx.make_current();
  return ctx;
}

std::vector<std::uint8_t> random_image(int w, int h, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::uint8_t> img(std::size_t(w) * h);
  for (auto& v : img) v = std::uint8_t(rng() & 255);
  return img;
}

std::vector<std::uint8_t> gpu_emulated(viz::AccumBlur& blur, const std::vector<std::uint8_t>& img, int w, int h) {
  gl::Texture src(w, h, GL_R8);
  src.upload(img.data(), GL_RED, GL_UNSIGNED_BYTE);
  blur.blur_emulated(src);
  return gl::read_pixels_u8(blur.emulated_framebuffer(), GL_RED).pixels;
}

struct Case {
  const char* name;
  std::vector<std::uint8_t> img;
};

std::vector<Case> cases(int w, int h) {
  std::vector<Case> c;
  c.push_back({"random", random_image(w, h, 1234 + w)});
  c.push_back({"all-0", std::vector<std::uint8_t>(std::size_t(w) * h, 0)});
  c.push_back({"all-255", std::vector<std::uint8_t>(std::size_t(w) * h, 255)});
  // checkerboard 0/255 and a ramp: extreme local sums and every value
  std::vector<std::uint8_t> chk(std::size_t(w) * h), ramp(std::size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      chk[std::size_t(y) * w + x] = ((x + y) & 1) ? 255 : 0;
      ramp[std::size_t(y) * w + x] = std::uint8_t((x + 7 * y) & 255);
    }
  c.push_back({"checker", chk});
  c.push_back({"ramp", ramp});
  return c;
}

}  // namespace

TEST(AccumBlurCpu, ReferenceEqualsRoundingOfTheSumWithTiesDown) {
  // closed form: c + floor((d + 7) / 16) == floor((S + 7) / 16) with S the exact weighted sum
  const int w = 37, h = 23;
  const auto img = random_image(w, h, 5);
  std::vector<std::uint8_t> out(img.size());
  std::vector<std::uint16_t> sums(img.size());
  viz::accum_blur_reference(img, w, h, out);
  viz::blur121_sums(img, w, h, sums);
  for (std::size_t i = 0; i < img.size(); ++i) ASSERT_EQ(out[i], (sums[i] + 7) / 16) << i;
}

TEST(AccumBlurCpu, ConstantImagesStayConstant) {
  for (int v : {0, 1, 8, 15, 16, 127, 200, 255}) {
    std::vector<std::uint8_t> img(64, std::uint8_t(v)), out(64);
    viz::accum_blur_reference(img, 8, 8, out);
    for (auto o : out) ASSERT_EQ(o, v);
  }
}

class AccumBlurGpu : public ::testing::TestWithParam<int> {};

TEST_P(AccumBlurGpu, BitExactAgainstCpuIntegerReference) {
  context();
  const int n = GetParam();
  viz::AccumBlur blur(n, n);
  for (const auto& c : cases(n, n)) {
    std::vector<std::uint8_t> ref(c.img.size());
    viz::accum_blur_reference(c.img, n, n, ref);
    const auto gpu = gpu_emulated(blur, c.img, n, n);
    ASSERT_EQ(gpu.size(), ref.size());
    std::size_t mismatches = 0, first = 0;
    for (std::size_t i = 0; i < ref.size(); ++i)
      if (gpu[i] != ref[i] && mismatches++ == 0) first = i;
    EXPECT_EQ(mismatches, 0u) << c.name << " " << n << "x" << n << ": first mismatch at " << first << " gpu "
                              << int(gpu[first]) << " ref " << int(ref[first]);
    if (mismatches) {
      // actual / expected / diff PNGs for inspection
      const std::string base = ::testing::TempDir() + "accum_blur_" + c.name + "_" + std::to_string(n);
      gl::Image8 a{n, n, 1, gpu}, e{n, n, 1, ref}, d{n, n, 1, std::vector<std::uint8_t>(ref.size())};
      for (std::size_t i = 0; i < ref.size(); ++i) d.pixels[i] = gpu[i] == ref[i] ? 0 : 255;
      gl::write_png(base + "_actual.png", a);
      gl::write_png(base + "_expected.png", e);
      gl::write_png(base + "_diff.png", d);
      std::printf("wrote %s_{actual,expected,diff}.png\n", base.c_str());
    }
  }
}

TEST_P(AccumBlurGpu, WithinOneLevelOfExactlyRoundedBlurAndOnlyOnTies) {
  context();
  const int n = GetParam();
  viz::AccumBlur blur(n, n);
  for (const auto& c : cases(n, n)) {
    const auto gpu = gpu_emulated(blur, c.img, n, n);
    std::vector<std::uint16_t> sums(c.img.size());
    viz::blur121_sums(c.img, n, n, sums);
    std::map<int, long> hist;
    for (std::size_t i = 0; i < sums.size(); ++i) {
      const int exact = int(std::lround(sums[i] / 16.0));  // exactly rounded float blur, ties up
      const int diff = int(gpu[i]) - exact;
      ++hist[diff];
      ASSERT_LE(std::abs(diff), 1) << c.name << " at " << i;
      // the only difference is the paper's +7 (ties down) against round-half-up
      if (diff != 0) {
        ASSERT_EQ(sums[i] % 16, 8) << c.name << " at " << i;
      }
    }
    std::printf("[ histogram ] %s %dx%d emulated - exactly rounded:", c.name, n, n);
    for (const auto& [d, count] : hist) std::printf("  %+d: %ld", d, count);
    std::printf("\n");
  }
}

TEST_P(AccumBlurGpu, FloatPathMatchesExactBlur) {
  context();
  const int n = GetParam();
  viz::AccumBlur blur(n, n);
  const auto img = random_image(n, n, 99);
  gl::Texture src(n, n, GL_R8);
  src.upload(img.data(), GL_RED, GL_UNSIGNED_BYTE);
  blur.blur_float(src);
  const auto f = gl::read_pixels_f32(blur.float_framebuffer(), 1);
  std::vector<std::uint16_t> sums(img.size());
  viz::blur121_sums(img, n, n, sums);
  double max_err = 0;
  for (std::size_t i = 0; i < sums.size(); ++i) max_err = std::max(max_err, std::abs(f[i] * 255.0 - sums[i] / 16.0));
  EXPECT_LT(max_err, 1e-3) << "float blur, in 8-bit levels";
}

// A float source takes the four-tap bilinear path (blur_float_linear.frag): the same kernel
// to float rounding, clamp to edge included (an 8-bit source read through 8-bit filter weights
// was 1 level off, which is why GL_R8 keeps the nine-tap path).
TEST_P(AccumBlurGpu, FloatSourceBilinearPathMatchesExactBlur) {
  context();
  const int n = GetParam();
  viz::AccumBlur blur(n, n);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> img(std::size_t(n) * n);
  for (float& v : img) v = u(rng) < 0.02f ? 40.0f * u(rng) : u(rng);  // a few bright focal texels
  gl::Texture src(n, n, GL_R32F);
  src.upload(img.data(), GL_RED, GL_FLOAT);
  blur.blur_float(src);
  const auto f = gl::read_pixels_f32(blur.float_framebuffer(), 1);
  const std::vector<float> ref = viz::blur121_f32(img, n, n);
  double max_rel = 0;
  for (std::size_t i = 0; i < ref.size(); ++i)
    max_rel = std::max(max_rel, std::abs(double(f[i]) - ref[i]) / std::max(double(ref[i]), 1e-3));
  std::printf("[ float blur ] %dx%d R32F source: max relative error %.2e\n", n, n, max_rel);
  EXPECT_LT(max_rel, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Sizes, AccumBlurGpu, ::testing::Values(64, 512));
