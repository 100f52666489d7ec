#include "scene_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

namespace huygens {

ShipPose SceneShipPath::pose(double time) const {
  ShipPose p;
  p.length = length;
  p.beam = beam;
  p.draft = draft;
  if (t.empty()) return p;
  if (t.size() == 1) {
    p.x = x[0], p.y = y[0];
    return p;
  }
  std::size_t k = 0;
  while (k + 2 < t.size() && time > t[k + 1]) ++k;
  const double span = std::max(t[k + 1] - t[k], 1e-12);
  const double s = std::clamp((time - t[k]) / span, 0.0, 1.0);
  p.x = x[k] + s * (x[k + 1] - x[k]);
  p.y = y[k] + s * (y[k + 1] - y[k]);
  p.heading = std::atan2(y[k + 1] - y[k], x[k + 1] - x[k]);
  return p;
}

ShipPose SceneShipPath::pose(const ShipState& s) const {
  ShipPose p;
  p.length = length;
  p.beam = beam;
  p.draft = draft;
  p.x = s.x_m;
  p.y = s.y_m;
  p.heading = s.heading_rad;
  return p;
}

std::vector<ShipPose> solver_ship_poses(const SceneGeometry& geo, const Solver& solver) {
  std::array<ShipState, kMaxFrameShips> now{};
  const std::size_t reported = solver.ship_poses(now);
  std::vector<ShipPose> poses;
  for (std::size_t i = 0; i < geo.ships.size(); ++i)
    poses.push_back(i < reported ? geo.ships[i].pose(now[i]) : geo.ships[i].pose(solver.time()));
  return poses;
}

namespace {
double num(const nlohmann::json& j, const char* key, double fallback) {
  if (j.is_object() && j.contains(key) && j[key].is_number()) return j[key].get<double>();
  return fallback;
}
}  // namespace

SceneGeometry scene_geometry(const Scene& scene, Solver& solver) {
  SceneGeometry g;
  const nlohmann::json& doc = *scene.doc;
  g.grid.rows = solver.height_rows();
  g.grid.cols = solver.height_cols();
  const nlohmann::json meta = solver.meta();
  double dx = num(meta, "dx", num(meta, "dx_m", 0.01));
  double x0 = 0.0, y0 = 0.0;
  if (doc.contains("grid") && doc["grid"].is_object()) {
    const auto& grid = doc["grid"];
    const double n = num(grid, "n", 0.0), len = num(grid, "length_m", 0.0);
    if (n > 0 && len > 0) dx = len / n;
    const double margin = num(grid, "margin", 0.0);
    x0 = y0 = margin * dx;
  }
  g.grid.dx = dx;
  g.grid.x0 = x0;
  g.grid.y0 = y0;
  if (doc.contains("water") && doc["water"].is_object() && doc["water"].contains("depth_m") &&
      doc["water"]["depth_m"].is_number())
    g.ground_z = -doc["water"]["depth_m"].get<double>();
  else
    g.ground_z = -SceneGeometry::kDeepGround;
  if (doc.contains("time") && doc["time"].is_object()) {
    g.dt = num(doc["time"], "dt_s", g.dt);
    g.display_per_step = std::max(1, static_cast<int>(num(doc["time"], "display_per_step", 3)));
  }
  g.dt = num(meta, "dt", g.dt);
  if (scene.solver != "huygens") {
    // height() is a depth or a level above the floor: draw it relative to its mean
    const auto h = solver.height();
    double sum = 0.0;
    for (float v : h) sum += v;
    g.height_offset = h.empty() ? 0.0 : sum / static_cast<double>(h.size());
    if (g.height_offset > 0.0) g.ground_z = -g.height_offset;
  }
  if (doc.contains("ships") && doc["ships"].is_array()) {
    for (const auto& s : doc["ships"]) {
      SceneShipPath p;
      p.length = num(s, "length_m", p.length);
      p.beam = num(s, "beam_m", p.beam);
      p.draft = num(s, "draft_m", p.draft);
      if (s.contains("path") && s["path"].is_array())
        for (const auto& w : s["path"]) {
          p.t.push_back(num(w, "t_s", 0.0));
          p.x.push_back(num(w, "x_m", 0.0));
          p.y.push_back(num(w, "y_m", 0.0));
        }
      g.ships.push_back(std::move(p));
    }
  }
  return g;
}

void apply_scene_render_block(const std::string& scene_file, RenderSettings& s) {
  std::ifstream f(scene_file);
  if (!f) return;  // load_scene reports a missing file with its own message
  const nlohmann::json doc = nlohmann::json::parse(f, nullptr, false);
  if (doc.is_discarded() || !doc.contains("render") || !doc["render"].is_object()) return;
  const auto& r = doc["render"];
  if (r.contains("caustics") && r["caustics"].is_boolean()) s.caustics = r["caustics"].get<bool>();
  if (r.contains("blur") && r["blur"].is_string()) {
    s.blur = r["blur"].get<std::string>() != "none";
    s.blur_float = r["blur"].get<std::string>() == "float";
  }
}

}  // namespace huygens
