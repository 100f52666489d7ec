// The interactive window of huygens-viz: GLFW (GL 3.3 core, loaded by libepoxy), the
// simulation on its own thread (Runner, docs/design.md 2), the renderer drawing the newest
// frames interpolated to the display time, Dear ImGui for the panel, mouse and keys.
#include "gl.hpp"  // epoxy before any other GL header
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "app.hpp"
#include "dye.hpp"
#include "foam.hpp"
#include "gl.hpp"
#include "huygens/common/program.hpp"
#include "huygens/pipeline/command.hpp"
#include "huygens/pipeline/runner.hpp"
#include "huygens/solvers/registry.hpp"
#include "scene_view.hpp"

namespace huygens {

namespace {

struct App {
  GLFWwindow* window = nullptr;
  Runner* runner = nullptr;
  WindowOptions opt;
  /// The scene as the user named it.
  std::string scene_name;
  SceneView view;
  OrbitCamera camera;
  RenderSettings settings;
  std::vector<float> field;
  bool show_panel = true;
  bool interpolate = true;
  /// The solver's run-time features (RenderInfo::toggles) and their state as the panel shows it;
  /// as the scene has them at start (and after Reset).
  std::vector<RenderToggle> toggles, toggles_at_start;
  bool screenshot_requested = false;
  int screenshot_count = 0;
  std::string last_screenshot;
  bool quit = false;
  double time_scale = 1.0;
  /// Plan view (P): the colour-mapped field with colour bar and axes instead of the picture;
  /// P steps through the level, and for a flow (LBM) its speed, dye and foam, back to the picture.
  bool plan = false;
  PlanQuantity plan_quantity = PlanQuantity::level;
  /// The newest frame's velocity (LBM) and the dye and foam it carries since the start (dye.hpp,
  /// foam.hpp).
  bool has_velocity = false;
  std::vector<float> velocity;
  std::unique_ptr<DyeField> dye;
  std::unique_ptr<FoamField> foam;
  double dye_time = 0.0;
  /// The camera follows the first ship until the user orbits, pans or zooms.
  bool follow = false;
  /// The panel's width (unit: px; the plan view leaves it free).
  float panel_width = 0.0f;
  /// Frames drawn (the render rows' call count in the timing table).
  unsigned long long frames_drawn = 0;
  // stones: radius and depth of the dent (the default is seen at the default scene's start-up
  // view: a 5 cm dent of 1 cm made a barely visible dimple)
  float stone_radius = 0.15f, stone_depth = 0.03f;
  /// Mesh subsampling factor (the renderer is rebuilt when it changes).
  int subsample = 4;
  // mouse state
  bool orbiting = false, panning = false, left_down = false, dragged_far = false;
  int drag_ship = -1;
  double press_x = 0, press_y = 0, last_x = 0, last_y = 0;
  double drag_last_t = 0;
  glm::dvec2 drag_last_pos{0.0}, drag_target{0.0}, drag_velocity{0.0};
  /// The last ShipTarget carried a non-zero cursor velocity (stopped by hold_drag_target()).
  bool drag_moving = false;
  // the ships as drawn in the last frame: where the solver has them (FrameInfo::ships),
  // interpolated to the display time like the heights; picking uses them too
  std::vector<ShipPose> ships_drawn;
  std::string message;
};

App* app_of(GLFWwindow* w) { return static_cast<App*>(glfwGetWindowUserPointer(w)); }

// Water point under the cursor: the view ray meets z = eta(x, y) (plane z = 0, then one
// correction with the height there). False when the ray misses the visible region.
bool cursor_hit(const App& a, double cx, double cy, glm::dvec2& hit) {
  int w, h;
  glfwGetWindowSize(a.window, &w, &h);
  if (w <= 0 || h <= 0) return false;
  const double ndc_x = 2.0 * cx / w - 1.0, ndc_y = 1.0 - 2.0 * cy / h;
  glm::dvec3 o, d;
  a.camera.ray_through(ndc_x, ndc_y, static_cast<double>(w) / h, o, d);
  if (std::abs(d.z) < 1e-9) return false;
  double z = 0.0;
  glm::dvec3 p;
  for (int it = 0; it < 3; ++it) {
    const double s = (z - o.z) / d.z;
    if (s <= 0) return false;
    p = o + s * d;
    const GridPlacement& g = a.view.grid;
    const double fj = (p.x - g.x0) / g.dx, fi = (p.y - g.y0) / g.dx;
    if (fj < 0 || fi < 0 || fj > g.cols - 1 || fi > g.rows - 1) return false;
    z = a.field[static_cast<std::size_t>(std::lround(fi)) * g.cols + static_cast<std::size_t>(std::lround(fj))] -
        a.view.height_offset;
  }
  hit = {p.x, p.y};
  return true;
}

// Refused commands come back from the runner: a refused toggle's control is un-ticked (set back
// to the state the solver kept), anything else is shown in the panel.
void take_refused(App& a) {
  Command c;
  while (a.runner->next_refused(c)) {
    if (const auto* t = std::get_if<cmd::Toggle>(&c)) {
      for (RenderToggle& g : a.toggles)
        if (t->feature == g.name) g.on = !t->on;
      a.message = std::string("refused: toggle ") + std::string(t->feature.view()) + (t->on ? " on" : " off");
    } else {
      a.message = std::string("refused: ") + command_kind(c);
    }
    std::printf("huygens-viz: %s\n", a.message.c_str());
  }
}

int ship_under(const App& a, glm::dvec2 p) {
  for (std::size_t i = 0; i < a.ships_drawn.size(); ++i) {
    const ShipPose& s = a.ships_drawn[i];
    const double c = std::cos(s.heading), sn = std::sin(s.heading);
    const double lx = c * (p.x - s.x) + sn * (p.y - s.y), ly = -sn * (p.x - s.x) + c * (p.y - s.y);
    if (std::abs(lx) <= 0.6 * s.length && std::abs(ly) <= 0.5 * s.beam + 0.1 * s.length) return static_cast<int>(i);
  }
  return -1;
}

// Reads the window's back buffer (after the panel is drawn, before the swap).
void save_screenshot(App& a, int width, int height) {
  std::string path = a.opt.screenshot;
  if (path.empty()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "huygens-viz-%04d.png", a.screenshot_count);
    path = buf;
  }
  ++a.screenshot_count;
  gl::Image8 img;
  img.width = width;
  img.height = height;
  img.channels = 4;
  img.pixels.resize(static_cast<std::size_t>(width) * height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, img.pixels.data());
  for (std::size_t p = 0; p < img.pixels.size(); p += 4) img.pixels[p + 3] = 255;
  gl::flip_rows(img);
  gl::write_png(path, img);
  a.last_screenshot = path;
  std::printf("huygens-viz: screenshot written to %s\n", path.c_str());
  std::fflush(stdout);
}

// The key bindings; the window's key callback and the --auto-frames automation both call this.
void on_key(App& a, int key) {
  switch (key) {
    case GLFW_KEY_SPACE:
      a.runner->send(a.runner->paused() ? Command{cmd::Resume{}} : Command{cmd::Pause{}});
      break;
    case GLFW_KEY_R:
      a.runner->send(cmd::Reset{});  // a fresh solver: the ships follow their scene paths again
      a.toggles = a.toggles_at_start;
      break;
    case GLFW_KEY_F1:
      a.show_panel = !a.show_panel;
      break;
    case GLFW_KEY_S:
      a.screenshot_requested = true;
      break;
    case GLFW_KEY_E:
      a.settings.exact_refraction = !a.settings.exact_refraction;
      break;
    case GLFW_KEY_F:
      a.settings.fresnel = a.settings.fresnel == FresnelModel::paper ? FresnelModel::schlick : FresnelModel::paper;
      a.settings.paper_glint = a.settings.fresnel == FresnelModel::paper;
      break;
    case GLFW_KEY_P:
      if (!a.plan) {
        a.plan = true, a.plan_quantity = PlanQuantity::level;
      } else if (a.has_velocity && a.plan_quantity != PlanQuantity::foam) {
        a.plan_quantity = a.plan_quantity == PlanQuantity::level   ? PlanQuantity::speed
                          : a.plan_quantity == PlanQuantity::speed ? PlanQuantity::dye
                                                                   : PlanQuantity::foam;
      } else if (a.view.particle_box && a.plan_quantity == PlanQuantity::level) {
        a.plan_quantity = PlanQuantity::particles;  // SPH: level, then the particles from the side
      } else {
        a.plan = false;
      }
      break;
    case GLFW_KEY_U:  // dive: the eye mirrored below the target's level (under the water), or back up
      a.camera.pitch = -a.camera.pitch;
      break;
    case GLFW_KEY_ESCAPE:
      a.quit = true;
      break;
    default:
      break;
  }
}

void key_callback(GLFWwindow* w, int key, int, int action, int) {
  App& a = *app_of(w);
  if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  on_key(a, key);
}

// The mouse bindings at cursor (x, y) in window coordinates; the window's callback and the
// --auto-frames automation both call this.
void on_mouse_button(App& a, int button, int action, int mods, double x, double y) {
  const bool shift = (mods & GLFW_MOD_SHIFT) != 0;
  if (button == GLFW_MOUSE_BUTTON_LEFT) {
    if (action == GLFW_PRESS) {
      a.left_down = true;
      a.dragged_far = false;
      a.press_x = x, a.press_y = y;
      glm::dvec2 p;
      a.drag_ship = -1;
      if (cursor_hit(a, x, y, p)) {
        a.drag_ship = ship_under(a, p);
        if (a.drag_ship >= 0) {
          a.drag_last_pos = a.drag_target = p;
          a.drag_velocity = glm::dvec2(0.0);
          a.drag_last_t = glfwGetTime();
        }
      }
    } else if (action == GLFW_RELEASE && a.left_down) {
      a.left_down = false;
      glm::dvec2 p;
      if (a.drag_ship >= 0) {
        // release: the ship heads for the last cursor point and stops there (the simulation
        // brakes it with its bounded acceleration)
        if (a.dragged_far)
          a.runner->send(cmd::ShipTarget{a.drag_ship, static_cast<float>(a.drag_target.x),
                                         static_cast<float>(a.drag_target.y), 0.0f, 0.0f});
      } else if (!a.dragged_far && cursor_hit(a, x, y, p)) {
        a.runner->send(cmd::Drop{static_cast<float>(p.x), static_cast<float>(p.y), a.stone_radius, a.stone_depth});
        std::printf("huygens-viz: stone dropped at (%.3f, %.3f) m\n", p.x, p.y);
      }
      a.drag_ship = -1;
    }
  } else if (button == GLFW_MOUSE_BUTTON_RIGHT) {
    a.orbiting = action == GLFW_PRESS && !shift;
    a.panning = action == GLFW_PRESS && shift;
  } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
    a.panning = action == GLFW_PRESS;
  }
  a.last_x = x, a.last_y = y;
}

