// Section "huygens": the propagator's step against the raw FFTW transforms it performs.
#include "bench.hpp"

namespace huygens::bench {

void bench_huygens(Context&) {}

}  // namespace huygens::bench
