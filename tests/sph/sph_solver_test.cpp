// The SPH solver adapter (huygens/sph/sph_solver.hpp): every key of the "sph" block lands in its
// parameter, errors name the JSON path (an old key names its new one), and the shipped scenes
// build, run, dump and take commands.
#include "huygens/sph/sph_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"
#include "scenes_dir.hpp"

using namespace huygens;

namespace {

const std::string kOkFluid = R"("fluid": [ { "min_m": [0, 0, 0], "max_m": [0.1, 0.1, 0.05] } ])";

// the scene error of an "sph" block with `extra` keys after a valid minimal set, or "<no error>"
SceneError error_of(const std::string& text) {
  try {
    make_solver(parse_scene_text(text));
  } catch (const SceneError& e) {
    return e;
  }
  return SceneError("<no error>", "");
}

std::string path_of(const std::string& text) { return error_of(text).path(); }

SceneError error_of_file(const std::string& file) {
  try {
    make_solver(load_scene(file));
  } catch (const SceneError& e) {
    return e;
  }
  return SceneError("<no error>", "");
}

std::string with(const std::string& extra) {
  return R"({"solver": "sph", "sph": {"spacing_m": 0.01, "container_m": [0.1, 0.1, 0.1], )" + kOkFluid + extra + "}}";
}

}  // namespace

TEST(SphScene, EveryKeyLandsInItsParameter) {
  const SphScene sc = parse_sph_scene(parse_scene_text(R"({"solver": "sph", "sph": {
      "spacing_m": 0.02, "support_factor": 1.8, "rest_density_kgpm3": 998, "viscosity_m2s": 2e-6,
      "artificial_viscosity": 0.02, "impact_alpha": 0.1, "impact_beta": 3, "wall_alpha": 0.5, "sound_speed_mps": 20,
      "gravity_mps2": [1, 0, -9], "container_m": [0.4, 0.3, 0.2],
      "fluid": [ { "min_m": [0, 0, 0], "max_m": [0.2, 0.3, 0.1] } ],
      "obstacles": [ { "type": "box", "min_m": [0.3, 0, 0], "max_m": [0.35, 0.1, 0.2] },
                     { "type": "cylinder", "centre_m": [0.3, 0.2], "radius_m": 0.03, "z1_m": 0.15 },
                     { "type": "sphere", "centre_m": [0.1, 0.2, 0.05], "radius_m": 0.04 } ],
      "time": { "cfl": 0.2, "force": 0.1, "viscous": 0.02, "dt_max_s": 5e-4 },
      "surface": { "cell_m": 0.01, "radius_factor": 1.5, "iso": 2.5 } }})"));
  const SphParams& p = sc.params;
  EXPECT_FLOAT_EQ(p.spacing_m, 0.02f);
  EXPECT_FLOAT_EQ(p.support_factor, 1.8f);
  EXPECT_FLOAT_EQ(p.rest_density_kgpm3, 998.f);
  EXPECT_FLOAT_EQ(p.viscosity_m2s, 2e-6f);
  EXPECT_FLOAT_EQ(p.artificial_viscosity, 0.02f);
  EXPECT_FLOAT_EQ(p.impact_alpha, 0.1f);
  EXPECT_FLOAT_EQ(p.impact_beta, 3.f);
  EXPECT_FLOAT_EQ(p.sound_speed_mps, 20.f);
  EXPECT_EQ(p.gravity_mps2, (std::array<float, 3>{1.f, 0.f, -9.f}));
  EXPECT_EQ(p.container_m, (std::array<float, 3>{0.4f, 0.3f, 0.2f}));
  ASSERT_EQ(p.fluid.size(), 1u);
  EXPECT_FLOAT_EQ(p.fluid[0].max_m[1], 0.3f);
  ASSERT_EQ(p.obstacles.size(), 3u);
  EXPECT_FLOAT_EQ(p.wall_alpha, 0.5f);
  EXPECT_EQ(p.obstacles[2].type, SphObstacle::Type::sphere);
  EXPECT_FLOAT_EQ(p.obstacles[2].sphere_centre_m[2], 0.05f);
  EXPECT_FLOAT_EQ(p.obstacles[2].radius_m, 0.04f);
  EXPECT_EQ(p.obstacles[0].type, SphObstacle::Type::box);
  EXPECT_FLOAT_EQ(p.obstacles[0].min_m[0], 0.3f);
  EXPECT_EQ(p.obstacles[1].type, SphObstacle::Type::cylinder);
  EXPECT_FLOAT_EQ(p.obstacles[1].centre_m[1], 0.2f);
  EXPECT_FLOAT_EQ(p.obstacles[1].radius_m, 0.03f);
  EXPECT_FLOAT_EQ(p.obstacles[1].z0_m, 0.f);
  EXPECT_FLOAT_EQ(p.obstacles[1].z1_m, 0.15f);
  EXPECT_FLOAT_EQ(p.cfl, 0.2f);
  EXPECT_FLOAT_EQ(p.force_factor, 0.1f);
  EXPECT_FLOAT_EQ(p.viscous_factor, 0.02f);
  EXPECT_FLOAT_EQ(p.dt_max_s, 5e-4f);
  EXPECT_FLOAT_EQ(sc.surface.cell_m, 0.01f);
  EXPECT_FLOAT_EQ(sc.surface.radius_m, 0.03f);
  EXPECT_FLOAT_EQ(sc.surface.iso, 2.5f);
  // defaults: the heightfield on the particle spacing and support radius, the flat-lattice iso
  const SphScene d = parse_sph_scene(parse_scene_text(with("")));
  EXPECT_FLOAT_EQ(d.surface.cell_m, 0.01f);
  EXPECT_FLOAT_EQ(d.surface.radius_m, 0.02f);
  EXPECT_FLOAT_EQ(d.surface.iso, sph_flat_iso(0.02f, 0.01f));
  EXPECT_FLOAT_EQ(d.params.viscosity_m2s, 1e-6f);
}