void mouse_button_callback(GLFWwindow* w, int button, int action, int mods) {
  App& a = *app_of(w);
  double x, y;
  glfwGetCursorPos(w, &x, &y);
  if (action == GLFW_PRESS && ImGui::GetIO().WantCaptureMouse) return;
  on_mouse_button(a, button, action, mods, x, y);
}

void cursor_callback(GLFWwindow* w, double x, double y) {
  App& a = *app_of(w);
  const double dx = x - a.last_x, dy = y - a.last_y;
  a.last_x = x, a.last_y = y;
  if (a.left_down && std::hypot(x - a.press_x, y - a.press_y) > 4.0) a.dragged_far = true;
  if (a.left_down && a.drag_ship >= 0) {
    glm::dvec2 p;
    if (!cursor_hit(a, x, y, p)) return;
    // the cursor is the target; its velocity (smoothed over ~0.1 s, mouse events are irregular)
    // lets the simulation track it without lagging (ShipWaves::steer)
    const double now = glfwGetTime(), dt = std::max(now - a.drag_last_t, 1e-3);
    const double w = 1.0 - std::exp(-dt / 0.1);
    a.drag_velocity += w * ((p - a.drag_last_pos) / dt - a.drag_velocity);
    a.drag_last_pos = a.drag_target = p;
    a.drag_last_t = now;
    a.drag_moving = true;
    a.runner->send(cmd::ShipTarget{a.drag_ship, static_cast<float>(p.x), static_cast<float>(p.y),
                                   static_cast<float>(a.drag_velocity.x), static_cast<float>(a.drag_velocity.y)});
    return;
  }
  if (a.orbiting || a.panning) a.follow = false;
  if (a.orbiting) {
    a.camera.yaw -= 0.005 * dx;
    // above the water (0.05 to 90 deg), or under it after a dive (U: -90 to -0.05 deg)
    a.camera.pitch = a.camera.pitch > 0.0 ? std::clamp(a.camera.pitch + 0.005 * dy, 0.05, 1.5706)
                                          : std::clamp(a.camera.pitch + 0.005 * dy, -1.5706, -0.05);
  } else if (a.panning) {
    const double scale = a.camera.distance * 0.0015;
    const double c = std::cos(a.camera.yaw), s = std::sin(a.camera.yaw);
    // the ground follows the cursor: screen right is (-sin yaw, cos yaw), screen up is the
    // horizontal view direction (-cos yaw, -sin yaw)
    a.camera.target += glm::dvec3(s * dx * scale - c * dy * scale, -c * dx * scale - s * dy * scale, 0.0);
  }
}

