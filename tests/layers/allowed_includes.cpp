// The control of ctest forbidden_include: what the viewer may include compiles with the viewer's link
// line, so a failure of the three others is their forbidden header, not the test's set-up.
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/render_info.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/solvers/registry.hpp"