TEST(SphScene, TheOldViscosityKeyIsRefusedNamingTheNewOne) {
  const SceneError e = error_of(with(R"(, "viscosity_m2ps": 1e-6)"));
  EXPECT_EQ(e.path(), "$.sph.viscosity_m2ps");
  EXPECT_NE(std::string(e.what()).find("\"viscosity_m2s\""), std::string::npos) << e.what();
}

TEST(SphScene, TheMethodKeyChoosesThePressureSolver) {
  EXPECT_EQ(parse_sph_scene(parse_scene_text(with(""))).params.method, SphMethod::wcsph);
  EXPECT_EQ(parse_sph_scene(parse_scene_text(with(R"(, "method": "dfsph")"))).params.method, SphMethod::dfsph);
  const SceneError e = error_of(with(R"(, "method": "pcisph")"));
  EXPECT_EQ(e.path(), "$.sph.method");
  EXPECT_NE(std::string(e.what()).find("dfsph"), std::string::npos) << e.what();
}

TEST(SphScene, ErrorsNameTheJsonPath) {
  EXPECT_EQ(path_of(with(R"(, "bogus": 1)")), "$.sph.bogus");
  EXPECT_EQ(path_of(R"({"solver": "sph", "sph": {"spacing_m": 0.01, "container_m": [0.1, 0.1], )" + kOkFluid + "}}"),
            "$.sph.container_m");
  EXPECT_EQ(
      path_of(R"({"solver": "sph", "sph": {"spacing_m": 0.01, "container_m": [0.1, -1, 0.1], )" + kOkFluid + "}}"),
      "$.sph.container_m[1]");
  EXPECT_EQ(path_of(R"({"solver": "sph", "sph": {"spacing_m": 0.01, "container_m": [0.1, 0.1, 0.1], "fluid": [
               { "min_m": [0, 0, 0], "max_m": [0.3, 0.1, 0.05] } ]}})"),
            "$.sph.fluid[0].max_m");
  EXPECT_EQ(path_of(with(R"(, "surface": {"radius_factor": 3.0})")), "$.sph.surface.radius_factor");
  EXPECT_EQ(path_of(with(R"(, "obstacles": [ {"type": "cone"} ])")), "$.sph.obstacles[0].type");
  EXPECT_EQ(
      path_of(with(R"(, "obstacles": [ {"type": "cylinder", "centre_m": [0.05], "radius_m": 0.01, "z1_m": 0.1} ])")),
      "$.sph.obstacles[0].centre_m");
  EXPECT_EQ(path_of(with(R"(, "time": {"cfl": 2})")), "$.sph.time.cfl");
  // walls are boundary particles; the mirror images are gone
  EXPECT_EQ(path_of(with(R"(, "boundary": "mirror")")), "$.sph.boundary");
  EXPECT_EQ(path_of(with(R"(, "boundary": "particles")")), "<no error>");
  EXPECT_EQ(path_of(with(R"(, "obstacles": [ {"type": "sphere", "centre_m": [0.05, 0.05], "radius_m": 0.01} ])")),
            "$.sph.obstacles[0].centre_m");
  EXPECT_EQ(path_of(with(R"(, "obstacles": [ {"type": "mesh"} ])")), "$.sph.obstacles[0].file");
  // a surface that would take more than 2e7 boundary particles is refused before sampling
  EXPECT_EQ(path_of(with(R"(, "obstacles": [ {"type": "sphere", "centre_m": [0, 0, 0], "radius_m": 1000} ])")),
            "$.sph.obstacles");
  // unstable settings are refused before the run, with the reason
  EXPECT_EQ(path_of(with(R"(, "artificial_viscosity": 0.001)")), "$.sph.artificial_viscosity");
  EXPECT_EQ(path_of(with(R"(, "sound_speed_mps": 1.0)")), "$.sph.sound_speed_mps");
  EXPECT_EQ(path_of(with("")), "<no error>");
  // the description is a string, as in the other solvers' scenes (an array nested 10 deep ran)
  EXPECT_EQ(
      path_of(R"({"solver": "sph", "description": [[1]], "sph": {"spacing_m": 0.01, "container_m": [0.1, 0.1, 0.1], )" +
              kOkFluid + "}}"),
      "$.description");
}

