#pragma once
// The folder of the shipped scenes for the tests: the environment variable HUYGENS_SCENES_DIR,
// which CTest sets for every test (tests/CMakeLists.txt), so that no test program has a path of
// the source tree compiled in. Unset (a test run by hand from the source root): "scenes".
#include <cstdlib>
#include <string>

namespace huygens::test {

inline std::string scenes_dir() {
  const char* dir = std::getenv("HUYGENS_SCENES_DIR");
  return dir && *dir ? dir : "scenes";
}

}  // namespace huygens::test
