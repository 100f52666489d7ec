// "solver": "lbm" scenes (lbm/solver.hpp): the shipped scenes run, outputs have the documented
// shapes, parse_lbm_scene resolves the time step, viscosity and fields, and bad or unstable scenes
// are refused with the JSON path of the offending value in every block of the scene.
#include "huygens/lbm/lbm_solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "huygens/common/npy.hpp"
#include "huygens/common/report.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/lbm/stoker.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"
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
  for (const char* name : {"dam_break.json", "channel.json", "flood.json"}) {
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

// Regions and obstacles are painted over their boxes only (solver.cpp, for_each_cell_in): every
// cell whose centre they hold and no other, checked against the whole-grid test on shapes whose
// edges fall between, on and near cell centres.
TEST(LbmScene, ShapesCoverExactlyTheCellsWhoseCentresTheyHold) {
  json j = json::parse(kBase);
  j["lbm"].erase("bed");
  const double dx = 0.5;
  struct Box {
    double x0, x1, y0, y1, depth;
  };
  const std::vector<Box> boxes = {{2.0, 4.0, 0.0, 4.0, 1.5},   {2.25, 2.26, 1.25, 3.75, 2.0},
                                  {-5.0, 0.75, 3.0, 9.0, 2.5}, {7.7499, 9.2501, 0.2, 0.3, 3.0},
                                  {19.0, 30.0, 1.0, 1.3, 3.5}, {12.0, 12.5, -1.0, 0.2501, 4.0}};
  j["lbm"]["initial"]["regions"] = json::array();
  for (const Box& b : boxes)
    j["lbm"]["initial"]["regions"].push_back(
        {{"x0_m", b.x0}, {"x1_m", b.x1}, {"y0_m", b.y0}, {"y1_m", b.y1}, {"depth_m", b.depth}});
  j["lbm"]["obstacles"] = {{{"type", "circle"}, {"x_m", 15.0}, {"y_m", 2.0}, {"radius_m", 1.0}},
                           {{"type", "rect"}, {"x0_m", 16.75}, {"x1_m", 17.25}, {"y0_m", 0.0}, {"y1_m", 1.75}}};
  auto solver = make_solver(parse_scene_text(j.dump()), RunOptions{false});
  const auto h = solver->outputs()[0].data;
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 40; ++c) {
      const double x = (c + 0.5) * dx, y = (r + 0.5) * dx;
      double want = 1.0;  // the base level; later regions win
      for (const Box& b : boxes)
        if (x >= b.x0 && x < b.x1 && y >= b.y0 && y < b.y1) want = b.depth;
      const bool solid =
          (x - 15.0) * (x - 15.0) + (y - 2.0) * (y - 2.0) <= 1.0 || (x >= 16.75 && x < 17.25 && y >= 0.0 && y < 1.75);
      EXPECT_FLOAT_EQ(h[r * 40 + c], solid ? 0.0f : static_cast<float>(want)) << "cell (" << r << ", " << c << ")";
    }
}

