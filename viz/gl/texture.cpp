// Textures, framebuffers, VAOs, readback and PNG I/O (stb from Debian's libstb: the
// implementation is compiled into libstb, so only the headers are included here).
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "gl.hpp"
#include "huygens/common/atomic_file.hpp"

namespace huygens::gl {

Texture::Texture(int width, int height, GLenum internal_format, int levels)
    : w_(width), h_(height), levels_(levels), fmt_(internal_format) {
  if (width <= 0 || height <= 0 || levels <= 0) throw GlError("Texture: bad size or level count");
  glGenTextures(1, &id_);
  glBindTexture(GL_TEXTURE_2D, id_);
  glTexStorage2D(GL_TEXTURE_2D, levels, internal_format, width, height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
  check("Texture: glTexStorage2D");
}

Texture::~Texture() {
  if (id_) glDeleteTextures(1, &id_);
}

Texture::Texture(Texture&& o) noexcept : id_(o.id_), w_(o.w_), h_(o.h_), levels_(o.levels_), fmt_(o.fmt_) { o.id_ = 0; }

Texture& Texture::operator=(Texture&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteTextures(1, &id_);
    id_ = o.id_;
    w_ = o.w_;
    h_ = o.h_;
    levels_ = o.levels_;
    fmt_ = o.fmt_;
    o.id_ = 0;
  }
  return *this;
}

void Texture::upload(const void* data, GLenum format, GLenum type, int level) {
  glBindTexture(GL_TEXTURE_2D, id_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const int lw = std::max(1, w_ >> level);
  const int lh = std::max(1, h_ >> level);
  glTexSubImage2D(GL_TEXTURE_2D, level, 0, 0, lw, lh, format, type, data);
  check("Texture::upload");
}

void Texture::set_filter(GLenum min_filter, GLenum mag_filter) {
  glBindTexture(GL_TEXTURE_2D, id_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(min_filter));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(mag_filter));
}

void Texture::set_wrap(GLenum wrap) {
  glBindTexture(GL_TEXTURE_2D, id_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
}

void Texture::bind(int unit) const {
  glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  glBindTexture(GL_TEXTURE_2D, id_);
}

Framebuffer::Framebuffer(const Texture& color, int level)
    : w_(std::max(1, color.width() >> level)), h_(std::max(1, color.height() >> level)) {
  glGenFramebuffers(1, &id_);
  glBindFramebuffer(GL_FRAMEBUFFER, id_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color.id(), level);
  const GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (st != GL_FRAMEBUFFER_COMPLETE) {
    glDeleteFramebuffers(1, &id_);
    id_ = 0;
    char buf[64];
    std::snprintf(buf, sizeof buf, "Framebuffer incomplete (status 0x%04X)", st);
    throw GlError(buf);
  }
}

Framebuffer::~Framebuffer() {
  if (id_) glDeleteFramebuffers(1, &id_);
}

Framebuffer::Framebuffer(Framebuffer&& o) noexcept : id_(o.id_), w_(o.w_), h_(o.h_) { o.id_ = 0; }

Framebuffer& Framebuffer::operator=(Framebuffer&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteFramebuffers(1, &id_);
    id_ = o.id_;
    w_ = o.w_;
    h_ = o.h_;
    o.id_ = 0;
  }
  return *this;
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, id_);
  glViewport(0, 0, w_, h_);
}

VertexArray::VertexArray() { glGenVertexArrays(1, &id_); }
VertexArray::~VertexArray() {
  if (id_) glDeleteVertexArrays(1, &id_);
}
VertexArray& VertexArray::operator=(VertexArray&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteVertexArrays(1, &id_);
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}

Image8 read_pixels_u8(const Framebuffer& fb, GLenum format) {
  int ch = 4;
  switch (format) {
    case GL_RED:
      ch = 1;
      break;
    case GL_RG:
      ch = 2;
      break;
    case GL_RGB:
      ch = 3;
      break;
    case GL_RGBA:
      ch = 4;
      break;
    default:
      throw GlError("read_pixels_u8: format must be GL_RED, GL_RG, GL_RGB or GL_RGBA");
  }
  Image8 img{fb.width(), fb.height(), ch, {}};
  img.pixels.resize(static_cast<std::size_t>(img.width) * img.height * ch);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, img.width, img.height, format, GL_UNSIGNED_BYTE, img.pixels.data());
  check("read_pixels_u8");
  return img;
}

std::vector<float> read_pixels_f32(const Framebuffer& fb, int channels) {
  static constexpr GLenum fmts[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  if (channels < 1 || channels > 4) throw GlError("read_pixels_f32: channels must be 1..4");
  std::vector<float> out(static_cast<std::size_t>(fb.width()) * fb.height() * channels);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id());
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, fb.width(), fb.height(), fmts[channels - 1], GL_FLOAT, out.data());
  check("read_pixels_f32");
  return out;
}

void flip_rows(Image8& img) {
  const std::size_t row = static_cast<std::size_t>(img.width) * img.channels;
  for (int y = 0; y < img.height / 2; ++y)
    std::swap_ranges(img.pixels.begin() + static_cast<std::ptrdiff_t>(y * row),
                     img.pixels.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     img.pixels.begin() + static_cast<std::ptrdiff_t>((img.height - 1 - y) * row));
}

void write_png(const std::string& path, const Image8& img) {
  if (img.channels < 1 || img.channels > 4 ||
      img.pixels.size() != static_cast<std::size_t>(img.width) * img.height * img.channels)
    throw GlError("write_png: inconsistent image for '" + path + "'");
  // encoded in memory, then written atomically (checked writes, no half-written PNG)
  std::string bytes;
  auto append = [](void* out, void* data, int size) {
    static_cast<std::string*>(out)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, img.width, img.height, img.channels, img.pixels.data(),
                              img.width * img.channels))
    throw GlError("write_png: cannot encode '" + path + "'");
  huygens::write_file_atomic(path, bytes);
}

Image8 read_png(const std::string& path, int channels) {
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, channels);
  if (!data) throw GlError("read_png: cannot read '" + path + "': " + stbi_failure_reason());
  Image8 img{w, h, channels ? channels : n, {}};
  img.pixels.assign(data, data + static_cast<std::size_t>(w) * h * img.channels);
  stbi_image_free(data);
  return img;
}

}  // namespace huygens::gl