// A drag that pauses (no cursor event for 50 ms): the target stops where the cursor is, instead
// of moving on at the last cursor velocity.
void hold_drag_target(App& a) {
  if (!a.left_down || a.drag_ship < 0 || !a.drag_moving || glfwGetTime() - a.drag_last_t < 0.05) return;
  a.drag_moving = false;
  a.drag_velocity = glm::dvec2(0.0);
  a.runner->send(cmd::ShipTarget{a.drag_ship, static_cast<float>(a.drag_target.x), static_cast<float>(a.drag_target.y),
                                 0.0f, 0.0f});
}

void scroll_callback(GLFWwindow* w, double, double yoff) {
  App& a = *app_of(w);
  if (ImGui::GetIO().WantCaptureMouse) return;
  a.camera.distance = std::clamp(a.camera.distance * std::pow(0.9, yoff), 0.01, 5000.0);
}

// The features: the solver's toggles (only those it has: RenderInfo::toggles; a refused one is
// un-ticked by take_refused) and the renderer's switches.
void panel_features(App& a) {
  for (std::size_t i = 0; i < a.toggles.size(); ++i) {
    RenderToggle& t = a.toggles[i];
    if (i > 0) ImGui::SameLine();
    if (ImGui::Checkbox(t.label.c_str(), &t.on)) a.runner->send(cmd::Toggle{CommandName{t.name}, t.on});
  }
  ImGui::Checkbox("plan view (P)", &a.plan);
  if (a.plan && a.has_velocity) {
    int q = static_cast<int>(a.plan_quantity);
    ImGui::SameLine();
    ImGui::Combo("shows", &q, "depth\0speed\0dye\0foam\0");
    a.plan_quantity = static_cast<PlanQuantity>(q);
  } else if (a.plan && a.view.particle_box) {
    int q = a.plan_quantity == PlanQuantity::particles ? 1 : 0;
    ImGui::SameLine();
    ImGui::Combo("shows", &q, "depth\0particles\0");
    a.plan_quantity = q == 1 ? PlanQuantity::particles : PlanQuantity::level;
  }
  ImGui::SameLine();
  ImGui::Checkbox("time interpolation", &a.interpolate);
  ImGui::Checkbox("caustics", &a.settings.caustics);
  ImGui::SameLine();
  ImGui::Checkbox("blur", &a.settings.blur);
  ImGui::SameLine();
  ImGui::Checkbox("float blur (8-bit modes)", &a.settings.blur_float);
  int mode = static_cast<int>(a.settings.caustics_mode);
  ImGui::Combo(
      "caustics mode", &mode,
      "conserving (explicit, float)\0paper MIP, 8-bit\0MIP, float\0explicit, 8-bit\0paper 000 eq. 4 (simple)\0");
  a.settings.caustics_mode = static_cast<CausticsMode>(mode);
  ImGui::Checkbox("exact Snell (E)", &a.settings.exact_refraction);
  ImGui::SameLine();
  ImGui::Checkbox("sun glint", &a.settings.sun_glint);
  ImGui::SameLine();
  ImGui::Checkbox("absorption", &a.settings.absorption);
  int fres = static_cast<int>(a.settings.fresnel);
  ImGui::Combo("Fresnel (F)", &fres, "off\0paper clamp(1-2.5 n.v)\0Schlick\0");
  a.settings.fresnel = static_cast<FresnelModel>(fres);
  int optics = static_cast<int>(a.settings.solid_optics);
  ImGui::Combo("solids in the water", &optics,
               "off (floor and sky only)\0traced per pixel\0paper 000: virtual eye maps\0");
  a.settings.solid_optics = static_cast<SolidOptics>(optics);
  if (a.has_velocity) {
    ImGui::Checkbox("dye (flow)", &a.settings.dye);
    ImGui::SameLine();
    ImGui::Checkbox("foam", &a.settings.foam);
    ImGui::SameLine();
  }
  ImGui::Checkbox("water", &a.settings.draw_water);
  ImGui::SameLine();
  ImGui::Checkbox("ships", &a.settings.draw_ship);
}