// The "render" block, as in the other solvers' scenes: its camera reaches the viewer's RenderInfo,
// a bad key names its path.
TEST(SphScene, TheRenderBlockReachesTheViewer) {
  const std::string scene = R"({"solver": "sph", "render": {"camera": {"pitch_deg": 35}}, "sph": {"spacing_m": 0.01,
      "container_m": [0.1, 0.1, 0.1], )" +
                            kOkFluid + "}}";
  EXPECT_EQ(parse_sph_scene(parse_scene_text(scene)).render.camera.pitch_deg, 35.0);
  EXPECT_EQ(make_solver(parse_scene_text(scene))->render_info().request.camera.pitch_deg, 35.0);
  EXPECT_EQ(path_of(R"({"solver": "sph", "render": {"camera": {"pitch": 35}}, "sph": {"spacing_m": 0.01,
      "container_m": [0.1, 0.1, 0.1], )" +
                    kOkFluid + "}}"),
            "$.render.camera.pitch");
}

// A scene that would run with no water, or with an obstacle that is not there, is refused: these ran
// to exit 0 with empty heightfields (fluid inside an obstacle, fluid thinner than the spacing) or
// without the obstacle (one outside the container).
TEST(SphScene, NoWaterOrAnObstacleOutsideTheContainerIsRefused) {
  const std::string fluid_in_box = R"({"solver": "sph", "sph": {"spacing_m": 0.01, "container_m": [0.1, 0.1, 0.1],
      "fluid": [ { "min_m": [0.02, 0.02, 0], "max_m": [0.05, 0.05, 0.05] } ],
      "obstacles": [ {"type": "box", "min_m": [0, 0, 0], "max_m": [0.08, 0.08, 0.08]} ]}})";
  const SceneError e = error_of(fluid_in_box);
  EXPECT_EQ(e.path(), "$.sph.fluid");
  EXPECT_NE(std::string(e.what()).find("no particle"), std::string::npos) << e.what();
  EXPECT_EQ(path_of(R"({"solver": "sph", "sph": {"spacing_m": 0.01, "container_m": [0.1, 0.1, 0.1],
      "fluid": [ { "min_m": [0, 0, 0], "max_m": [0.1, 0.1, 0.004] } ]}})"),
            "$.sph.fluid");
  EXPECT_EQ(path_of(with(R"(, "obstacles": [ {"type": "box", "min_m": [5, 5, 5], "max_m": [6, 6, 6]} ])")),
            "$.sph.obstacles[0]");
  EXPECT_EQ(path_of(with(R"(, "obstacles": [ {"type": "sphere", "centre_m": [0.05, 0.05, -1], "radius_m": 0.5} ])")),
            "$.sph.obstacles[0]");
  EXPECT_EQ(path_of(with(R"(, "obstacles": [ {"type": "box", "min_m": [0.02, 0.02, 0], "max_m": [0.03, 0.03, 0.01]},
      {"type": "cylinder", "centre_m": [-1, 0.05], "radius_m": 0.1, "z1_m": 0.1} ])")),
            "$.sph.obstacles[1]");
  // touching or overlapping the container is fine (a wedge on the floor, a cylinder through the lid)
  EXPECT_EQ(path_of(with(R"(, "obstacles": [ {"type": "cylinder", "centre_m": [0.05, 0.05], "radius_m": 0.01,
      "z0_m": -1, "z1_m": 2} ])")),
            "<no error>");
}

