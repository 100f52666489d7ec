#pragma once
// The sRGB transfer functions (IEC 61966-2-1): colours are given as sRGB values (what a user picks
// and what a PNG holds) and decoded to linear radiance on input; every pass shades, absorbs and sums
// in linear radiance; the tone map pass encodes once at the end (tone_map_pass.hpp). The shaders
// carry the same two functions (shaders/ground_common.glsl, ship.frag, tonemap.frag).
#include <cmath>
#include <glm/glm.hpp>

namespace huygens {

/// sRGB value in [0, 1] -> linear: c / 12.92 up to 0.04045, else ((c + 0.055) / 1.055)^2.4.
inline double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
/// Linear in [0, 1] -> sRGB value: 12.92 l up to 0.0031308, else 1.055 l^(1/2.4) - 0.055.
inline double linear_to_srgb(double l) { return l <= 0.0031308 ? 12.92 * l : 1.055 * std::pow(l, 1.0 / 2.4) - 0.055; }

inline glm::vec3 srgb_to_linear(const glm::vec3& c) {
  return {static_cast<float>(srgb_to_linear(c.r)), static_cast<float>(srgb_to_linear(c.g)),
          static_cast<float>(srgb_to_linear(c.b))};
}

}  // namespace huygens
