// Section "render": the renderer's per-pass times under the machine's GL (Mesa llvmpipe here),
// by running the two render benchmarks that own a GL context, so that huygens-bench itself stays
// free of GL: `huygens-viz --benchmark` (ground, surface, caustics and ship passes at 1280 x 720
// and 640 x 360, the simulation's share of a frame, the refraction coefficients' cost) and
// `huygens-caustics-bench` (caustics and the accumulation-buffer blur emulation against the
// paper's 18 ms, run time against error). Skipped, and said so, when the viewer was not built
// (HUYGENS_BUILD_VIZ=OFF), its programs are not found or no GL context can be made
// (huygens-gl-info fails); when a context can be made, a failing render benchmark counts as a
// failed check. The viewer gets the embedded ocean.json written to a temporary folder.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
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

namespace fs = std::filesystem;

// A program of the viewer: beside huygens-bench (an installed bin/), else at its place in the
// build tree relative to huygens-bench's folder; empty when neither exists.
std::string sibling_program(const std::string& name, const std::string& build_rel) {
  std::error_code ec;
  const fs::path dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  for (const fs::path& p : {dir / name, dir / build_rel})
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  return {};
}

// The shipped scene written to a fresh temporary folder (removed by the caller).
fs::path write_temp_scene(const std::string& name) {
  std::string tmpl = (fs::temp_directory_path() / "huygens-bench-XXXXXX").string();
  if (!mkdtemp(tmpl.data())) throw std::runtime_error("huygens-bench: cannot make a temporary folder");
  const fs::path file = fs::path(tmpl) / name;
  std::ofstream(file, std::ios::binary) << shipped_scene(name);
  return file;
}

}  // namespace

void bench_render(Context& ctx) {
#if defined(HUYGENS_VIZ_REL) && defined(HUYGENS_GL_INFO_REL) && defined(HUYGENS_CAUSTICS_BENCH_REL)
  const std::string viz = sibling_program("huygens-viz", HUYGENS_VIZ_REL),
                    gl_info = sibling_program("huygens-gl-info", HUYGENS_GL_INFO_REL),
                    caustics = sibling_program("huygens-caustics-bench", HUYGENS_CAUSTICS_BENCH_REL);
  if (viz.empty() || gl_info.empty() || caustics.empty()) {
    std::printf("\n== render: skipped: huygens-viz, huygens-gl-info or huygens-caustics-bench not found ==\n");
    return;
  }
  std::string out;
  if (run_capture(gl_info, out) != 0) {
    std::printf("\n== render: skipped: no GL context could be made (huygens-gl-info) ==\n%s", out.c_str());
    return;
  }
  const fs::path scene = write_temp_scene("ocean.json");
  struct Job {
    std::string title, cmd;
  };
  const Job jobs[] = {
      {"huygens-viz --benchmark scenes/ocean.json (per-pass ms, llvmpipe unless a GPU is present)",
       "'" + viz + "' '" + scene.string() + "' --benchmark"},
      {std::string("huygens-caustics-bench") + (ctx.quick ? " --quick" : "") +
           " (caustics + accumulation-buffer blur, paper 004 sec. 5-6)",
       "'" + caustics + "'" + (ctx.quick ? " --quick" : "")},
  };
  for (const Job& j : jobs) {
    const auto t0 = std::chrono::steady_clock::now();
    const int rc = run_capture(j.cmd, out);
    std::printf("\n== render: %s (%.1f s) ==\n%s", j.title.c_str(), seconds_since(t0), out.c_str());
    std::fflush(stdout);
    ctx.expect(rc == 0, "render: `" + j.cmd + "` exited " + std::to_string(rc));
  }
  std::error_code ec;
  fs::remove_all(scene.parent_path(), ec);
#else
  (void)ctx;
  std::printf("\n== render: skipped: built without the viewer (configure with -DHUYGENS_BUILD_VIZ=ON) ==\n");
#endif
}

}  // namespace huygens::bench
