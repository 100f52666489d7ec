// CPU references of the accumulation-buffer blur emulation of paper 004 section 6 (no GL).
//
// The 8-bit image v is blurred with [1 2 1; 2 4 2; 1 2 1] (clamp to edge). The paper
// splits every value into a = v >> 4 and b = v & 15, sums the 16 shifted copies of each
// part separately (green: c = sum w a <= 240, blue: d = sum w b <= 240, so no 8-bit
// channel overflows), and recombines out = c + floor((d + 7) / 16). Since the full sum
// is S = sum w v = 16 c + d, out = floor((S + 7) / 16): S/16 rounded to nearest with ties
// rounded down, which differs from round-half-up floor((S + 8) / 16) exactly where
// S mod 16 == 8, by one level.
#pragma once

#include <cstdint>
#include <span>

namespace huygens::viz {

/// The 16 shifted draws of the paper, as pixel offsets (4x centre, 2x each edge neighbour,
/// 1x each corner): together the kernel [1 2 1; 2 4 2; 1 2 1].
inline constexpr int kAccumOffsets[16][2] = {{0, 0}, {0, 0}, {0, 0},  {0, 0},  {1, 0}, {1, 0},  {-1, 0}, {-1, 0},
                                             {0, 1}, {0, 1}, {0, -1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}};

/// Integer reference of the emulation: the same split, 16 additive copies and recombination
/// lookup as the GPU passes. `in`, `out`: width*height bytes, row-major.
void accum_blur_reference(std::span<const std::uint8_t> in, int width, int height, std::span<std::uint8_t> out);

/// The exact blur S = sum w v (integer, 0..4080) per pixel, clamp to edge.
void blur121_sums(std::span<const std::uint8_t> in, int width, int height, std::span<std::uint16_t> sums);

}  // namespace huygens::viz
