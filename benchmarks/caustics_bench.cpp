// huygens-caustics-bench [--quick] [--only speed|error] [--csv FILE] [--png FILE]
// Times the caustics pass (paper 004 sec. 5) and the blur (sec. 6, emulated and float) under
// the headless EGL context (llvmpipe here) next to the paper's 18 ms for generating and
// blurring caustics (GeForce 4 Ti 4200, 2003), and prints the renderer's run time against
// error: relative L2 of the blurred, normalised caustics against a photon-histogram reference.
// Kept out of huygens-bench so that its link line stays free of GL.
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "accum_blur.hpp"
#include "caustics.hpp"
#include "gl/gl.hpp"
#include "huygens/common/atomic_file.hpp"
#include "huygens/common/isa.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/stats.hpp"  // median_seconds

using namespace huygens;
using viz::CausticsArea;
using viz::CausticsParams;
using viz::CausticsProjection;

namespace {

struct Mode {
  const char* name;
  CausticsArea area;
  bool float_target;
  float offset;
  bool isotropic = false;
};

CausticsParams make_params(int mesh, int tex, const Mode& m, CausticsProjection proj) {
  CausticsParams p;
  p.mesh_cols = p.mesh_rows = mesh;
  p.texture_width = p.texture_height = tex;
  p.area = m.area;
  p.float_target = m.float_target;
  p.mip_lod_offset = m.offset;
  p.mip_isotropic_lod = m.isotropic;
  p.projection = proj;
  return p;
}

// The paper's path (MIP u8 + emulated blur) on a wind sea with a ship, oblique sun, into `png`:
// left the MIP mode, right the explicit mode; top row unblurred, bottom row blurred.
void write_panel(const std::string& png) {
  // the paper's path (MIP u8 + emulated blur) on a wind sea with a ship, oblique sun;
  // left: MIP mode, right: explicit mode, top row unblurred, bottom row blurred
  const auto field = viz::synthetic_wind_sea(384, 15.0 * 384 / 512, 1.0, 1.2, false);
  auto ship = viz::make_ellipse_hull(4.0f, 5.0f, 0.4f, 2.5f, 0.8f);
  ship.height_m = 0.3f;
  const int T = 512;
  gl::Image8 out{2 * T, 2 * T, 1, std::vector<std::uint8_t>(std::size_t(4) * T * T)};
  viz::AccumBlur blur(T, T);
  for (int k = 0; k < 2; ++k) {
    auto p = make_params(96, T, Mode{"", k ? CausticsArea::Explicit : CausticsArea::Mip, false, 0.5f},
                         CausticsProjection::Linear);
    p.sun_dir = {0.3f, 0.2f, -1.0f};
    viz::CausticsRenderer r(p);
    r.render(field.view(), &ship);
    const auto raw = gl::read_pixels_u8(r.framebuffer(), GL_RED);
    blur.blur_emulated(r.texture());
    const auto bl = gl::read_pixels_u8(blur.emulated_framebuffer(), GL_RED);
    for (int y = 0; y < T; ++y)
      for (int x = 0; x < T; ++x) {
        // GL rows are bottom first; the PNG is top first
        out.pixels[std::size_t(T - 1 - y) * 2 * T + std::size_t(k * T + x)] = raw.pixels[std::size_t(y) * T + x];
        out.pixels[std::size_t(2 * T - 1 - y) * 2 * T + std::size_t(k * T + x)] = bl.pixels[std::size_t(y) * T + x];
      }
  }
  gl::write_png(png, out);
  std::printf("wrote %s\n", png.c_str());
}

// The paper's sizes (N = 512, margin 64 -> 384 visible, subsampled by 4 -> 96), each pass as a
// ratio to a copy pass measured in the same run.
Table speed_table(int reps) {
  // baseline measured in the same run: one full-screen texelFetch copy into an R8 target
  // (llvmpipe's fill rate), so the passes can be compared as ratios on a loaded machine
  const auto copy_prog = gl::program_from_strings(gl::fullscreen_vertex_shader(), R"(#version 330 core
uniform sampler2D u_src;
out vec4 o_color;
void main() { o_color = vec4(texelFetch(u_src, ivec2(gl_FragCoord.xy), 0).r); }
)",
                                                  "copy");
  Table t({"mesh", "texture", "field", "pass", "cpu mesh ms", "median ms", "x copy pass", "paper ms"});
  struct Size {
    int mesh, tex, field;
  };
  for (const Size& sz : {Size{96, 512, 384}, Size{192, 1024, 768}}) {
    stop_request::throw_if_requested("the speed table abandoned at mesh " + std::to_string(sz.mesh));
    const auto field = viz::synthetic_wind_sea(sz.field, 15.0 * sz.field / 512.0, 1.0, 0.6, false);
    const Mode modes[] = {{"caustics MIP u8 (paper)", CausticsArea::Mip, false, 0.5f},
                          {"caustics explicit u8", CausticsArea::Explicit, false, 0.0f},
                          {"caustics MIP f32", CausticsArea::Mip, true, 0.5f},
                          {"caustics explicit f32", CausticsArea::Explicit, true, 0.0f}};
    const std::string m = std::to_string(sz.mesh), x = std::to_string(sz.tex), f = std::to_string(sz.field);
    viz::AccumBlur blur(sz.tex, sz.tex);
    gl::Texture src(sz.tex, sz.tex, GL_R8), dst(sz.tex, sz.tex, GL_R8);
    gl::Framebuffer dst_fb(dst);
    gl::VertexArray vao;
    const double copy = median_seconds(reps, [&] {
      dst_fb.bind();
      vao.bind();
      copy_prog.use();
      src.bind(0);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glFinish();
    });
    t.add({m, x, f, "copy pass (baseline)", "", num(copy * 1e3, 3), "1", ""});
    for (const auto& md : modes) {
      viz::CausticsRenderer r(make_params(sz.mesh, sz.tex, md, CausticsProjection::Linear));
      double cpu = 0;
      const double sec = median_seconds(reps, [&] {
        r.render(field.view());
        glFinish();
        cpu = r.last_cpu_seconds();
      });
      t.add({m, x, f, md.name, num(cpu * 1e3, 3), num(sec * 1e3, 3), num(sec / copy, 3), ""});
    }
    viz::CausticsRenderer paper(make_params(sz.mesh, sz.tex, modes[0], CausticsProjection::Linear));
    paper.render(field.view());
    viz::CausticsRenderer flt(make_params(sz.mesh, sz.tex, modes[3], CausticsProjection::Linear));
    flt.render(field.view());
    glFinish();
    const double be = median_seconds(reps, [&] {
      blur.blur_emulated(paper.texture());
      glFinish();
    });
    const double bf = median_seconds(reps, [&] {
      blur.blur_float(flt.texture());
      glFinish();
    });
    const double both = median_seconds(reps, [&] {
      paper.render(field.view());
      blur.blur_emulated(paper.texture());
      glFinish();
    });
    t.add({m, x, f, "blur emulated (16 draws + lookup)", "", num(be * 1e3, 3), num(be / copy, 3), ""});
    t.add({m, x, f, "blur float", "", num(bf * 1e3, 3), num(bf / copy, 3), ""});
    t.add({m, x, f, "MIP u8 caustics + emulated blur", "", num(both * 1e3, 3), num(both / copy, 3),
           sz.mesh == 96 ? "18" : ""});
  }
  std::printf("\n== caustics speed (median of %d, glFinish after each) ==\n%s", reps, t.text().c_str());
  std::fflush(stdout);  // each table is out when it is done, also into a file or a pipe
  return t;
}

