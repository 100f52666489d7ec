// Scene errors name the JSON path; the program exits 2 on each kind of error.
#include "huygens/common/scene.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>

#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"

using namespace huygens;

namespace {
std::string error_path_of(const std::string& text) {
  try {
    auto s = parse_scene_text(text);
    make_solver(s, RunOptions{false});
  } catch (const SceneError& e) {
    return e.path();
  }
  return "<no error>";
}
}  // namespace

TEST(JsonIn, TypesRangesAndUnknownKeys) {
  auto s = parse_scene_text(R"({"grid": {"n": 64, "length_m": 2.5, "bad": 1}, "list": [{"a": "x"}]})");
  auto grid = s.root().object("grid");
  EXPECT_EQ(grid.integer("n", 2, 1 << 14), 64);
  EXPECT_DOUBLE_EQ(grid.number("length_m", 0.0, 100.0), 2.5);
  EXPECT_DOUBLE_EQ(grid.number("absent", 7.0, 0.0, 10.0), 7.0);
  try {
    grid.allow_only({"n", "length_m"});
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.grid.bad");
  }
  try {
    grid.number("length_m", 3.0, 4.0);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.grid.length_m");
  }
  auto list = s.root().array("list");
  ASSERT_EQ(list.size(), 1u);
  try {
    list[0].string("a", "", {"y", "z"});
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.list[0].a");
  }
}

TEST(JsonIn, SyntaxErrorNamesLineAndColumn) {
  try {
    parse_scene_text("{\n  \"solver\": \"huygens\",\n  \"grid\": { \"n\": 64,, }\n}");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$");
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  }
}

TEST(JsonIn, UnknownSolverIsRefused) { EXPECT_EQ(error_path_of(R"({"solver": "navier"})"), "$.solver"); }

// ---- the "huygens" scene: one test per kind of error -------------
namespace {
// A valid scene with one field replaced (JSON-merge style) for the error tests.
std::string huygens_scene(const std::string& grid_json = "", const std::string& extra = "") {
  const std::string grid = grid_json.empty() ? R"({"n": 64, "length_m": 2.0, "margin": 8})" : grid_json;
  return R"({"solver": "huygens", "grid": )" + grid + R"(, "time": {"dt_s": 0.02}, "stokes": false,
             "initial": [{"type": "gaussian", "x_m": 1.0, "y_m": 1.0, "sigma_m": 0.1, "amplitude_m": 0.01}])" +
         extra + "}";
}
}  // namespace

TEST(HuygensScene, ValidSceneBuildsAndSteps) {
  auto solver = make_solver(parse_scene_text(huygens_scene({}, R"(, "drops": [{"t_s": 0.03, "x_m": 0.5, "y_m": 0.5,
      "radius_m": 0.05, "depth_m": 0.01}], "ships": [], "wind": null, "water": {"depth_m": null})")),
                            RunOptions{false});
  for (int i = 0; i < 3; ++i) solver->step();
  EXPECT_EQ(solver->height_rows(), 48u);
  EXPECT_EQ(solver->height().size(), 48u * 48u);
  const auto meta = solver->meta();
  EXPECT_EQ(meta["solver"], "huygens");
  EXPECT_EQ(meta["visible"]["rows"][0], 8);
  EXPECT_EQ(meta["visible"]["rows"][1], 56);
  const auto& st = solver->stats();
  EXPECT_EQ(st[st.find("drops")].calls, 1u);
  EXPECT_EQ(st[st.find("propagate")].calls, 3u);
}

TEST(HuygensScene, SyntaxError) { EXPECT_EQ(error_path_of("{\"solver\": \"huygens\", \"grid\": {\"n\": 64,, }"), "$"); }

TEST(HuygensScene, UnknownKey) {
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 64, "length_m": 2.0, "margin": 8, "size": 3})")), "$.grid.size");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "drop": [])")), "$.drop");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "drops": [{"t_s": 1, "x_m": 1, "y_m": 1, "radius_m": 0.1,
      "depth_m": 0.01, "colour": 3}])")),
            "$.drops[0].colour");
}

