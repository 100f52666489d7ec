// huygens-gl-info: makes a headless EGL context and prints the renderer, a smoke check
// that rendering works here (e.g. with no DISPLAY). Exit 0 on success, 1 with the reason,
// 2 on a bad command line (it takes only --help).
#include <cstdio>
#include <cstring>

#include "gl.hpp"

int main(int argc, char** argv) {
  if (argc > 1) {
    const char* usage =
        "usage: huygens-gl-info   (no arguments: prints the GL renderer of a headless EGL context\n"
        "                          and checks a clear and readback)\n"
        "exit codes: 0 ok; 1 no GL context or a wrong readback; 2 bad usage\n";
    if (argc == 2 && std::strcmp(argv[1], "--help") == 0) {
      std::fputs(usage, stdout);
      return 0;
    }
    std::fprintf(stderr, "huygens-gl-info: unknown argument '%s'\n%s", argv[1], usage);
    return 2;
  }
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
