// Section "render": the renderer's per-pass times under the machine's GL (Mesa llvmpipe here),
// by running the two render benchmarks that own a GL context, so that huygens-bench itself stays
// free of GL: `huygens-viz --benchmark` (ground, surface, caustics and ship passes at 1280 x 720
// and 640 x 360, the simulation's share of a frame, the refraction coefficients' cost) and
// `huygens-caustics-bench` (caustics and the accumulation-buffer blur emulation against the
// paper's 18 ms, run time against error). Skipped, and said so, when the viewer was not built
// (HUYGENS_BUILD_VIZ=OFF) or no GL context can be made (huygens-gl-info fails); when a context
// can be made, a failing render benchmark counts as a failed check.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

#include "bench.hpp"

namespace huygens::bench {

namespace {

// Runs a command, returns its exit status (-1 when it could not start) and its output.
int run_capture(const std::string& cmd, std::string& out) {
  out.clear();
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return -1;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) out += buf.data();
  const int st = pclose(p);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

}  // namespace

void bench_render(Context& ctx) {
#if defined(HUYGENS_VIZ_EXE) && defined(HUYGENS_GL_INFO_EXE) && defined(HUYGENS_CAUSTICS_BENCH_EXE)
  std::string out;
  if (run_capture(HUYGENS_GL_INFO_EXE, out) != 0) {
    std::printf("\n== render: skipped: no GL context could be made (huygens-gl-info) ==\n%s", out.c_str());
    return;
  }
  const std::string scene = std::string(HUYGENS_SOURCE_DIR) + "/scenes/ocean.json";
  struct Job {
    std::string title, cmd;
  };
  const Job jobs[] = {
      {"huygens-viz --benchmark scenes/ocean.json (per-pass ms, llvmpipe unless a GPU is present)",
       std::string(HUYGENS_VIZ_EXE) + " '" + scene + "' --benchmark"},
      {std::string("huygens-caustics-bench") + (ctx.quick ? " --quick" : "") +
           " (caustics + accumulation-buffer blur, paper 004 sec. 5-6)",
       std::string(HUYGENS_CAUSTICS_BENCH_EXE) + (ctx.quick ? " --quick" : "")},
  };
  for (const Job& j : jobs) {
    const auto t0 = std::chrono::steady_clock::now();
    const int rc = run_capture(j.cmd, out);
    std::printf("\n== render: %s (%.1f s) ==\n%s", j.title.c_str(), seconds_since(t0), out.c_str());
    std::fflush(stdout);
    ctx.expect(rc == 0, "render: `" + j.cmd + "` exited " + std::to_string(rc));
  }
#else
  (void)ctx;
  std::printf("\n== render: skipped: built without the viewer (configure with -DHUYGENS_BUILD_VIZ=ON) ==\n");
#endif
}

}  // namespace huygens::bench
