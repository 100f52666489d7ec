// CPU references of the accumulation-buffer blur emulation (paper 004 section 6).
#include "accum_blur_cpu.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace huygens::viz {
namespace {
void check(std::size_t in, std::size_t out, int w, int h) {
  if (w < 1 || h < 1 || in != std::size_t(w) * h || out != std::size_t(w) * h)
    throw std::invalid_argument("accum blur: buffers must hold width*height values");
}
}  // namespace

void accum_blur_reference(std::span<const std::uint8_t> in, int w, int h, std::span<std::uint8_t> out) {
  check(in.size(), out.size(), w, h);
  // pass 1: 16 additive draws of the split texture into the green (high) and blue (low) channels
  std::vector<std::uint8_t> green(in.size(), 0), blue(in.size(), 0);
  for (const auto& off : kAccumOffsets)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int xs = std::clamp(x + off[0], 0, w - 1), ys = std::clamp(y + off[1], 0, h - 1);
        const std::uint8_t v = in[std::size_t(ys) * w + xs];
        const std::size_t o = std::size_t(y) * w + x;
        // saturating 8-bit add, as the RGBA8 blend does (never reached: sums stay <= 240)
        green[o] = std::uint8_t(std::min(255, green[o] + (v >> 4)));
        blue[o] = std::uint8_t(std::min(255, blue[o] + (v & 15)));
      }
  // pass 2: recombination lookup c + floor((d + 7) / 16)
  for (std::size_t o = 0; o < in.size(); ++o) out[o] = std::uint8_t(std::min(255, green[o] + (blue[o] + 7) / 16));
}

void blur121_sums(std::span<const std::uint8_t> in, int w, int h, std::span<std::uint16_t> sums) {
  check(in.size(), sums.size(), w, h);
  static constexpr int k[3] = {1, 2, 1};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int s = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          s += k[dx + 1] * k[dy + 1] * in[std::size_t(std::clamp(y + dy, 0, h - 1)) * w + std::clamp(x + dx, 0, w - 1)];
      sums[std::size_t(y) * w + x] = std::uint16_t(s);
    }
}

}  // namespace huygens::viz
