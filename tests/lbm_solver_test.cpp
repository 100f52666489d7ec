// "solver": "lbm" scenes: the shipped scenes run, outputs have the documented shapes, and bad
// or unstable scenes are refused with the JSON path of the offending value.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "huygens/common/npy.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"
#include "scenes_dir.hpp"

using namespace huygens;
using nlohmann::json;

namespace {

const char* kBase = R"({
  "solver": "lbm",
  "lbm": {
    "grid": {"cols": 40, "rows": 8, "cell_m": 0.5},
    "time": {"cfl": 0.5},
    "water": {"tau": 0.6},
    "bed": {"type": "bump", "x_m": 10.0, "half_width_m": 3.0, "height_m": 0.2},
    "initial": {"surface_m": 1.0, "regions": [{"x0_m": 2.0, "x1_m": 4.0, "surface_m": 1.05}]},
    "boundaries": {"left": "wall", "right": "slip", "bottom": "periodic", "top": "periodic"},
    "obstacles": [{"type": "circle", "x_m": 15.0, "y_m": 2.0, "radius_m": 0.6}]
  }
})";

std::string error_path(const json& doc) {
  try {
    make_solver(parse_scene_text(doc.dump()), RunOptions{false});
  } catch (const SceneError& e) {
    return e.path();
  }
  return "<no error>";
}

}  // namespace

TEST(LbmScene, ShippedScenesRunAndDumpTheDocumentedFields) {
  for (const char* name : {"dam_break.json", "channel.json"}) {
    auto solver = make_solver(load_scene(huygens::test::scenes_dir() + "/" + name), RunOptions{false});
    for (int i = 0; i < 5; ++i) solver->step();
    const auto out = solver->outputs();
    ASSERT_EQ(out.size(), 3u) << name;
    const std::size_t r = solver->height_rows(), c = solver->height_cols();
    EXPECT_EQ(out[0].name, "h");
    EXPECT_EQ(out[0].shape, (std::vector<std::size_t>{r, c}));
    EXPECT_EQ(out[1].name, "u");
    EXPECT_EQ(out[1].shape, (std::vector<std::size_t>{r, c, 2}));
    EXPECT_EQ(out[2].name, "eta");
    EXPECT_EQ(out[1].data.size(), 2 * r * c);
    for (float x : out[0].data) ASSERT_TRUE(std::isfinite(x) && x >= 0.0f);
    EXPECT_EQ(solver->height().size(), r * c);
    EXPECT_EQ(solver->meta()["solver"], "lbm");
    EXPECT_EQ(solver->stats().all()[1].calls, 5u);
  }
}

TEST(LbmScene, SurfaceIsDepthPlusBed) {
  auto solver = make_solver(parse_scene_text(kBase), RunOptions{false});
  const auto out = solver->outputs();
  const auto h = out[0].data, eta = out[2].data;
  // Still water at 1.0 m over the bump away from the raised region, 0 depth in the obstacle.
  EXPECT_NEAR(eta[2 * 40 + 20], 1.0f, 1e-6f);  // x = 10.25 m: on the bump
  EXPECT_NEAR(h[2 * 40 + 20], 1.0f - 0.2f * (1 - (0.25f / 3) * (0.25f / 3)), 1e-6f);
  EXPECT_NEAR(eta[2 * 40 + 5], 1.05f, 1e-6f);  // x = 2.75 m: raised region
  EXPECT_EQ(h[4 * 40 + 30], 0.0f);             // (x, y) = (15.25, 2.25): in the obstacle
}

TEST(LbmScene, ErrorsNameTheJsonPath) {
  const json base = json::parse(kBase);
  EXPECT_EQ(error_path(base), "<no error>");
  json j = base;
  j["lbm"]["grid"]["bad"] = 1;
  EXPECT_EQ(error_path(j), "$.lbm.grid.bad");
  j = base;
  j["lbm"]["water"]["tau"] = 0.52;  // tau < 0.55
  EXPECT_EQ(error_path(j), "$.lbm.water.tau");
  j = base;
  j["lbm"]["water"] = {{"viscosity_m2s", 1e-6}};
  EXPECT_EQ(error_path(j), "$.lbm.water.viscosity_m2s");
  j = base;
  j["lbm"]["time"] = {{"dt_s", 1.0}};  // far beyond 0.8 of the lattice speed
  EXPECT_EQ(error_path(j), "$.lbm.time.dt_s");
  j = base;
  j["lbm"]["initial"]["regions"][0]["surface_m"] = 0.0;  // dry: depth 0 on a flat bed
  EXPECT_EQ(error_path(j), "$.lbm.initial");
  j = base;
  j["lbm"]["initial"] = {{"dam", {{"x_m", 10.0}, {"left_depth_m", 1.0}, {"right_depth_m", 0.1}}}};
  EXPECT_EQ(error_path(j), "$.lbm.initial.dam.right_depth_m");  // transcritical: refused
  j = base;
  j["lbm"]["boundaries"]["right"] = "periodic";  // left is a wall: unpaired
  EXPECT_EQ(error_path(j), "$.lbm.boundaries.left");
  j = base;
  j["lbm"]["boundaries"]["left"] = "inflow";  // no discharge given
  EXPECT_EQ(error_path(j), "$.lbm.inflow");
  j = base;
  j["lbm"]["obstacles"][0]["type"] = "hexagon";
  EXPECT_EQ(error_path(j), "$.lbm.obstacles[0].type");
  j = base;
  j["lbm"]["bed"] = {{"type", "npy"}, {"file", "/nonexistent/bed.npy"}};
  EXPECT_EQ(error_path(j), "$.lbm.bed.file");
  j = base;
  j["extra"] = 1;
  EXPECT_EQ(error_path(j), "$.extra");
}

TEST(LbmScene, BedFromNpyKeepsStillWaterStill) {
  const auto dir = std::filesystem::temp_directory_path() / "huygens_lbm_bed_test";
  std::filesystem::create_directories(dir);
  const int rows = 6, cols = 20;
  std::vector<float> bed(rows * cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) bed[r * cols + c] = 0.05f * static_cast<float>((c * 7 + r * 3) % 5);
  write_npy((dir / "bed.npy").string(), bed, {static_cast<std::size_t>(rows), static_cast<std::size_t>(cols)});
  json j = json::parse(kBase);
  j["lbm"]["grid"] = {{"cols", cols}, {"rows", rows}, {"cell_m", 0.5}};
  j["lbm"]["bed"] = {{"type", "npy"}, {"file", (dir / "bed.npy").string()}};
  j["lbm"]["initial"] = {{"surface_m", 1.0}};
  j["lbm"]["obstacles"] = json::array();
  auto solver = make_solver(parse_scene_text(j.dump()), RunOptions{false});
  for (int i = 0; i < 200; ++i) solver->step();
  const auto eta = solver->height();
  for (int i = 0; i < rows * cols; ++i) ASSERT_NEAR(eta[i], 1.0f, 2e-6f) << i;
  j["lbm"]["grid"]["cols"] = cols + 1;  // shape mismatch
  EXPECT_EQ(error_path(j), "$.lbm.bed.file");
  std::filesystem::remove_all(dir);
}
