// The solver registry (solvers/registry.hpp) with the test-only toy solver registered from outside
// the library (register_solver.cpp, register_cases.cpp): found by name, built, sized, validated.
#include "huygens/solvers/registry.hpp"

#include <gtest/gtest.h>

#include "huygens/solvers/sizing.hpp"
#include "huygens/validation/validation.hpp"
#include "toy_solver.hpp"

using namespace huygens;

namespace {
const char* kToy = R"({"solver": "toy", "toy": {"n": 32, "dt_s": 0.005}})";
}

TEST(Registry, LibrarySolversComeFirstThenTheRegisteredOnes) {
  std::vector<std::string> names;
  for (const SolverEntry& e : registered_solvers()) names.push_back(e.name);
  EXPECT_EQ(names, (std::vector<std::string>{"huygens", "sph", "lbm", "toy"}));
}

TEST(Registry, UnknownSolverNamesThePathAndTheRegisteredNames) {
  try {
    make_solver(parse_scene_text(R"({"solver": "tsunami"})"));
    FAIL() << "an unknown solver was built";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("$.solver"), std::string::npos) << what;
    EXPECT_NE(what.find("\"toy\""), std::string::npos) << what;
  }
}

TEST(Registry, ANameRegistersOnce) {
  EXPECT_THROW(register_solver(toy::toy_solver_entry()), std::invalid_argument);
  SolverEntry nameless = toy::toy_solver_entry();
  nameless.name = "";
  EXPECT_THROW(register_solver(nameless), std::invalid_argument);
  SolverEntry no_factory = toy::toy_solver_entry();
  no_factory.name = "toy2";
  no_factory.make = nullptr;
  EXPECT_THROW(register_solver(no_factory), std::invalid_argument);
}

TEST(Registry, TheToyIsBuiltSizedAndStepped) {
  const Scene scene = parse_scene_text(kToy);
  auto solver = make_solver(scene, RunOptions{false});
  ASSERT_EQ(solver->height_rows(), 32u);
  const float start = solver->height()[0];
  for (int i = 0; i < 10; ++i) solver->step();
  EXPECT_EQ(solver->steps(), 11);
  EXPECT_LT(solver->height()[0], start);  // a standing wave on its way down from its crest
  const SceneSizing z = scene_sizing(scene);
  EXPECT_EQ(z.solver, "toy");
  EXPECT_FALSE(z.distributed);
  EXPECT_EQ(scene_rank_memory(scene)(4).total(), 3u * 32u * 32u * 4u);
}

TEST(Registry, AToySceneErrorNamesItsPath) {
  try {
    make_solver(parse_scene_text(R"({"solver": "toy", "toy": {"n": 64, "dt_s": 1}})"));
    FAIL() << "an unstable step was accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("$.toy.dt_s"), std::string::npos) << e.what();
  }
}

TEST(Registry, TheToysValidationCaseRunsAfterTheLibrarysAndPasses) {
  const std::vector<ValidationCase> all = all_validation_cases();
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front().solver, "huygens");
  EXPECT_EQ(all.back().name, "toy_standing_wave");
  for (const ValidationRow& r : all.back().run()) EXPECT_TRUE(r.pass) << r.quantity << " " << r.error;
}
