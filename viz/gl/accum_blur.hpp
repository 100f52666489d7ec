// Accumulation-buffer blur emulation of paper 004 section 6 on the GPU (GL 3.3 core),
// and a plain float-target blur as the comparison path.
//
// Emulated path (Figure 8): the 8-bit source (GL_R8) is drawn 16 times, shifted by the
// offsets kAccumOffsets (kernel [1 2 1; 2 4 2; 1 2 1]), with additive blending into an
// RGBA8 target; each draw reads the source texel v and does a dependent lookup in a
// 256 x 1 table giving (0, v >> 4, v & 15, 0) (green = high 4 bits, blue = low 4 bits).
// A second pass reads c (green) and d (blue) and writes, through a 256 x 256 lookup,
// the gray level c + floor((d + 7) / 16) into a GL_R8 target. Equal bit for bit to
// accum_blur_reference() (tests/viz/accum_blur_test.cpp).
// Float path: one pass into GL_R32F, nine texelFetch taps weighted [1 2 1; 2 4 2; 1 2 1] / 16;
// for a GL_R32F source the same kernel as four bilinear taps at (+-1/2, +-1/2) texel (each
// averages a 2 x 2 block; faster under llvmpipe, and exact there because float textures are
// filtered in float, unlike 8-bit ones). Both clamp to edge.
#pragma once

#include "accum_blur_cpu.hpp"
#include "gl/gl.hpp"

namespace huygens::viz {

class AccumBlur {
 public:
  /// Allocates the targets and lookup tables for width x height images (a current GL context is needed).
  AccumBlur(int width, int height);
  ~AccumBlur();
  AccumBlur(const AccumBlur&) = delete;
  AccumBlur& operator=(const AccumBlur&) = delete;

  /// Blur an 8-bit GL_R8 texture of the constructed size by the emulation; returns the GL_R8 result.
  const gl::Texture& blur_emulated(const gl::Texture& src_r8);
  /// Blur any single-channel texture (GL_R8 read as [0,1], GL_R32F as is) in float; returns GL_R32F.
  const gl::Texture& blur_float(const gl::Texture& src);

  const gl::Texture& emulated_result() const { return out8_; }
  const gl::Framebuffer& emulated_framebuffer() const { return fb_out8_; }
  const gl::Texture& float_result() const { return outf_; }
  const gl::Framebuffer& float_framebuffer() const { return fb_outf_; }
  /// The RGBA8 accumulation target of the first pass (green = c, blue = d).
  const gl::Framebuffer& accumulation_framebuffer() const { return fb_accum_; }

 private:
  int w_, h_;
  gl::Texture split_lut_, combine_lut_, accum_, out8_, outf_;
  gl::Framebuffer fb_accum_, fb_out8_, fb_outf_;
  gl::Program split_, combine_, float_, float_linear_;
  gl::VertexArray vao_;
  GLuint linear_ = 0;
};

}  // namespace huygens::viz
