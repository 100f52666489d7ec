#include "huygens/common/npy.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "huygens/common/atomic_file.hpp"

namespace huygens {

std::string npy_header(const std::vector<std::size_t>& shape) {
  std::ostringstream dict;
  dict << "{'descr': '<f4', 'fortran_order': False, 'shape': (";
  for (std::size_t i = 0; i < shape.size(); ++i)
    dict << shape[i] << (shape.size() == 1 || i + 1 < shape.size() ? ", " : "");
  dict << "), }";
  std::string header = dict.str();
  // magic (6) + version (2) + header length (2) + header + '\n' is padded to 64 bytes.
  const std::size_t total = 10 + header.size() + 1;
  header.append((64 - total % 64) % 64, ' ');
  header.push_back('\n');
  const unsigned short len = static_cast<unsigned short>(header.size());
  const char lead[10] = {
      '\x93', 'N', 'U', 'M', 'P', 'Y', 1, 0, static_cast<char>(len & 0xff), static_cast<char>(len >> 8)};
  return std::string(lead, sizeof lead) + header;
}

void write_npy(const std::string& path, std::span<const float> data, const std::vector<std::size_t>& shape, Sync sync) {
  std::size_t count = 1;
  for (auto s : shape) count *= s;
  if (count != data.size()) throw std::invalid_argument("write_npy: shape does not match data size");
  AtomicFile f(path, sync);
  f.write(npy_header(shape));
  f.write(std::as_bytes(data));
  f.commit();
}

// read_npy, parse_npy: npy_read.cpp

}  // namespace huygens