// Run time against error: each mode against a photon-histogram reference.
Table error_table(bool quick) {
  const int tex = quick ? 256 : 512, n = quick ? 257 : 385, per_cell = quick ? 8 : 16, border = tex / 16;
  Table t(
      {"field", "mode", "projection", "mesh", "ms (caustics + blur)", "rel L2", "rel L2 / contrast", "total light"});
  struct FieldCase {
    const char* name;
    viz::SyntheticField f;
  };
  const FieldCase fields[] = {{"wind sea", viz::synthetic_wind_sea(n, 2.0, 0.5, 0.6, false)},
                              {"ring wave", viz::synthetic_ring_wave(n, 2.0, 0.5, 0.6)}};
  const Mode modes[] = {{"explicit f32 + float blur", CausticsArea::Explicit, true, 0.0f},
                        {"MIP o=0 f32 + float blur", CausticsArea::Mip, true, 0.0f},
                        {"MIP o=0.5 f32 + float blur", CausticsArea::Mip, true, 0.5f},
                        {"MIP o=0.5 isotropic f32 + float blur", CausticsArea::Mip, true, 0.5f, true},
                        {"explicit u8 + emulated blur", CausticsArea::Explicit, false, 0.0f},
                        {"MIP o=0 u8 + emulated blur", CausticsArea::Mip, false, 0.0f},
                        {"MIP o=0.5 u8 + emulated blur", CausticsArea::Mip, false, 0.5f}};
  viz::AccumBlur blur(tex, tex);
  for (const auto& fc : fields) {
    auto p0 = make_params(96, tex, modes[0], CausticsProjection::Exact);
    const auto t0 = std::chrono::steady_clock::now();
    const auto ref = viz::blur121_f32(viz::photon_caustics(p0, fc.f.view(), per_cell, 1), tex, tex);
    const double tr = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto ref2 = viz::blur121_f32(viz::photon_caustics(p0, fc.f.view(), per_cell, 2), tex, tex);
    const auto nd = viz::compare_caustics(ref2, ref, tex, tex, border);
    t.add({fc.name, fmt("photon reference, %d^2 per cell (noise floor)", per_cell), "exact", std::to_string(n),
           num(tr * 1e3, 4), num(nd.rel_l2 / std::sqrt(2.0), 3), num(nd.rel_l2_contrast / std::sqrt(2.0), 3), "1"});
    for (const auto& m : modes)
      for (auto proj : {CausticsProjection::Linear, CausticsProjection::Exact})
        for (int mesh : {48, 96, 192}) {
          if (proj == CausticsProjection::Exact && mesh != 96) continue;
          stop_request::throw_if_requested(std::string("the error table abandoned at ") + fc.name + ", " + m.name);
          viz::CausticsRenderer r(make_params(mesh, tex, m, proj));
          const double s = median_seconds(quick ? 3 : 7, [&] {
            r.render(fc.f.view());
            if (m.float_target)
              blur.blur_float(r.texture());
            else
              blur.blur_emulated(r.texture());
            glFinish();
          });
          std::vector<float> img;
          if (m.float_target) {
            img = gl::read_pixels_f32(blur.float_framebuffer(), 1);
          } else {
            const auto u8 = gl::read_pixels_u8(blur.emulated_framebuffer(), GL_RED);
            img.assign(u8.pixels.begin(), u8.pixels.end());
            for (auto& v : img) v /= r.params().unit_level_u8;
          }
          const auto d = viz::compare_caustics(img, ref, tex, tex, border);
          t.add({fc.name, m.name, proj == CausticsProjection::Linear ? "linear" : "exact", std::to_string(mesh),
                 num(s * 1e3, 3), num(d.rel_l2, 3), num(d.rel_l2_contrast, 3), num(d.mean_a / d.mean_b, 4)});
        }
  }
  std::printf(
      "\n== caustics run time against error (texture %d^2, surface %d^2, depth 0.5 m, sun overhead; "
      "errors on the interior, both blurred and normalised to mean 1) ==\n%s",
      tex, n, t.text().c_str());
  std::fflush(stdout);
  return t;
}

}  // namespace

