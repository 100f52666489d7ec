#pragma once
// The .npy reader's checks (NumPy format versions 1.0 to 3.0, little-endian float32, C order).
// The reader trusts nothing in the file: a bad magic string or version, a header dict that is
// not {'descr': '<f4', 'fortran_order': False, 'shape': (d0, d1, ...)}, a shape whose element
// count overflows and a data size that differs from the shape's are an NpyError naming the file
// and what is wrong, raised before the data are allocated (docs/robustness.md).
#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>

#include "huygens/common/npy.hpp"

namespace huygens {

/// A malformed or unsupported .npy: what() names the file and what is wrong.
class NpyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses a whole .npy held in memory (read_npy, npy.hpp, reads a file); `name` stands for the file in messages.
NpyArray parse_npy(std::span<const std::byte> bytes, const std::string& name);

/// Index of the first value that is not finite or lies outside [lo, hi]; nullopt when all are
/// valid. For callers that check the values of an array a user supplied.
std::optional<std::size_t> first_invalid(std::span<const float> v, double lo, double hi);

}  // namespace huygens