void panel_parameters(App& a) {
  ImGui::SliderFloat("refractive index", &a.settings.index, 1.0f, 2.0f, "%.3f");
  ImGui::SliderInt("mesh subsampling", &a.subsample, 1, 16);
  ImGui::SliderFloat3("absorption 1/m", &a.settings.absorb_rgb.x, 0.0f, 2.0f, "%.3f");
  if (ImGui::SliderFloat3("sun direction", &a.settings.sun_dir.x, -1.0f, 1.0f, "%.2f"))
    a.settings.sun_dir.z = std::max(a.settings.sun_dir.z, 0.05f);
  // the glint's brightness: E_sun over the sky's radiance (RenderSettings::sun_irradiance)
  ImGui::SliderFloat("sun irradiance sr", &a.settings.sun_irradiance, 0.001f, 40.0f, "%.3f",
                     ImGuiSliderFlags_Logarithmic);
  float ts = static_cast<float>(a.time_scale);
  if (ImGui::SliderFloat("time scale", &ts, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic)) {
    a.time_scale = ts;
    a.runner->send(cmd::SetParam{CommandName{"time_scale"}, a.time_scale});
  }
  ImGui::SliderFloat("stone radius m", &a.stone_radius, 0.01f, 0.5f, "%.3f", ImGuiSliderFlags_Logarithmic);
  ImGui::SliderFloat("stone depth m", &a.stone_depth, 0.001f, 0.1f, "%.3f", ImGuiSliderFlags_Logarithmic);
}