int bench_main(int argc, char** argv) {
  bool quick = false;
  std::string csv, png, only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw UsageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--quick")
      quick = true;
    else if (a == "--csv")
      csv = nonempty_arg(a, value());
    else if (a == "--png")
      png = nonempty_arg(a, value());
    else if (a == "--only")
      only = nonempty_arg(a, value());
    else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: huygens-caustics-bench [--quick] [--only speed|error] [--csv FILE] [--png FILE]\n"
          "exit codes: 0 ok; 1 a GL or write failure; 2 bad usage; 130/143 stopped by SIGINT/SIGTERM\n"
          "  (the table being measured is abandoned; the complete ones are printed, and written to\n"
          "  --csv with a first line that says the run stopped; a second signal ends it at once)\n");
      return 0;
    } else
      throw UsageError("unknown argument '" + a + "'");
  }
  if (!only.empty() && only != "speed" && only != "error") throw UsageError("--only takes 'speed' or 'error'");
  stop_request::install();                      // SIGINT/SIGTERM: the table being measured is abandoned
  for (const std::string& target : {csv, png})  // checked before the run, not after it
    if (!target.empty()) check_output_file(target);
  const std::string machine = machine_line(omp_get_max_threads());
  std::printf("%s\n", machine.c_str());  // where the figures ran
  {
    gl::HeadlessContext ctx;
    const char* lp = std::getenv("LP_NUM_THREADS");
    std::printf("GL: %s, %s (LP_NUM_THREADS=%s)\n", ctx.renderer().c_str(), ctx.version().c_str(), lp ? lp : "unset");
    std::fflush(stdout);
    std::vector<std::pair<std::string, Table>> tables;
    std::string stopped;  // what a SIGINT/SIGTERM abandoned
    try {
      if (!png.empty()) write_panel(png);
      if (only.empty() || only == "speed") tables.emplace_back("caustics speed", speed_table(quick ? 5 : 15));
      if (only.empty() || only == "error") tables.emplace_back("caustics error", error_table(quick));
    } catch (const StopRequested& e) {
      stopped = e.what();
    }
    std::printf("\nload average (1 min) at the end: %.2f\n", load_average());
    if (!csv.empty()) {  // the complete tables; a stopped run says so in its first line, then the machine line
      std::string text = stopped.empty() ? ""
                                         : "# stopped by " + std::string(stop_request::signal_name()) + ": " + stopped +
                                               "; the tables below are complete\n";
      text += "# " + machine + "; load average at the end " + fmt("%.2f", load_average()) + "\n";
      for (const auto& [title, table] : tables) text += "# " + title + "\n" + table.csv() + "\n";
      write_file_atomic(csv, text);
    }
    if (!stopped.empty())
      throw StopRequested(stopped + "; " + std::to_string(tables.size()) + " complete table(s) printed above" +
                          (csv.empty() ? "" : " and in " + csv));
  }
  return 0;
}

int main(int argc, char** argv) {
  return run_program("huygens-caustics-bench", argv, [&]() { return bench_main(argc, argv); });
}
