// Accumulation-buffer blur emulation of paper 004 section 6 (GPU) and the float blur.
#include "accum_blur.hpp"

#include <cstdint>
#include <vector>

namespace huygens::viz {

AccumBlur::AccumBlur(int width, int height)
    : w_(width),
      h_(height),
      split_lut_(256, 1, GL_RGBA8),
      combine_lut_(256, 256, GL_R8),
      accum_(width, height, GL_RGBA8),
      out8_(width, height, GL_R8),
      outf_(width, height, GL_R32F),
      fb_accum_(accum_),
      fb_out8_(out8_),
      fb_outf_(outf_) {
  // split table: v -> (0, v >> 4, v & 15, 0)
  std::vector<std::uint8_t> split(256 * 4, 0);
  for (int v = 0; v < 256; ++v) {
    split[4 * v + 1] = std::uint8_t(v >> 4);
    split[4 * v + 2] = std::uint8_t(v & 15);
  }
  split_lut_.upload(split.data(), GL_RGBA, GL_UNSIGNED_BYTE);
  // combine table: (c, d) -> c + floor((d + 7) / 16), saturated (never reached: c, d <= 240)
  std::vector<std::uint8_t> comb(256 * 256);
  for (int c = 0; c < 256; ++c)
    for (int d = 0; d < 256; ++d) {
      const int v = c + (d + 7) / 16;
      comb[std::size_t(c) * 256 + d] = std::uint8_t(v > 255 ? 255 : v);
    }
  combine_lut_.upload(comb.data(), GL_RED, GL_UNSIGNED_BYTE);
  const auto vs = gl::fullscreen_vertex_shader();
  split_ = gl::program_from_strings(vs, gl::shader_source("blur_split.frag"), "blur_split");
  combine_ = gl::program_from_strings(vs, gl::shader_source("blur_combine.frag"), "blur_combine");
  float_ = gl::program_from_strings(vs, gl::shader_source("blur_float.frag"), "blur_float");
  float_linear_ = gl::program_from_strings(vs, gl::shader_source("blur_float_linear.frag"), "blur_float_linear");
  // the float blur reads its source bilinearly (four taps, blur_float.frag) through a sampler
  // object, so the source texture's own filter stays as its owner set it
  glGenSamplers(1, &linear_);
  glSamplerParameteri(linear_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glSamplerParameteri(linear_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glSamplerParameteri(linear_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glSamplerParameteri(linear_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  split_.set("u_src", 0);
  split_.set("u_split_lut", 1);
  combine_.set("u_accum", 0);
  combine_.set("u_combine_lut", 1);
  float_.set("u_src", 0);
  float_linear_.set("u_src", 0);
  gl::check("AccumBlur setup");
}

AccumBlur::~AccumBlur() { glDeleteSamplers(1, &linear_); }

const gl::Texture& AccumBlur::blur_emulated(const gl::Texture& src) {
  if (src.width() != w_ || src.height() != h_ || src.internal_format() != GL_R8)
    throw gl::GlError("AccumBlur::blur_emulated: source must be GL_R8 of the constructed size");
  vao_.bind();
  glDisable(GL_DEPTH_TEST);
  // pass 1: 16 shifted additive draws into the RGBA8 accumulation target
  fb_accum_.bind();
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  split_.use();
  src.bind(0);
  split_lut_.bind(1);
  const GLint loc = split_.loc("u_offset");
  for (const auto& off : kAccumOffsets) {
    glUniform2i(loc, off[0], off[1]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glDisable(GL_BLEND);
  // pass 2: recombination lookup into the 8-bit result
  fb_out8_.bind();
  combine_.use();
  accum_.bind(0);
  combine_lut_.bind(1);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  gl::check("AccumBlur::blur_emulated");
  return out8_;
}

const gl::Texture& AccumBlur::blur_float(const gl::Texture& src) {
  if (src.width() != w_ || src.height() != h_)
    throw gl::GlError("AccumBlur::blur_float: source must have the constructed size");
  vao_.bind();
  glDisable(GL_BLEND);
  fb_outf_.bind();
  const bool linear = src.internal_format() == GL_R32F;
  (linear ? float_linear_ : float_).use();
  src.bind(0);
  if (linear) glBindSampler(0, linear_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindSampler(0, 0);
  gl::check("AccumBlur::blur_float");
  return outf_;
}

}  // namespace huygens::viz