// Shapes that together cover more than 64 times the grid are refused at their list's key, before
// any is painted (a set-up that grows with shapes x grid cells).
TEST(LbmScene, ShapesCoveringTheGridManyTimesOverAreRefusedAtTheirKey) {
  json j = json::parse(kBase);
  j["lbm"]["initial"]["regions"] = json::array();
  for (int i = 0; i < 64; ++i) j["lbm"]["initial"]["regions"].push_back({{"depth_m", 1.0}});
  EXPECT_EQ(error_path(j), "<no error>");  // 64 whole-grid regions: at the bound
  j["lbm"]["initial"]["regions"].push_back({{"depth_m", 1.0}});
  EXPECT_EQ(error_path(j), "$.lbm.initial.regions");
  // rectangles over the left half: a box of 21 x 8 cells each (a cell of margin), 120 of them and the
  // circle's 4 x 4 fit the bound of 64 x 320 cells, 124 do not
  j = json::parse(kBase);
  for (int i = 0; i < 120; ++i)
    j["lbm"]["obstacles"].push_back({{"type", "rect"}, {"x0_m", 0.0}, {"x1_m", 10.0}, {"y0_m", 0.0}, {"y1_m", 4.0}});
  EXPECT_EQ(error_path(j), "<no error>");
  for (int i = 0; i < 4; ++i)
    j["lbm"]["obstacles"].push_back({{"type", "rect"}, {"x0_m", 0.0}, {"x1_m", 10.0}, {"y0_m", 0.0}, {"y1_m", 4.0}});
  EXPECT_EQ(error_path(j), "$.lbm.obstacles");
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
  j["lbm"]["initial"]["regions"][0]["surface_m"] = 0.0;  // dry land: accepted (wetting and drying)
  EXPECT_EQ(error_path(j), "<no error>");
  j["lbm"]["initial"]["regions"][0] = {{"depth_m", -0.1}};  // a negative depth is not
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

namespace {

struct BadScene {
  const char* what;
  std::function<void(json&)> edit;
  const char* path;
};

void expect_paths(const std::vector<BadScene>& cases) {
  for (const BadScene& c : cases) {
    json j = json::parse(kBase);
    c.edit(j);
    EXPECT_EQ(error_path(j), c.path) << c.what;
  }
}

}  // namespace

TEST(LbmScene, GridAndWaterErrorsNameTheirPath) {
  expect_paths({
      {"grid missing", [](json& j) { j["lbm"].erase("grid"); }, "$.lbm.grid"},
      {"description not a string",
       [](json& j) {
         j["description"] = {{"a", 1}};
       },
       "$.description"},
      {"cell size missing", [](json& j) { j["lbm"]["grid"].erase("cell_m"); }, "$.lbm.grid.cell_m"},
      {"no columns", [](json& j) { j["lbm"]["grid"]["cols"] = 0; }, "$.lbm.grid.cols"},
      {"unsuffixed cell", [](json& j) { j["lbm"]["grid"]["cell"] = 0.5; }, "$.lbm.grid.cell"},
      {"tau and viscosity", [](json& j) { j["lbm"]["water"]["viscosity_m2s"] = 1e-3; }, "$.lbm.water.tau"},
      {"negative gravity", [](json& j) { j["lbm"]["water"]["gravity_mps2"] = -9.81; }, "$.lbm.water.gravity_mps2"},
      {"unsuffixed gravity", [](json& j) { j["lbm"]["water"]["gravity"] = 9.81; }, "$.lbm.water.gravity"},
      {"zero dry threshold", [](json& j) { j["lbm"]["water"]["min_depth_m"] = 0.0; }, "$.lbm.water.min_depth_m"},
  });
}

TEST(LbmScene, BedAndInitialErrorsNameTheirPath) {
  expect_paths({
      {"unknown bed", [](json& j) { j["lbm"]["bed"]["type"] = "stairs"; }, "$.lbm.bed.type"},
      {"bump without width", [](json& j) { j["lbm"]["bed"].erase("half_width_m"); }, "$.lbm.bed.half_width_m"},
      {"flat bed with a bump key", [](json& j) { j["lbm"]["bed"]["type"] = "flat"; }, "$.lbm.bed.half_width_m"},
      {"npy without file",
       [](json& j) {
         j["lbm"]["bed"] = {{"type", "npy"}};
       },
       "$.lbm.bed.file"},
      {"bed force", [](json& j) { j["lbm"]["bed_force"] = "upwind"; }, "$.lbm.bed_force"},
      {"no initial", [](json& j) { j["lbm"].erase("initial"); }, "$.lbm.initial"},
      {"no level", [](json& j) { j["lbm"]["initial"].erase("surface_m"); }, "$.lbm.initial"},
      {"depth and surface", [](json& j) { j["lbm"]["initial"]["depth_m"] = 1.0; }, "$.lbm.initial.surface_m"},
      {"velocity element",
       [](json& j) {
         j["lbm"]["initial"]["velocity_mps"] = {0.0, "fast"};
       },
       "$.lbm.initial.velocity_mps[1]"},
      {"velocity size", [](json& j) { j["lbm"]["initial"]["velocity_mps"] = {0.0}; }, "$.lbm.initial.velocity_mps"},
      {"region velocity range",
       [](json& j) {
         j["lbm"]["initial"]["regions"][0]["velocity_mps"] = {0.0, 1e5};
       },
       "$.lbm.initial.regions[0].velocity_mps[1]"},
      {"region unknown key", [](json& j) { j["lbm"]["initial"]["regions"][0]["x_m"] = 1.0; },
       "$.lbm.initial.regions[0].x_m"},
      {"dam without right depth",
       [](json& j) {
         j["lbm"]["initial"]["dam"] = {{"x_m", 5.0}, {"left_depth_m", 1.0}};
       },
       "$.lbm.initial.dam.right_depth_m"},
  });
}

TEST(LbmScene, ObstacleBoundaryAndTimeErrorsNameTheirPath) {
  expect_paths({
      {"circle without radius", [](json& j) { j["lbm"]["obstacles"][0].erase("radius_m"); },
       "$.lbm.obstacles[0].radius_m"},
      {"rect with a circle's keys", [](json& j) { j["lbm"]["obstacles"][0]["type"] = "rect"; },
       "$.lbm.obstacles[0].radius_m"},
      {"unknown side", [](json& j) { j["lbm"]["boundaries"]["top"] = "open"; }, "$.lbm.boundaries.top"},
      {"inflow on a wall",
       [](json& j) {
         j["lbm"]["inflow"] = {{"discharge_m2s", 0.1}};
       },
       "$.lbm.inflow"},
      {"outflow on a slip side",
       [](json& j) {
         j["lbm"]["outflow"] = {{"depth_m", 1.0}};
       },
       "$.lbm.outflow"},
      {"outflow on the left", [](json& j) { j["lbm"]["boundaries"]["left"] = "outflow"; }, "$.lbm.boundaries.left"},
      {"force size",
       [](json& j) {
         j["lbm"]["force"] = {{"accel_mps2", {0.0}}};
       },
       "$.lbm.force.accel_mps2"},
      {"force element",
       [](json& j) {
         j["lbm"]["force"] = {{"accel_mps2", {0.0, "down"}}};
       },
       "$.lbm.force.accel_mps2[1]"},
      {"dt and cfl", [](json& j) { j["lbm"]["time"]["dt_s"] = 0.01; }, "$.lbm.time.cfl"},
      {"zero cfl", [](json& j) { j["lbm"]["time"]["cfl"] = 0.0; }, "$.lbm.time.cfl"},
      {"cfl beyond the lattice speed", [](json& j) { j["lbm"]["time"]["cfl"] = 0.9; }, "$.lbm.time.cfl"},
      {"unknown time key", [](json& j) { j["lbm"]["time"]["dt"] = 0.01; }, "$.lbm.time.dt"},
      {"everything solid",
       [](json& j) {
         j["lbm"]["obstacles"] = {{{"type", "rect"}, {"x0_m", 0.0}, {"x1_m", 20.0}, {"y0_m", 0.0}, {"y1_m", 4.0}}};
       },
       "$.lbm.obstacles"},
      {"dry threshold above the water", [](json& j) { j["lbm"]["water"]["min_depth_m"] = 2.0; }, "$.lbm.initial"},
  });
}

// A shape that holds no cell does nothing: these ran to exit 0 without it (a rect with x1 < x0, an
// obstacle outside the grid, a region beyond it).
TEST(LbmScene, AnObstacleOrRegionHoldingNoCellIsRefused) {
  expect_paths({
      {"inverted rect",
       [](json& j) {
         j["lbm"]["obstacles"].push_back(
             {{"type", "rect"}, {"x0_m", 6.0}, {"x1_m", 5.0}, {"y0_m", 0.0}, {"y1_m", 4.0}});
       },
       "$.lbm.obstacles[1]"},
      {"rect outside the grid",
       [](json& j) {
         j["lbm"]["obstacles"][0] = {{"type", "rect"}, {"x0_m", 50.0}, {"x1_m", 60.0}, {"y0_m", 0.0}, {"y1_m", 4.0}};
       },
       "$.lbm.obstacles[0]"},
      {"circle outside the grid", [](json& j) { j["lbm"]["obstacles"][0]["x_m"] = -100.0; }, "$.lbm.obstacles[0]"},
      {"circle of radius 0", [](json& j) { j["lbm"]["obstacles"][0]["radius_m"] = 0.0; }, "$.lbm.obstacles[0]"},
      {"region beyond the grid",
       [](json& j) {
         j["lbm"]["initial"]["regions"][0]["x0_m"] = 30.0;
         j["lbm"]["initial"]["regions"][0]["x1_m"] = 40.0;
       },
       "$.lbm.initial.regions[0]"},
  });
}

TEST(LbmScene, ParseResolvesTimeStepViscosityAndFields) {
  const LbmScene s = parse_lbm_scene(parse_scene_text(kBase));
  const LbmParams& p = s.params;
  EXPECT_EQ(p.cols, 40);
  EXPECT_EQ(p.rows, 8);
  EXPECT_DOUBLE_EQ(p.cell_m, 0.5);
  // cfl 0.5 on the deepest still water (the raised region, 1.05 m); tau 0.6 -> nu.
  const double dt = 0.5 * 0.5 / std::sqrt(9.81 * 1.05);
  EXPECT_NEAR(p.dt_s, dt, 1e-6 * dt);
  EXPECT_NEAR(p.viscosity_m2s, 0.1 * 0.25 / (3.0 * p.dt_s), 1e-12);
  EXPECT_EQ(p.left, LbmSide::wall);
  EXPECT_EQ(p.right, LbmSide::slip);
  EXPECT_EQ(p.bottom, LbmSide::periodic);
  EXPECT_EQ(p.bed_force, LbmBedForce::centred);
  EXPECT_EQ(p.expected_froude, 0.0);
  // The obstacle: cell centres within 0.6 m of (15, 2) m are (r, c) = (3..4, 29..30).
  int solid = 0;
  for (auto v : s.fields.solid) solid += v;
  EXPECT_EQ(solid, 4);
  EXPECT_EQ(s.fields.solid[3 * 40 + 29], 1);
  EXPECT_EQ(s.fields.solid[4 * 40 + 30], 1);
  EXPECT_NEAR(s.fields.bed_m[20], 0.2f * (1 - (0.25f / 3) * (0.25f / 3)), 1e-7f);
  EXPECT_FLOAT_EQ(s.fields.depth_m[5], 1.05f);
  // The Solver built from the parsed scene is the one make_solver builds.
  auto a = make_lbm_solver(s);
  auto b = make_solver(parse_scene_text(kBase), RunOptions{false});
  for (int i = 0; i < 3; ++i) a->step(), b->step();
  const auto ha = a->height(), hb = b->height();
  ASSERT_EQ(ha.size(), hb.size());
  for (std::size_t i = 0; i < ha.size(); ++i) ASSERT_EQ(ha[i], hb[i]) << i;
}

TEST(LbmScene, DamFlowBoundsTheTimeStep) {
  json j = json::parse(kBase);
  j["lbm"]["initial"] = {{"dam", {{"x_m", 10.0}, {"left_depth_m", 1.0}, {"right_depth_m", 0.5}}}};
  j["lbm"]["bed"] = {{"type", "flat"}};
  const LbmScene s = parse_lbm_scene(parse_scene_text(j.dump()));
  const StokerSolution st = stoker_solve({1.0, 0.5, 9.81});
  EXPECT_DOUBLE_EQ(s.params.expected_signal_speed_mps, st.max_signal_speed_mps);
  EXPECT_DOUBLE_EQ(s.params.expected_froude, st.middle_velocity_mps / std::sqrt(9.81 * st.middle_depth_m));
  EXPECT_GT(st.max_signal_speed_mps, std::sqrt(9.81));  // the dam's flow, not the still water, sets dt
  EXPECT_NEAR(s.params.dt_s, 0.5 * 0.5 / st.max_signal_speed_mps, 1e-12);
  EXPECT_FLOAT_EQ(s.fields.depth_m[19], 1.0f);  // x = 9.75 m
  EXPECT_FLOAT_EQ(s.fields.depth_m[20], 0.5f);  // x = 10.25 m
  // Too steep a dam names the right depth and the largest ratio that would run.
  j["lbm"]["initial"]["dam"]["right_depth_m"] = 0.1;
  try {
    parse_lbm_scene(parse_scene_text(j.dump()));
    FAIL() << "a transcritical dam was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.lbm.initial.dam.right_depth_m");
    EXPECT_NE(std::string(e.what()).find("h_L/h_R <= 5."), std::string::npos) << e.what();
  }
}

