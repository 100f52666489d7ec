// Must not compile: a render pass including the viewer app's renderer (the passes are below the
// renderer that runs them; no mutual includes; viz/CMakeLists.txt). ctest forbidden_include.
#include "renderer.hpp"
