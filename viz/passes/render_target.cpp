#include "render_target.hpp"

#include <algorithm>
#include <utility>

namespace huygens {

RenderTarget::RenderTarget(int width, int height, int samples)
    : color_(width, height, GL_RGBA8), hdr_(width, height, GL_RGBA16F), w_(width), h_(height) {
  color_.set_filter(GL_LINEAR, GL_LINEAR);
  hdr_.set_filter(GL_NEAREST, GL_NEAREST);
  GLint most = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &most);
  samples_ = std::clamp(samples, 1, static_cast<int>(most));
  const GLsizei n = samples_;
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_ > 1 ? n : 0, GL_DEPTH_COMPONENT24, width, height);
  glGenFramebuffers(1, &hdr_fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, hdr_fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, hdr_.id(), 0);
  if (samples_ == 1) glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw gl::GlError("RenderTarget: incomplete half-float framebuffer");
  if (samples_ > 1) {
    glGenRenderbuffers(1, &ms_color_);
    glBindRenderbuffer(GL_RENDERBUFFER, ms_color_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_RGBA16F, width, height);
    glGenFramebuffers(1, &ms_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ms_color_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw gl::GlError("RenderTarget: incomplete multisampled framebuffer");
  }
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_.id(), 0);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw gl::GlError("RenderTarget: incomplete framebuffer");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::check("RenderTarget");
}

void RenderTarget::release() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (hdr_fbo_) glDeleteFramebuffers(1, &hdr_fbo_);
  if (ms_fbo_) glDeleteFramebuffers(1, &ms_fbo_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  if (ms_color_) glDeleteRenderbuffers(1, &ms_color_);
  depth_ = fbo_ = hdr_fbo_ = ms_fbo_ = ms_color_ = 0;
}

RenderTarget::~RenderTarget() { release(); }

RenderTarget::RenderTarget(RenderTarget&& o) noexcept
    : color_(std::move(o.color_)),
      hdr_(std::move(o.hdr_)),
      depth_(o.depth_),
      fbo_(o.fbo_),
      hdr_fbo_(o.hdr_fbo_),
      ms_fbo_(o.ms_fbo_),
      ms_color_(o.ms_color_),
      w_(o.w_),
      h_(o.h_),
      samples_(o.samples_) {
  o.depth_ = o.fbo_ = o.hdr_fbo_ = o.ms_fbo_ = o.ms_color_ = 0;
}

RenderTarget& RenderTarget::operator=(RenderTarget&& o) noexcept {
  if (this != &o) {
    release();
    color_ = std::move(o.color_);
    hdr_ = std::move(o.hdr_);
    depth_ = o.depth_;
    fbo_ = o.fbo_;
    hdr_fbo_ = o.hdr_fbo_;
    ms_fbo_ = o.ms_fbo_;
    ms_color_ = o.ms_color_;
    w_ = o.w_;
    h_ = o.h_;
    samples_ = o.samples_;
    o.depth_ = o.fbo_ = o.hdr_fbo_ = o.ms_fbo_ = o.ms_color_ = 0;
  }
  return *this;
}

void RenderTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo_ ? ms_fbo_ : hdr_fbo_);
  glViewport(0, 0, w_, h_);
}

void RenderTarget::resolve_scene() const {
  if (!ms_fbo_) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, ms_fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, hdr_fbo_);
  glBlitFramebuffer(0, 0, w_, h_, 0, 0, w_, h_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

gl::Image8 RenderTarget::read() const {
  gl::Image8 img;
  img.width = w_;
  img.height = h_;
  img.channels = 4;
  img.pixels.resize(static_cast<std::size_t>(w_) * h_ * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w_, h_, GL_RGBA, GL_UNSIGNED_BYTE, img.pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  gl::check("RenderTarget::read");
  gl::flip_rows(img);
  return img;
}
}  // namespace huygens
