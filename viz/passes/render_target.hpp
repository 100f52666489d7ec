#pragma once
// The frame buffers the scene is drawn into (docs/viz.md "Anti-aliasing").
#include "gl.hpp"

namespace huygens {

/// Where the scene is drawn: a half-float colour buffer + depth renderbuffer (bind()), with
/// `samples` samples per pixel (multisample anti-aliasing: the edges of hulls, solids, the water's
/// outline and the deck are covered in part by each pixel; 1 = none), resolved into the
/// half-float texture hdr() (resolve_scene()); and the 8-bit display image (fbo(), color(),
/// read()) the renderer tone-maps that into.
class RenderTarget {
 public:
  /// Samples per pixel by default (clamped to what the driver offers).
  static constexpr int kDefaultSamples = 4;
  RenderTarget() = default;
  RenderTarget(int width, int height, int samples = kDefaultSamples);
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;
  RenderTarget(RenderTarget&& o) noexcept;
  RenderTarget& operator=(RenderTarget&& o) noexcept;
  int width() const { return w_; }
  int height() const { return h_; }
  /// The 8-bit display image's framebuffer (blit / read from here).
  GLuint fbo() const { return fbo_; }
  const gl::Texture& color() const { return color_; }
  /// Binds the half-float scene framebuffer for drawing.
  void bind() const;
  /// The drawn scene into hdr(): the samples of each pixel averaged (a blit; nothing without
  /// multisampling).
  void resolve_scene() const;
  int samples() const { return samples_; }
  const gl::Texture& hdr() const { return hdr_; }
  GLuint hdr_fbo() const { return hdr_fbo_; }
  /// RGBA8 pixels, top row first.
  gl::Image8 read() const;

 private:
  void release();
  gl::Texture color_, hdr_;
  GLuint depth_ = 0, fbo_ = 0, hdr_fbo_ = 0;
  GLuint ms_fbo_ = 0, ms_color_ = 0;  // the multisampled scene (samples_ > 1)
  int w_ = 0, h_ = 0, samples_ = 1;
};

}  // namespace huygens
