// Must not compile: a viewer file including a solver's header (the viewer reads the core through
// pipeline/solver.hpp and pipeline/render_info.hpp only; docs/design.md 1). ctest forbidden_include.
#include "huygens/spectral/spectral_solver.hpp"
