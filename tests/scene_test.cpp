// Scene errors name the JSON path; the program exits 2 on each kind of error.
#include "huygens/scene.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "huygens/solver.hpp"

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

TEST(JsonIn, UnknownSolverIsRefused) {
  EXPECT_EQ(error_path_of(R"({"solver": "navier"})"), "$.solver");
}