TEST(LbmScene, NullVectorsAreZero) {
  json j = json::parse(kBase);
  j["lbm"]["initial"]["velocity_mps"] = {0.1, 0.0};
  j["lbm"]["initial"]["regions"][0]["velocity_mps"] = nullptr;  // the region is at rest
  j["lbm"]["force"] = {{"accel_mps2", nullptr}};
  const LbmScene s = parse_lbm_scene(parse_scene_text(j.dump()));
  EXPECT_FLOAT_EQ(s.fields.ux_mps[0], 0.1f);  // x = 0.25 m: outside the region
  EXPECT_FLOAT_EQ(s.fields.ux_mps[5], 0.0f);  // x = 2.75 m: inside
  EXPECT_EQ(s.params.accel_mps2[0], 0.0);
  EXPECT_EQ(s.params.accel_mps2[1], 0.0);
  j["lbm"]["initial"]["velocity_mps"] = nullptr;
  EXPECT_FLOAT_EQ(parse_lbm_scene(parse_scene_text(j.dump())).fields.ux_mps[0], 0.0f);
}

// A bed file with a NaN, an infinity or a height beyond 1e4 m is refused at the key that named
// it, with the row, column, flat index and value (a NaN bed used to run to the end, exit 0).
TEST(LbmScene, NonFiniteOrOutOfRangeBedIsRefusedNamingTheCell) {
  const auto dir = std::filesystem::temp_directory_path() / "huygens_lbm_bad_bed_test";
  std::filesystem::create_directories(dir);
  const int rows = 4, cols = 10;
  json j = json::parse(kBase);
  j["lbm"]["grid"] = {{"cols", cols}, {"rows", rows}, {"cell_m", 0.5}};
  j["lbm"]["bed"] = {{"type", "npy"}, {"file", (dir / "bed.npy").string()}};
  j["lbm"]["initial"] = {{"surface_m", 1.0}};
  j["lbm"]["obstacles"] = json::array();
  for (const float bad : {std::nanf(""), INFINITY, 2e4f}) {
    std::vector<float> bed(rows * cols, 0.1f);
    bed[2 * cols + 7] = bad;
    write_npy((dir / "bed.npy").string(), bed, {static_cast<std::size_t>(rows), static_cast<std::size_t>(cols)});
    try {
      make_solver(parse_scene_text(j.dump()), RunOptions{false});
      ADD_FAILURE() << bad << " accepted";
    } catch (const SceneError& e) {
      const std::string m = e.what();
      EXPECT_EQ(e.path(), "$.lbm.bed.file");
      EXPECT_NE(m.find("row 2, column 7 (flat index 27)"), std::string::npos) << m;
      EXPECT_NE(m.find("bed value " + fmt("%g", bad)), std::string::npos) << m;
    }
  }
  // a malformed file: the reader's message (the file and the fault) under the same key
  {
    std::ofstream f(dir / "bed.npy", std::ios::binary);
    const char bytes[] = "\x93NUMPY\x01\x00\x10\x00{'shape': (x,)} ";  // a 16-byte header dict
    f.write(bytes, sizeof bytes - 1);
  }
  try {
    make_solver(parse_scene_text(j.dump()), RunOptions{false});
    ADD_FAILURE() << "malformed bed accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.lbm.bed.file");
    EXPECT_NE(std::string(e.what()).find("bed.npy: bad header"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}