// A mesh obstacle's OBJ is read relative to the scene file; a bad one names the file and line.
TEST(SphScene, MeshObstacleFromAnObjFile) {
  const std::string dir = ::testing::TempDir();
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  };
  write("tet.obj", "v 0 0 0\nv 0.04 0 0\nv 0 0.04 0\nv 0 0 0.04\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write("bad.obj", "v 0 0 0\nv 0.04 0 0\nv 0 0.04 0\nf 1 2 9\n");
  const std::string ok =
      write("mesh.json", with(R"(, "obstacles": [ {"type": "mesh", "file": "tet.obj", "position_m": [0.03, 0.03, 0.0],
                                                  "scale": 2.0} ])"));
  const SphScene sc = parse_sph_scene(load_scene(ok));
  ASSERT_EQ(sc.params.obstacles.size(), 1u);
  const SphObstacle& o = sc.params.obstacles[0];
  EXPECT_EQ(o.type, SphObstacle::Type::mesh);
  EXPECT_FLOAT_EQ(o.min_m[0], 0.03f);
  EXPECT_FLOAT_EQ(o.max_m[2], 0.08f);
  EXPECT_TRUE(o.blocks(0.04f, 0.04f, 0.01f, 0.f));
  auto solver = make_solver(load_scene(ok));
  solver->step();
  const std::string bad = write("bad.json", with(R"(, "obstacles": [ {"type": "mesh", "file": "bad.obj"} ])"));
  const SceneError e = error_of_file(bad);
  EXPECT_EQ(e.path(), "$.sph.obstacles[0].file");
  EXPECT_NE(std::string(e.what()).find("bad.obj:4: face vertex 9 outside the 3 vertices so far"), std::string::npos)
      << e.what();
}

// The OBJ path is relative to the scene file's folder, not to the working directory: a scene
// loaded by a relative path still finds its mesh after the working directory changed (the
// folder is made absolute when the scene is loaded); a built-in scene (text without a file, as
// the viewer carries the shipped scenes) reads its mesh only from its embedded files, and a
// mesh that is not there is a scene error naming the JSON path. The solver's RenderInfo carries
// the mesh's triangles as placed (the viewer draws them).
TEST(SphScene, MeshPathIsRelativeToTheSceneNotTheWorkingDirectory) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(::testing::TempDir()) / "sph_mesh_cwd";
  fs::remove_all(root);
  fs::create_directories(root / "scene" / "meshes");
  fs::create_directories(root / "elsewhere");
  const std::string tet = "v 0 0 0\nv 0.04 0 0\nv 0 0.04 0\nv 0 0 0.04\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::ofstream(root / "scene" / "meshes" / "tet.obj") << tet;
  const std::string text =
      with(R"(, "obstacles": [ {"type": "mesh", "file": "meshes/tet.obj", "position_m": [0.03, 0.03, 0.0]} ])");
  std::ofstream(root / "scene" / "mesh.json") << text;
  const fs::path cwd = fs::current_path();
  fs::current_path(root / "elsewhere");
  const Scene loaded = load_scene("../scene/mesh.json");
  fs::current_path(root);  // the working directory moves on before the solver is made
  std::unique_ptr<Solver> solver;
  EXPECT_NO_THROW(solver = make_solver(loaded)) << "the mesh beside the scene, found from another folder";
  // built in: the embedded files, never the working directory (which holds meshes/tet.obj here)
  fs::current_path(root / "scene");
  Scene builtin = parse_scene_text(text, "mesh.json");
  builtin.embedded = [](std::string_view) { return std::string_view(); };
  std::string path = "<no error>", what;
  try {
    make_solver(builtin);
  } catch (const SceneError& e) {
    path = e.path(), what = e.what();
  }
  fs::current_path(cwd);
  EXPECT_EQ(path, "$.sph.obstacles[0].file");
  EXPECT_NE(what.find("meshes/tet.obj"), std::string::npos) << what;
  builtin.embedded = [&](std::string_view f) { return f == "meshes/tet.obj" ? std::string_view(tet) : ""; };
  ASSERT_NO_THROW(solver = make_solver(builtin));
  const RenderInfo info = solver->render_info();
  ASSERT_EQ(info.obstacles.size(), 1u);
  const RenderObstacle& o = info.obstacles[0];
  EXPECT_EQ(o.kind, RenderObstacle::Kind::mesh);
  ASSERT_EQ(o.triangles_m.size(), 4u * 9u) << "the four faces, three corners each";
  EXPECT_FLOAT_EQ(o.triangles_m[0], 0.03f) << "vertex 1 of face 1 moved by position_m";
  EXPECT_FLOAT_EQ(o.triangles_m[3 + 1], 0.07f) << "vertex 3 (0, 0.04, 0) of face 1, y";
  EXPECT_FLOAT_EQ(static_cast<float>(o.max_m[2]), 0.04f);
}