// Simulation stages from the newest frame's counters (a stage the scene does not use costs
// nothing and is not listed), then the render passes of the last frame.
void panel_timing(App& a, const WaterRenderer& r, const FramePair& fp) {
  if (!ImGui::BeginTable("timing", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) return;
  ImGui::TableSetupColumn("stage");
  ImGui::TableSetupColumn("ms/call");
  ImGui::TableSetupColumn("calls");
  ImGui::TableHeadersRow();
  auto row = [](const char* name, double ms, unsigned long long calls) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(name);
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", ms);
    ImGui::TableNextColumn();
    ImGui::Text("%llu", calls);
  };
  if (fp) {
    const auto& names = a.runner->stage_names();
    for (std::size_t i = 0; i < fp.newest->stages.size() && i < names.size(); ++i) {
      const StageCounter& c = fp.newest->stages[i];
      if (c.calls == 0) continue;
      row(("sim: " + names[i]).c_str(), 1e-6 * static_cast<double>(c.ns) / static_cast<double>(c.calls),
          static_cast<unsigned long long>(c.calls));
    }
  }
  const RenderTimes& t = r.times;
  // render passes: the last frame's time, and the frames drawn so far
  const unsigned long long n = a.frames_drawn;
  row("render: mesh+normals (CPU)", t.prepare, n);
  row("render: upload", t.upload, n);
  row("render: caustics", t.caustics, n);
  row("render: ground", t.ground, n);
  row("render: surface", t.surface, n);
  row("render: ship+solids", t.ship, n);
  row("render: tone map", t.tonemap, n);
  ImGui::EndTable();
}

