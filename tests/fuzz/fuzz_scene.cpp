// libFuzzer target: scene text through every parser `huygens run` applies before it allocates a
// solver (parse_scene_text, then parse_huygens_scene, parse_sph_scene or parse_lbm_scene). A
// SceneError, or a ResourceError from the memory check the parsers end with, is the expected
// refusal; any other exception, a crash or a sanitizer report is a finding (docs/robustness.md,
// "Fuzzing").
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "huygens/common/program.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/lbm/lbm_solver.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/spectral/spectral_solver.hpp"
#include "huygens/sph/sph_solver.hpp"

namespace {

// parse_lbm_scene allocates its initial fields (rows x cols cells) and loops over them per
// region; the target keeps to grids of at most 2^16 cells (the memory check of a real run refuses
// what does not fit). A value that is not a number is left to the parser to refuse.
bool lbm_grid_is_small(const nlohmann::json& doc) {
  if (!doc.contains("lbm") || !doc["lbm"].is_object() || !doc["lbm"].contains("grid")) return true;
  const nlohmann::json& grid = doc["lbm"]["grid"];
  if (!grid.is_object()) return true;
  double cells = 1;
  for (const char* key : {"rows", "cols"})
    if (grid.contains(key) && grid[key].is_number()) cells *= grid[key].get<double>();
  return cells <= 65536;
}

}  // namespace

// The memory check refuses above 1 GiB whatever the machine has, so that a finding does not
// depend on the memory free when the fuzzer runs.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  setenv("HUYGENS_MAX_MEMORY_GIB", "1", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const huygens::Scene scene = huygens::parse_scene_text(text, "fuzz.json");
    if (scene.solver == "huygens")
      huygens::parse_huygens_scene(scene, huygens::RunOptions{false});
    else if (scene.solver == "sph")
      huygens::parse_sph_scene(scene);
    else if (lbm_grid_is_small(*scene.doc))
      huygens::parse_lbm_scene(scene);
  } catch (const huygens::SceneError&) {
  } catch (const huygens::ResourceError&) {
  }
  return 0;
}
