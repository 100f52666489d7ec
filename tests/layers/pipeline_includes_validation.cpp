// Must not compile: the core's pipeline including the validation library (the core never depends on
// validation; docs/design.md 1). ctest forbidden_include.
#include "huygens/validation/validation.hpp"