void panel(App& a, const WaterRenderer& r, const FramePair& fp, double fps) {
  // on the right-hand side (ships start on the left), wide enough for its labels; its sections
  // start collapsed so the panel covers only a strip at the top (a followed ship and its wake
  // are in the middle of the view)
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float width = std::min(470.0f, 0.45f * display.x);
  a.panel_width = width;
  ImGui::SetNextWindowPos(ImVec2(display.x - width - 10.0f, 10.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(width, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("huygens-viz");
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 11.0f);  // room for the longest label
  ImGui::Text("%s: %s", a.scene_name.c_str(), scale_text(a.view, a.settings, r.tile_m()).c_str());
  ImGui::Text("t = %.3f s, step %lld, %.1f fps", fp ? fp.newest->info.time_s : 0.0,
              fp ? static_cast<long long>(fp.newest->info.step) : 0LL, fps);
  ImGui::Text("commands applied %llu, refused %llu", static_cast<unsigned long long>(a.runner->commands_applied()),
              static_cast<unsigned long long>(a.runner->commands_rejected()));
  if (!a.message.empty()) ImGui::TextUnformatted(a.message.c_str());
  if (a.runner->failed()) ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s", a.runner->error().message.c_str());
  bool paused = a.runner->paused();
  if (ImGui::Checkbox("pause (space)", &paused)) on_key(a, GLFW_KEY_SPACE);
  ImGui::SameLine();
  if (ImGui::Button("reset (R)")) on_key(a, GLFW_KEY_R);
  ImGui::SameLine();
  if (ImGui::Button("screenshot (S)")) on_key(a, GLFW_KEY_S);
  if (ImGui::CollapsingHeader("features")) panel_features(a);
  if (ImGui::CollapsingHeader("parameters")) panel_parameters(a);
  if (ImGui::CollapsingHeader("timing (ms)")) panel_timing(a, r, fp);
  if (!a.last_screenshot.empty()) ImGui::Text("last screenshot: %s", a.last_screenshot.c_str());
  ImGui::TextWrapped(
      "left click: stone; left drag on a ship: move it; right drag: orbit; shift+right or "
      "middle drag: pan; wheel: zoom; P: plan view (again: speed, dye, foam or particles); F1: hide this panel");
  ImGui::PopItemWidth();
  ImGui::End();
}

// A GL 3.3 core window with its context current, or null (the message is printed).
GLFWwindow* open_window(const WindowOptions& opt, const std::string& scene_name) {
  glfwSetErrorCallback([](int code, const char* msg) { std::fprintf(stderr, "GLFW error %d: %s\n", code, msg); });
  if (!glfwInit()) {
    std::fprintf(stderr,
                 "huygens-viz: no display (GLFW could not initialise). Without a display server use\n"
                 "  huygens-viz %s --headless --frames 60 --screenshot out.png\n",
                 scene_name.c_str());
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(opt.width, opt.height, "huygens-viz", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    std::fprintf(stderr, "huygens-viz: could not create a GL 3.3 core window\n");
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(opt.auto_frames > 0 ? 0 : 1);
  return window;
}

// Samples per pixel of the window's target: as asked, else 4 on a GPU and 1 on a software
// renderer (llvmpipe shades every sample: 4 samples took 1.9x the frame time, docs/viz.md).
int window_samples(int asked) {
  if (asked > 0) return asked;
  const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = r ? r : "";
  const bool software = name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos ||
                        name.find("Software") != std::string::npos;
  return software ? 1 : RenderTarget::kDefaultSamples;
}

// The renderer for the scene's view at mesh subsampling `subsample`, showing the current field.
std::unique_ptr<WaterRenderer> make_renderer(const App& a, int subsample) {
  auto r = std::make_unique<WaterRenderer>(a.view.grid, a.view.ground_z, subsample);
  place_scene(*r, a.view);
  r->times.enabled = true;
  r->set_heights(a.field);
  return r;
}

// One displayed frame: the newest frames sampled at the display time, the scene drawn and
// blitted, the panel over it, the screenshot if one was asked for, the swap.
void draw_frame(App& a, WaterRenderer& renderer, RenderTarget& target, double fps) {
  take_refused(a);
  const FramePair fp = a.runner->frames();
  const double t = a.interpolate ? a.runner->display_time() : std::numeric_limits<double>::infinity();
  if (fp) {
    fp.sample(t, a.field);
    renderer.set_heights(a.field);
    renderer.set_sea_time(std::min(t, fp.newest->info.time_s));
  }
  // the hulls at the same display time as the heights, where the solver has them (a dragged ship
  // is where the simulation has steered it, not where the cursor is)
  if (fp) frame_ships(a.view, fp, t, a.ships_drawn);
  // the flow: its velocity and the dye and foam it carries (advected once per new frame; a
  // reset, which starts the time again, starts them again)
  if (fp && (a.has_velocity = fp.velocity(a.velocity))) {
    const double tn = fp.newest->info.time_s;
    if (tn < a.dye_time) a.dye->reset(), a.foam->reset(), a.dye_time = 0.0;
    if (tn > a.dye_time) {
      a.dye->advect(a.velocity, tn - a.dye_time);
      a.foam->step(fp.newest->eta.span(), a.velocity, tn - a.dye_time);
      a.dye_time = tn;
    }
    renderer.set_dye(a.dye->values());
    renderer.set_foam(a.foam->values());
  }
  renderer.set_ships(a.ships_drawn);
  for (const RenderToggle& g : a.toggles)  // the sea beyond the region goes with the wind's
    if (g.name == "wind") a.settings.ambient_sea = g.on;
  int fw, fh;
  glfwGetFramebufferSize(a.window, &fw, &fh);
  if (fw > 0 && fh > 0) {
    if (target.width() != fw || target.height() != fh) target = RenderTarget(fw, fh, window_samples(a.opt.samples));
    if (a.follow && !a.ships_drawn.empty()) follow_ship(a.view, a.ships_drawn[0], a.camera);
    renderer.plan_reserve_right = a.show_panel ? a.panel_width + 10.0 : 0.0;
    if (a.plan)
      render_plan_view(
          renderer, a.view,
          PlanData{a.field, a.has_velocity ? std::span<const float>(a.velocity) : std::span<const float>{},
                   a.dye->values(), a.foam->values(),
                   fp && fp.newest->has_particles ? fp.newest->particles.span() : std::span<const float>{}},
          a.plan_quantity, fp ? fp.newest->info.time_s : 0.0, a.scene_name, target);
    else
      renderer.render(a.camera, a.settings, target);
    ++a.frames_drawn;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target.fbo());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, fw, fh, 0, 0, fw, fh, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
  }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  if (a.show_panel) panel(a, renderer, fp, fps);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (a.screenshot_requested && fw > 0 && fh > 0) {
    a.screenshot_requested = false;
    save_screenshot(a, fw, fh);  // what the window shows, panel included (F1 hides it)
  }
  glfwSwapBuffers(a.window);
}

// A window point (x, y) whose ray hits the simulated water and no ship: the middle of the window
// or the first such point of a coarse raster from there (the camera may frame a moving ship in
// the middle, or the region's edge). False if there is none.
bool open_water_point(const App& a, int ww, int wh, double& x, double& y) {
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 9; ++c) {
      x = (0.5 + 0.1 * ((c + 1) / 2) * (c % 2 ? 1 : -1)) * ww;  // 0.5, 0.4, 0.6, 0.3, 0.7, ...
      y = (0.5 + 0.1 * ((r + 1) / 2) * (r % 2 ? 1 : -1)) * wh;
      glm::dvec2 p;
      if (cursor_hit(a, x, y, p) && ship_under(a, p) < 0) return true;
    }
  return false;
}

// --auto-frames: a left click on open water halfway (through the mouse handler), then the S key's
// screenshot and Esc, as a user would.
void automate(App& a, long frame) {
  const int n = a.opt.auto_frames;
  if (n <= 0) return;
  if (frame == n / 2) {
    int ww, wh;
    glfwGetWindowSize(a.window, &ww, &wh);
    double x = 0.5 * ww, y = 0.5 * wh;
    if (!open_water_point(a, ww, wh, x, y)) std::printf("huygens-viz: no open water to click on\n");
    on_mouse_button(a, GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0, x, y);
    on_mouse_button(a, GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0, x, y);
  }
  if (frame == n) on_key(a, GLFW_KEY_S);  // same path as the S key
  if (frame == n + 1) on_key(a, GLFW_KEY_ESCAPE);
}

// The window's loop until it is closed; returns the frames drawn.
long frame_loop(App& a) {
  a.subsample = a.opt.subsample;
  std::unique_ptr<WaterRenderer> renderer = make_renderer(a, a.subsample);
  RenderTarget target;
  long frame = 0;
  auto t_last = std::chrono::steady_clock::now();
  double fps = 0.0;
  while (!glfwWindowShouldClose(a.window) && !a.quit && stop_request::signal() == 0) {
    glfwPollEvents();
    hold_drag_target(a);
    if (a.subsample != renderer->subsample()) {
      renderer.reset();  // free the old GL objects first
      renderer = make_renderer(a, a.subsample);
    }
    draw_frame(a, *renderer, target, fps);
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - t_last).count();
    t_last = now;
    fps = 0.9 * fps + 0.1 * (dt > 0 ? 1.0 / dt : 0.0);
    automate(a, ++frame);
  }
  return frame;
}

void install_callbacks(GLFWwindow* window, App& a) {
  glfwSetWindowUserPointer(window, &a);
  glfwSetKeyCallback(window, key_callback);
  glfwSetMouseButtonCallback(window, mouse_button_callback);
  glfwSetCursorPosCallback(window, cursor_callback);
  glfwSetScrollCallback(window, scroll_callback);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);  // chains the callbacks installed above
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

}  // namespace

