// libFuzzer target: bytes through parse_npy, the checks read_npy applies to a file. An NpyError
// is the expected refusal; any other exception, a crash, a sanitizer report or an array whose
// element count differs from its shape's product is a finding (docs/robustness.md, "Fuzzing").
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "huygens/common/npy.hpp"
#include "huygens/common/npy_read.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const huygens::NpyArray a = huygens::parse_npy(std::as_bytes(std::span(data, size)), "fuzz.npy");
    std::size_t count = 1;
    for (const std::size_t d : a.shape) count *= d;
    if (count != a.data.size()) std::abort();
    (void)huygens::first_invalid(a.data, -1e4, 1e4);
  } catch (const huygens::NpyError&) {
  }
  return 0;
}
