// Must not compile: a render pass including the solver registry (a pass reads the core's render
// description only, huygens/pipeline). ctest forbidden_include.
#include "huygens/solvers/registry.hpp"