TEST(HuygensScene, WrongType) {
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": "64", "length_m": 2.0, "margin": 8})")), "$.grid.n");
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 64, "length_m": [2.0], "margin": 8})")), "$.grid.length_m");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "water": {"depth_m": "deep"})")), "$.water.depth_m");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "drops": {"t_s": 1})")), "$.drops");
}

TEST(HuygensScene, NegativeSize) {
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": -64, "length_m": 2.0, "margin": 8})")), "$.grid.n");
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 64, "length_m": -2.0, "margin": 8})")), "$.grid.length_m");
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 64, "length_m": 2.0, "margin": -1})")), "$.grid.margin");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "drops": [{"t_s": 1, "x_m": 1, "y_m": 1, "radius_m": -0.1,
      "depth_m": 0.01}])")),
            "$.drops[0].radius_m");
}

TEST(HuygensScene, MarginTooLargeForN) {
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 64, "length_m": 2.0, "margin": 32})")), "$.grid.margin");
}

TEST(HuygensScene, NonPowerOfTwoN) {
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 100, "length_m": 2.0, "margin": 8})")), "$.grid.n");
}

TEST(HuygensScene, OutOfRangeValues) {
  const std::string g = R"({"n": 64, "length_m": 2.0, "margin": 8})";
  EXPECT_EQ(error_path_of(R"({"solver": "huygens", "grid": )" + g + R"(, "time": {"dt_s": 0}})"), "$.time.dt_s");
  EXPECT_EQ(error_path_of(R"({"solver": "huygens", "grid": )" + g + R"(, "time": {"dt_s": -1}})"), "$.time.dt_s");
  EXPECT_EQ(error_path_of(R"({"solver": "huygens", "grid": )" + g + R"(})"), "$.time");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "drops": [{"t_s": 1, "x_m": 3, "y_m": 1, "radius_m": 0.1,
      "depth_m": 0.01}])")),
            "$.drops[0].x_m");
  EXPECT_EQ(error_path_of(R"({"solver": "huygens", "grid": )" + g +
                          R"(, "time": {"dt_s": 0.1}, "initial": [{"type": "ring"}]})"),
            "$.initial[0].type");
}

TEST(HuygensScene, Issue3FeatureErrorsNameTheirPath) {
  // stokes, ships, wind and render are parsed; bad values name their JSON path
  EXPECT_EQ(error_path_of(R"({"solver": "huygens", "grid": {"n": 64, "length_m": 2.0, "margin": 8},
      "time": {"dt_s": 0.1}, "stokes": "yes"})"),
            "$.stokes");
  EXPECT_EQ(error_path_of(R"({"solver": "huygens", "grid": {"n": 64, "length_m": 2.0, "margin": 8},
      "time": {"dt_s": 0.1}, "stokes": true})"),
            "<no error>");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "ships": [{"length_m": 1}])")), "$.ships[0].beam_m");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "ships": {"length_m": 1})")), "$.ships");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "wind": {"speed_mps": 5})")), "$.wind.direction_deg");
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "render": 3)")), "$.render");
  // a ship moving more than a quarter of its patch per step is refused before the run
  EXPECT_EQ(error_path_of(huygens_scene({}, R"(, "ships": [{"length_m": 0.1, "beam_m": 0.03, "draft_m": 0.01,
      "path": [{"t_s": 0, "x_m": 0.5, "y_m": 1}, {"t_s": 0.1, "x_m": 1.9, "y_m": 1}]}])")),
            "$.ships");
}

