#pragma once
// NumPy .npy writer (format version 1.0, little-endian float32, C order) and
// a reader for the same (versions 1.0 to 3.0; its checks in npy_read.hpp), used by tests and by
// scenes that name an array (an LBM bed). Writes are an AtomicFile's (FILE.tmp, flushed, then
// renamed): a file that exists is always complete.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "huygens/common/atomic_file.hpp"

namespace huygens {

/// The bytes before the data of a float32 C-order .npy of this shape: magic, version 1.0, header
/// length and the header dict padded to a multiple of 64 bytes (write_npy writes exactly these;
/// the MPI dump writer writes them on rank 0 and each rank's rows after them).
std::string npy_header(const std::vector<std::size_t>& shape);

/// Writes `data` with the given shape (product of shape == data.size()). Throws on I/O error.
void write_npy(const std::string& path, std::span<const float> data, const std::vector<std::size_t>& shape,
               Sync sync = Sync::to_disk);

/// A float32 array read back from .npy.
struct NpyArray {
  std::vector<std::size_t> shape;
  std::vector<float> data;
};
/// Reads a float32 little-endian C-order .npy, a regular file. Throws NpyError (npy_read.hpp)
/// naming the file for anything else, before allocating more than the file holds.
NpyArray read_npy(const std::string& path);

}  // namespace huygens
