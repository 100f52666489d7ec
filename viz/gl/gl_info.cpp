// huygens-gl-info: makes a headless EGL context and prints the renderer, a smoke check
// that rendering works here (e.g. with no DISPLAY). Exit 0 on success, 1 with the reason.
#include <cstdio>

#include "gl.hpp"

int main() {
  try {
    huygens::gl::HeadlessContext ctx;
    std::printf("GL_RENDERER: %s\nGL_VERSION:  %s\n", ctx.renderer().c_str(), ctx.version().c_str());
    // clear a small RGBA8 target and read it back
    huygens::gl::Texture tex(4, 4, GL_RGBA8);
    huygens::gl::Framebuffer fb(tex);
    fb.bind();
    glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    const auto img = huygens::gl::read_pixels_u8(fb);
    const bool ok = img.pixels[1] == 255 && img.pixels[0] == 0;
    std::printf("clear/readback: %s\n", ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "huygens-gl-info: %s\n", e.what());
    return 1;
  }
}