TEST(SphScene, ShippedScenesBuildAndRun) {
  for (const char* name : {"pool.json", "sph_dam_break.json", "sph_wedge.json"}) {
    auto solver = make_solver(load_scene(huygens::test::scenes_dir() + "/" + name));
    for (int k = 0; k < 3; ++k) solver->step();
    const auto out = solver->outputs();
    ASSERT_EQ(out.size(), 5u);
    const std::size_t n = out[0].shape[0];
    for (std::size_t i = 0; i < 4; ++i) {
      EXPECT_EQ(out[i].name, std::vector<std::string>({"pos", "vel", "density", "pressure"})[i]);
      EXPECT_TRUE(out[i].per_particle);
      EXPECT_EQ(out[i].shape[0], n);
      EXPECT_EQ(out[i].data.size(), n * (i < 2 ? 3 : 1));
    }
    EXPECT_EQ(out[2].shape.size(), 1u) << "one density per particle";
    EXPECT_GT(*std::min_element(out[2].data.begin(), out[2].data.end()), 0.0f);
    EXPECT_EQ(out[4].name, "eta");
    EXPECT_FALSE(out[4].per_particle);
    EXPECT_EQ(out[4].shape[0], solver->height_rows());
    EXPECT_EQ(out[4].shape[1], solver->height_cols());
    EXPECT_EQ(solver->meta()["dt"]["steps"], 3);
    EXPECT_EQ(solver->stats().find("surface") >= 0, true);
  }
  auto pool = make_solver(load_scene(huygens::test::scenes_dir() + "/pool.json"));
  EXPECT_TRUE(pool->apply(cmd::Drop{0.05f, 0.05f, 0.02f, 0.01f}));
  EXPECT_TRUE(pool->apply(cmd::SetParam{"gravity_x", 2.0}));
  EXPECT_FALSE(pool->apply(cmd::SetParam{"no_such_param", 1.0}));
  EXPECT_FALSE(pool->apply(cmd::Pause{}));
  const auto n = pool->meta()["particles"].get<std::size_t>();
  EXPECT_GT(n, 2500u);
  EXPECT_LT(n, 3500u);
}

TEST(SphScene, ParticlesForTheViewerArePositionsAndSpeeds) {
  auto solver = make_solver(load_scene(huygens::test::scenes_dir() + "/pool.json"));
  const RenderInfo info = solver->render_info();
  ASSERT_TRUE(info.particle_box_m.has_value());
  EXPECT_DOUBLE_EQ((*info.particle_box_m)[0], solver->meta()["container_m"][0].get<double>());
  EXPECT_DOUBLE_EQ((*info.particle_box_m)[2], solver->meta()["container_m"][2].get<double>());
  for (int k = 0; k < 3; ++k) solver->step();
  ASSERT_TRUE(solver->apply(cmd::Drop{0.05f, 0.05f, 0.02f, 0.01f}));  // a splash: some particles move fast
  solver->step();
  const std::span<const float> p = solver->particles();
  const auto out = solver->outputs();
  ASSERT_EQ(p.size(), out[0].shape[0] * 4);
  // the same positions and speeds as the "pos" and "vel" dumps (in id order; particles() in memory order)
  std::vector<std::array<float, 4>> a, b;
  float fastest = 0.0f;
  for (std::size_t i = 0; i < p.size() / 4; ++i) {
    a.push_back({p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]});
    const float* v = &out[1].data[3 * i];
    b.push_back({out[0].data[3 * i], out[0].data[3 * i + 1], out[0].data[3 * i + 2],
                 std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])});
    EXPECT_GE(p[4 * i + 3], 0.0f);
    fastest = std::max(fastest, p[4 * i + 3]);
  }
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  EXPECT_GT(fastest, 0.05f) << "the splash's particles have a speed";
  EXPECT_EQ(solver->particles().size(), p.size()) << "the same size every call";
}
