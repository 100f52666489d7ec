// Must not compile: one solver's module including another's header (each solver sees common and
// pipeline only; core/CMakeLists.txt). ctest forbidden_include.
#include "huygens/lbm/shallow.hpp"
