// huygens_gl: the small OpenGL infrastructure shared by the renderer passes, the
// visualizer app and the render tests. Headless EGL context, shader programs,
// textures/framebuffers, readback and PNG I/O. GL functions are loaded with libepoxy,
// so this header includes <epoxy/gl.h> (include it before any other GL header).
// The API is documented in viz/gl/README.md.
#pragma once

#include <epoxy/gl.h>

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace huygens::gl {

/// Any GL/EGL failure: context creation, shader compile/link (with the info log),
/// incomplete framebuffer, GL error flag, PNG I/O.
struct GlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws GlError("<where>: GL error 0x....") if glGetError() reports an error.
void check(std::string_view where);

// ---------------------------------------------------------------------------------
// Headless context: EGL surfaceless platform (Mesa), no window, no display server.

struct ContextOptions {
  /// Requested core-profile version (Mesa llvmpipe returns its highest compatible one, 4.5).
  int major = 3;
  int minor = 3;
  /// Create a debug context and print GL debug messages of severity medium/high to stderr.
  bool debug = false;
};

/// Owns an EGL display + core-profile context made current on the creating thread with
/// no surface (EGL_KHR_surfaceless_context). All rendering goes to framebuffer objects.
/// Move-only. Throws GlError naming the failing EGL call and the EGL error code.
class HeadlessContext {
 public:
  explicit HeadlessContext(const ContextOptions& opt = {});
  ~HeadlessContext();
  HeadlessContext(HeadlessContext&& o) noexcept;
  HeadlessContext& operator=(HeadlessContext&& o) noexcept;
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  /// Make the context current on the calling thread (it is current after construction).
  void make_current() const;
  /// GL_RENDERER / GL_VERSION strings, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string renderer() const;
  std::string version() const;

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

// ---------------------------------------------------------------------------------
// Shaders

/// The source of a file of the project's shaders/ directory by base name ("caustics.vert"),
/// compiled into huygens_gl at build time (huygens_embed); throws GlError for an unknown name.
std::string_view shader_source(std::string_view file);

/// A linked GLSL program. Move-only RAII wrapper around the GL name.
class Program {
 public:
  Program() = default;
  explicit Program(GLuint id) : id_(id) {}
  ~Program();
  Program(Program&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  Program& operator=(Program&& o) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }
  /// Uniform location; -1 if the uniform does not exist or was optimised away.
  GLint loc(const char* name) const { return glGetUniformLocation(id_, name); }
  // Uniform setters: bind the program for the update and restore the previous one (GL 3.3).
  void set(const char* name, int v) const;
  void set(const char* name, float v) const;
  void set(const char* name, float x, float y) const;
  void set(const char* name, float x, float y, float z) const;
  void set(const char* name, float x, float y, float z, float w) const;
  /// Column-major 3x3 / 4x4 matrix (e.g. glm::value_ptr(m)).
  void set_mat3(const char* name, const float* m) const;
  void set_mat4(const char* name, const float* m) const;

 private:
  GLuint id_ = 0;
};

/// Compile and link a vertex + fragment program from source strings. `name` is used in
/// error messages. Throws GlError with the compile or link log. `geometry` may be empty.
Program program_from_strings(std::string_view vertex_src, std::string_view fragment_src, std::string_view name,
                             std::string_view geometry_src = {});
/// Same from the compiled-in shaders/ files (shader_source()); `geometry_file` may be empty.
Program program_from_shaders(std::string_view vertex_file, std::string_view fragment_file,
                             std::string_view geometry_file = {});

/// The vertex shader of a full-screen triangle (no vertex buffer needed: draw with
/// glDrawArrays(GL_TRIANGLES, 0, 3) and any VAO bound). Outputs `vec2 uv` in [0,1]^2.
std::string_view fullscreen_vertex_shader();

// ---------------------------------------------------------------------------------
// Textures and framebuffers

/// A 2D texture (optionally with a MIP chain). Move-only RAII.
class Texture {
 public:
  Texture() = default;
  /// Allocates width x height storage with `internal_format` (GL_RGBA8, GL_R8, GL_R32F,
  /// GL_RGBA32F, ...), `levels` MIP levels (1 = no MIP map), nearest filtering, clamp to edge.
  Texture(int width, int height, GLenum internal_format, int levels = 1);
  ~Texture();
  Texture(Texture&& o) noexcept;
  Texture& operator=(Texture&& o) noexcept;
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;

  GLuint id() const { return id_; }
  int width() const { return w_; }
  int height() const { return h_; }
  int levels() const { return levels_; }
  GLenum internal_format() const { return fmt_; }
  /// Upload a whole level; `format`/`type` describe `data` (e.g. GL_RED, GL_UNSIGNED_BYTE).
  /// Rows are tightly packed (unpack alignment 1 is set).
  void upload(const void* data, GLenum format, GLenum type, int level = 0);
  /// Set min/mag filters and wrap mode (GL_CLAMP_TO_EDGE, GL_REPEAT, ...).
  void set_filter(GLenum min_filter, GLenum mag_filter);
  void set_wrap(GLenum wrap);
  /// Bind to texture unit `unit`.
  void bind(int unit) const;

 private:
  GLuint id_ = 0;
  int w_ = 0, h_ = 0, levels_ = 0;
  GLenum fmt_ = 0;
};

/// A framebuffer object with one colour attachment (a Texture level it does not own).
/// Move-only RAII. Throws GlError if incomplete.
class Framebuffer {
 public:
  Framebuffer() = default;
  explicit Framebuffer(const Texture& color, int level = 0);
  ~Framebuffer();
  Framebuffer(Framebuffer&& o) noexcept;
  Framebuffer& operator=(Framebuffer&& o) noexcept;
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  GLuint id() const { return id_; }
  int width() const { return w_; }
  int height() const { return h_; }
  /// Bind as GL_FRAMEBUFFER and set the viewport to the whole attachment.
  void bind() const;

 private:
  GLuint id_ = 0;
  int w_ = 0, h_ = 0;
};

/// A VAO with nothing attached (core profile needs a VAO bound for any draw).
class VertexArray {
 public:
  VertexArray();
  ~VertexArray();
  VertexArray(VertexArray&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  VertexArray& operator=(VertexArray&& o) noexcept;
  VertexArray(const VertexArray&) = delete;
  VertexArray& operator=(const VertexArray&) = delete;
  GLuint id() const { return id_; }
  void bind() const { glBindVertexArray(id_); }

 private:
  GLuint id_ = 0;
};

// ---------------------------------------------------------------------------------
// Readback and PNG

/// 8-bit image, rows top to bottom unless stated, `channels` interleaved (1..4).
struct Image8 {
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> pixels;  ///< width*height*channels bytes
};

/// Read the framebuffer's colour attachment (GL rows: bottom row first) as 8-bit.
/// `format` GL_RED (1 channel), GL_RG, GL_RGB or GL_RGBA. Binds `fb`.
Image8 read_pixels_u8(const Framebuffer& fb, GLenum format = GL_RGBA);
/// Read the framebuffer as floats (bottom row first), `channels` = 1..4.
std::vector<float> read_pixels_f32(const Framebuffer& fb, int channels = 1);

/// Reverse row order in place (GL bottom-up <-> image top-down).
void flip_rows(Image8& img);
/// Write a PNG (stb_image_write); the rows are written in the order stored. Throws GlError.
void write_png(const std::string& path, const Image8& img);
/// Read a PNG (stb_image); `channels` 0 keeps the file's channel count. Throws GlError.
Image8 read_png(const std::string& path, int channels = 0);

}  // namespace huygens::gl