// Keys of the older format (no unit suffix) are refused at their path, naming the new key.
TEST(HuygensScene, OldKeysAreRefusedNamingTheNewOne) {
  auto message_of = [](const std::string& text) -> std::string {
    try {
      make_solver(parse_scene_text(text), RunOptions{false});
    } catch (const SceneError& e) {
      return e.what();
    }
    return "<no error>";
  };
  const std::string head = R"({"solver": "huygens", "grid": {"n": 64, "length_m": 2.0, "margin": 8}, )";
  struct Case {
    std::string scene, path, new_key;
  };
  const Case cases[] = {
      {head + R"("time": {"dt": 0.02}})", "$.time.dt", "dt_s"},
      {head + R"("time": {"dt_s": 0.02}, "water": {"gravity": 9.81}})", "$.water.gravity", "gravity_mps2"},
      {head + R"("time": {"dt_s": 0.02}, "water": {"surface_tension": 0}})", "$.water.surface_tension",
       "surface_tension_npm"},
      {head + R"("time": {"dt_s": 0.02}, "water": {"density": 1000}})", "$.water.density", "density_kgpm3"},
      {huygens_scene({}, R"(, "drops": [{"t": 0.1, "x_m": 1, "y_m": 1, "radius_m": 0.1, "depth_m": 0.01}])"),
       "$.drops[0].t", "t_s"},
      {huygens_scene({}, R"(, "ships": [{"length_m": 0.1, "beam_m": 0.03, "draft_m": 0.01,
          "path": [{"t_s": 0, "x_m": 0.5, "y_m": 1}, {"t": 1, "x_m": 0.6, "y_m": 1}]}])"),
       "$.ships[0].path[1].t", "t_s"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(error_path_of(c.scene), c.path);
    EXPECT_NE(message_of(c.scene).find("\"" + c.new_key + "\""), std::string::npos) << message_of(c.scene);
  }
}

namespace {
// The real program on a scene file with this grid: exit code 2 and the JSON path on stderr.
void expect_program_exits_two_naming(const std::string& name, const std::string& grid, const std::string& path) {
  const std::string dir = ::testing::TempDir();
  const std::string scene = dir + "/" + name + ".json", out = dir + "/" + name + ".out";
  {
    std::ofstream f(scene);
    f << huygens_scene(grid);
  }
  const std::string cmd = std::string(HUYGENS_CLI) + " run " + scene + " --steps 1 > " + out + " 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  std::ifstream f(out);
  const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find(path), std::string::npos) << text;
}
}  // namespace

TEST(HuygensScene, ProgramExitsTwoAndNamesThePath) {
  expect_program_exits_two_naming("bad_margin", R"({"n": 64, "length_m": 2.0, "margin": 40})", "$.grid.margin");
}

// ---- numbers the parser or a getter cannot hold: a SceneError with the path, never a crash ----
namespace {
std::string message_or_none(const std::string& text) {
  try {
    auto s = parse_scene_text(text);
    make_solver(s, RunOptions{false});
  } catch (const SceneError& e) {
    return e.what();
  }
  return "<no error>";
}
}  // namespace

TEST(JsonIn, NumberOverflowingADoubleNamesItsPath) {
  // nlohmann raises out_of_range.406 for these, which used to escape as an abort
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 64, "length_m": 1e400, "margin": 8})")), "$.grid.length_m");
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 64, "length_m": -1e400, "margin": 8})")), "$.grid.length_m");
  const std::string digits(400, '7');
  EXPECT_EQ(error_path_of(huygens_scene("", R"(, "drops": [{"t_s": 0.1}, {"t_s": )" + digits + "}]")),
            "$.drops[1].t_s");
  EXPECT_EQ(error_path_of(R"({"solver": "sph", "sph": {"container_m": [1, 2, 3e999]}})"), "$.sph.container_m[2]");
  const std::string m = message_or_none(huygens_scene(R"({"n": 64, "length_m": 1e400, "margin": 8})"));
  EXPECT_NE(m.find("overflow"), std::string::npos) << m;
  EXPECT_NE(m.find("1e400"), std::string::npos) << m;
}

TEST(JsonIn, IntegerGetterRefusesWhatAnIntegerCannotHold) {
  auto s = parse_scene_text(R"({"a": 1e300, "b": -1e300, "c": 18446744073709551615, "d": 9223372036854775808.0,
                                "e": 2.5, "f": "64", "g": 64.0, "h": true, "i": null, "j": [64]})");
  const JsonIn r = s.root();
  for (const char* key : {"a", "b", "c", "d", "e", "f", "h", "i", "j"}) {
    try {
      r.integer(key, 1, 1 << 14);
      ADD_FAILURE() << key << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.path(), std::string("$.") + key);
      EXPECT_NE(std::string(e.what()).find("[1, 16384]"), std::string::npos) << e.what();  // names the range
    }
  }
  EXPECT_EQ(r.integer("g", 1, 1 << 14), 64);  // 64.0 is 64
  // an unsigned above LLONG_MAX is not wrapped to a negative number inside a wide range
  EXPECT_THROW(r.integer("c", std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max()),
               SceneError);
  EXPECT_THROW(r.integer("c", -10, -1), SceneError);  // 2^64 - 1 would wrap to -1
}

