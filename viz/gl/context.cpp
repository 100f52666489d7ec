// Headless GL context through EGL's surfaceless platform (Mesa): no window, no display
// server, rendering into framebuffer objects only. GL and EGL are loaded with libepoxy.
#include <epoxy/egl.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "gl.hpp"

namespace huygens::gl {
namespace {

std::string egl_fail(const char* what) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%04X)", what, static_cast<unsigned>(eglGetError()));
  return buf;
}

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

void GLAPIENTRY debug_callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                               const void*) {
  if (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM)
    std::fprintf(stderr, "[gl debug] type 0x%X: %s\n", type, message);
}

}  // namespace

HeadlessContext::HeadlessContext(const ContextOptions& opt) {
  // surfaceless platform display (client extension EGL_MESA_platform_surfaceless)
  const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client_ext, "EGL_MESA_platform_surfaceless"))
    throw GlError("EGL: EGL_MESA_platform_surfaceless is not available (need Mesa's libEGL)");
  EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (dpy == EGL_NO_DISPLAY) throw GlError(egl_fail("eglGetPlatformDisplayEXT(SURFACELESS_MESA)"));
  EGLint maj = 0, min = 0;
  if (!eglInitialize(dpy, &maj, &min)) throw GlError(egl_fail("eglInitialize"));
  display_ = dpy;
  auto fail = [&](const char* what) {
    const std::string msg = egl_fail(what);
    eglTerminate(dpy);
    display_ = nullptr;
    throw GlError(msg);
  };
  if (!has_extension(eglQueryString(dpy, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    fail("EGL_KHR_surfaceless_context check");
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");

  // any config that can render desktop GL; there is no surface, so surface type is free
  const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
  EGLConfig cfg = nullptr;
  EGLint ncfg = 0;
  if (!eglChooseConfig(dpy, cfg_attr, &cfg, 1, &ncfg) || ncfg < 1) fail("eglChooseConfig(EGL_OPENGL_BIT)");

  const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION,
                             opt.major,
                             EGL_CONTEXT_MINOR_VERSION,
                             opt.minor,
                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                             EGL_CONTEXT_OPENGL_DEBUG,
                             opt.debug ? EGL_TRUE : EGL_FALSE,
                             EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
  if (ctx == EGL_NO_CONTEXT) fail("eglCreateContext(core profile)");
  context_ = ctx;
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    eglDestroyContext(dpy, ctx);
    context_ = nullptr;
    fail("eglMakeCurrent(surfaceless)");
  }
  if (opt.debug && epoxy_gl_version() >= 43) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, nullptr);
  }
  if (epoxy_gl_version() < opt.major * 10 + opt.minor) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "EGL context has GL %d.%d, need %d.%d", epoxy_gl_version() / 10,
                  epoxy_gl_version() % 10, opt.major, opt.minor);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    context_ = display_ = nullptr;
    throw GlError(buf);
  }
}

HeadlessContext::~HeadlessContext() {
  if (!display_) return;
  auto dpy = static_cast<EGLDisplay>(display_);
  if (context_) {
    if (eglGetCurrentContext() == static_cast<EGLContext>(context_))
      eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, static_cast<EGLContext>(context_));
  }
  // eglTerminate is reference-counted per display only with EGL_KHR_display_reference;
  // Mesa's surfaceless display is shared process-wide, so terminating here would kill
  // other live contexts on the same display. Release the thread state instead.
  eglReleaseThread();
}

HeadlessContext::HeadlessContext(HeadlessContext&& o) noexcept : display_(o.display_), context_(o.context_) {
  o.display_ = o.context_ = nullptr;
}

HeadlessContext& HeadlessContext::operator=(HeadlessContext&& o) noexcept {
  if (this != &o) {
    this->~HeadlessContext();
    display_ = o.display_;
    context_ = o.context_;
    o.display_ = o.context_ = nullptr;
  }
  return *this;
}

void HeadlessContext::make_current() const {
  if (!eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                      static_cast<EGLContext>(context_)))
    throw GlError(egl_fail("eglMakeCurrent"));
}

std::string HeadlessContext::renderer() const {
  const auto* s = glGetString(GL_RENDERER);
  return s ? reinterpret_cast<const char*>(s) : "";
}

std::string HeadlessContext::version() const {
  const auto* s = glGetString(GL_VERSION);
  return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace huygens::gl