int run_window(ViewerSolver scene, const WindowOptions& opt) {
  GLFWwindow* window = open_window(opt, scene.name);
  if (!window) return 1;
  int code = 0;
  {
    App a;
    a.window = window;
    a.opt = opt;
    a.settings = opt.settings;
    a.scene_name = scene.name;
    a.view = scene_view(scene.info);
    a.toggles = a.toggles_at_start = scene.info.toggles;  // as the scene has them
    const auto h = scene.solver->height();
    a.field.assign(h.begin(), h.end());
    int fbw = opt.width, fbh = opt.height;
    glfwGetFramebufferSize(window, &fbw, &fbh);
    const ViewSetup setup = view_setup(scene, fbh > 0 ? static_cast<double>(fbw) / fbh : 16.0 / 9.0);
    a.camera = setup.camera;
    a.follow = a.view.follow_ship;
    a.plan = opt.plan;
    a.plan_quantity = opt.plan_quantity;
    a.velocity.assign(2 * a.view.grid.rows * a.view.grid.cols, 0.0f);
    a.dye = std::make_unique<DyeField>(a.view.grid);
    a.foam = std::make_unique<FoamField>(a.view.grid, scene.info.bed_m);
    RunnerParams rp;
    rp.realtime = true;
    rp.start_paused = opt.paused;
    // Reset makes a fresh solver from the same scene
    Runner runner(std::move(scene.solver), rp, [s = scene.scene, ro = scene.options] { return make_solver(s, ro); });
    a.runner = &runner;
    install_callbacks(window, a);
    runner.start();
    const long frames = frame_loop(a);
    runner.stop();
    std::printf("huygens-viz: %ld frames, commands applied %llu, refused %llu\n", frames,
                static_cast<unsigned long long>(runner.commands_applied()),
                static_cast<unsigned long long>(runner.commands_rejected()));
    if (runner.failed()) {
      std::fprintf(stderr, "huygens-viz: simulation stopped: %s\n", runner.error().message.c_str());
      code = 3;
    }
    if (opt.auto_frames > 0 && a.screenshot_count == 0) code = 1;
    if (stop_request::signal() != 0) {  // the window closed as Esc would close it
      std::fprintf(stderr, "huygens-viz: stopped by %s: the window closed after %ld frames\n",
                   stop_request::signal_name(), frames);
      code = stop_request::exit_code();
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace huygens