TEST(JsonIn, NumberGettersRefuseWrongTypesNamingThePath) {
  auto s = parse_scene_text(R"({"x": "1.0", "v": [1, "2", 3], "w": [1, 2], "b": 1, "t": 3})");
  const JsonIn r = s.root();
  EXPECT_THROW(r.number("x", 0.0, 2.0), SceneError);
  try {
    r.vec<3>("v", 0.0, 10.0);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.v[1]");
  }
  try {
    r.vec<3>("w", 0.0, 10.0);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.w");
  }
  try {
    r.vec<2>("w", 0.0, 1.5);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "$.w[1]");
    EXPECT_NE(std::string(e.what()).find("[0, 1.5]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(r.boolean("b", false), SceneError);
  EXPECT_THROW(r.string("t", ""), SceneError);
}

TEST(JsonIn, LoadSceneRefusesADirectory) {
  try {
    load_scene(::testing::TempDir());
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos) << e.what();
  }
}

// An input with no size (/dev/zero) was read until memory ran out (2 GiB under a 3 GiB ulimit -v,
// then a syntax error); it is refused after 64 MiB, as a mesh file of a scene is.
TEST(JsonIn, AnEndlessSceneOrMeshFileIsRefusedAfter64MiB) {
  try {
    load_scene("/dev/zero");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("larger than 64 MiB"), std::string::npos) << e.what();
  }
  Scene s = parse_scene_text(R"({"solver": "sph"})");
  s.dir = "/dev";
  try {
    read_scene_file(s, "zero");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("larger than 64 MiB"), std::string::npos) << e.what();
  }
  s.dir = ::testing::TempDir();
  EXPECT_THROW(read_scene_file(s, "."), std::runtime_error);  // a directory
}

// The real program on a number that overflows a double: exit 2 and the path, no abort.
TEST(HuygensScene, ProgramExitsTwoOnANumberOverflow) {
  expect_program_exits_two_naming("overflow", R"({"n": 64, "length_m": 1e400, "margin": 8})", "$.grid.length_m");
}

// A key repeated in one object: nlohmann kept the later value silently ("n": 512, "n": 64 ran at 64).
TEST(JsonIn, ARepeatedKeyIsRefusedNamingItsPath) {
  EXPECT_EQ(error_path_of(huygens_scene(R"({"n": 512, "n": 64, "length_m": 1, "margin": 8})")), "$.grid.n");
  EXPECT_EQ(error_path_of(R"({"solver": "huygens", "solver": "sph"})"), "$.solver");
  const std::string m = message_or_none(huygens_scene("", R"(, "drops": [{"t_s": 0.1, "x_m": 1, "x_m": 2}])"));
  EXPECT_NE(m.find("$.drops[0].x_m"), std::string::npos) << m;
  EXPECT_NE(m.find("twice"), std::string::npos) << m;
  // the same key in different objects is not a repeat
  EXPECT_EQ(error_path_of(R"({"solver": "sph", "sph": {"spacing_m": 0.01, "container_m": [0.1, 0.1, 0.1],
      "fluid": [{"min_m": [0, 0, 0], "max_m": [0.1, 0.1, 0.05]}, {"min_m": [0, 0, 0.06], "max_m": [0.1, 0.1, 0.08]}]}})"),
            "<no error>");
}

TEST(HuygensScene, RoundTripEveryIsCheckedAndResolved) {
  for (const char* bad : {R"({"n": 64, "length_m": 2.0, "margin": 8, "round_trip_every": -1})",
                          R"({"n": 64, "length_m": 2.0, "margin": 8, "round_trip_every": 65})",
                          R"({"n": 64, "length_m": 2.0, "margin": 8, "round_trip_every": 2.5})",
                          R"({"n": 64, "length_m": 2.0, "margin": 8, "round_trip_every": "4"})"})
    EXPECT_EQ(error_path_of(huygens_scene(bad)), "$.grid.round_trip_every") << bad;
}
