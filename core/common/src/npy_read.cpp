#include "huygens/common/npy_read.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

namespace huygens {

namespace {

static_assert(std::endian::native == std::endian::little, "the .npy reader copies '<f4' data as is");

// The largest header dict accepted (NumPy writes well under 1 KiB; version 2 allows 4 GiB).
constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

[[noreturn]] void npy_fail(const std::string& name, const std::string& what) { throw NpyError(name + ": " + what); }

// Where the data of a .npy start, its shape and its element count.
struct NpyLayout {
  std::vector<std::size_t> shape;
  std::size_t count = 1;
  std::size_t data_offset = 0;
};

// The header dict, a Python literal: {'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }
// with the three keys in any order, single or double quotes, optional trailing commas.
class HeaderDict {
 public:
  HeaderDict(std::string text, std::string name) : t_(std::move(text)), name_(std::move(name)) {}

  void parse(std::string& descr, bool& fortran, std::vector<std::size_t>& shape) {
    bool seen[3] = {false, false, false};
    expect('{');
    while (!eat('}')) {
      const std::string key = quoted();
      expect(':');
      const int k = key == "descr" ? 0 : key == "fortran_order" ? 1 : key == "shape" ? 2 : -1;
      if (k < 0) fail("unknown header key '" + key + "'");
      if (seen[k]) fail("header key '" + key + "' given twice");
      seen[k] = true;
      if (k == 0) descr = quoted();
      if (k == 1) fortran = boolean();
      if (k == 2) shape = tuple();
      if (!eat(',')) {
        expect('}');
        break;
      }
    }
    skip_space();
    if (pos_ != t_.size()) fail("unexpected text after the header dict at offset " + std::to_string(pos_));
    if (!seen[0] || !seen[1] || !seen[2]) fail("the header dict must give 'descr', 'fortran_order' and 'shape'");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { npy_fail(name_, "bad header: " + what); }
  void skip_space() {
    while (pos_ < t_.size() && (t_[pos_] == ' ' || t_[pos_] == '\n' || t_[pos_] == '\t' || t_[pos_] == '\r')) ++pos_;
  }
  bool eat(char c) {
    skip_space();
    if (pos_ >= t_.size() || t_[pos_] != c) return false;
    ++pos_;
    return true;
  }
  void expect(char c) {
    if (!eat(c)) fail(std::string("expected '") + c + "' at offset " + std::to_string(pos_));
  }
  std::string quoted() {
    skip_space();
    const char q = pos_ < t_.size() ? t_[pos_] : '\0';
    if (q != '\'' && q != '"') fail("expected a quoted string at offset " + std::to_string(pos_));
    const auto end = t_.find(q, pos_ + 1);
    if (end == std::string::npos) fail("unterminated string at offset " + std::to_string(pos_));
    std::string out = t_.substr(pos_ + 1, end - pos_ - 1);
    pos_ = end + 1;
    return out;
  }
  bool boolean() {
    skip_space();
    for (const bool b : {true, false}) {
      const std::string w = b ? "True" : "False";
      if (t_.compare(pos_, w.size(), w) == 0) {
        pos_ += w.size();
        return b;
      }
    }
    fail("'fortran_order' must be True or False");
  }
  // "(d0, d1, ...)": non-negative decimal integers, each below 2^64
  std::vector<std::size_t> tuple() {
    std::vector<std::size_t> dims;
    expect('(');
    while (!eat(')')) {
      skip_space();
      if (pos_ >= t_.size() || t_[pos_] < '0' || t_[pos_] > '9')
        fail("'shape' must be a tuple of non-negative integers");
      std::size_t d = 0;
      for (; pos_ < t_.size() && t_[pos_] >= '0' && t_[pos_] <= '9'; ++pos_)
        if (__builtin_mul_overflow(d, std::size_t{10}, &d) ||
            __builtin_add_overflow(d, std::size_t(t_[pos_] - '0'), &d))
          fail("a 'shape' dimension does not fit in 64 bits");
      dims.push_back(d);
      if (!eat(',')) {
        expect(')');
        break;
      }
    }
    return dims;
  }

  std::string t_;
  std::string name_;
  std::size_t pos_ = 0;
};

// The magic string, version and header length of `head` (the first bytes of a file of
// `file_size` bytes, the whole header when the file holds it); the dict's shape checked against
// the file size.
NpyLayout parse_layout(std::span<const std::byte> head, std::size_t file_size, const std::string& name) {
  const auto u8 = [&](std::size_t i) { return static_cast<std::size_t>(std::to_integer<unsigned char>(head[i])); };
  const std::string too_short = "too short for a .npy file (" + std::to_string(file_size) + " bytes)";
  if (head.size() < 10) npy_fail(name, too_short);
  if (std::memcmp(head.data(), "\x93NUMPY", 6) != 0) npy_fail(name, "not a .npy file (bad magic string)");
  const std::size_t major = u8(6), minor = u8(7);
  if (major < 1 || major > 3 || minor != 0)
    npy_fail(name, "unsupported .npy format version " + std::to_string(major) + "." + std::to_string(minor) +
                       " (1.0, 2.0 and 3.0 are read)");
  // version 1: a 2-byte little-endian header length; versions 2 and 3: 4 bytes
  const std::size_t start = major == 1 ? 10 : 12;
  if (head.size() < start) npy_fail(name, too_short);
  const std::size_t len = major == 1 ? u8(8) | u8(9) << 8 : u8(8) | u8(9) << 8 | u8(10) << 16 | u8(11) << 24;
  if (len > kMaxHeaderBytes) npy_fail(name, "header length " + std::to_string(len) + " exceeds 1 MiB");
  if (start + len > file_size || start + len > head.size())
    npy_fail(name, "header length " + std::to_string(len) + " runs past the end of the file (" +
                       std::to_string(file_size) + " bytes)");
  std::string descr;
  bool fortran = false;
  NpyLayout out;
  HeaderDict(std::string(reinterpret_cast<const char*>(head.data()) + start, len), name)
      .parse(descr, fortran, out.shape);
  if (descr != "<f4") npy_fail(name, "dtype '" + descr + "' is not '<f4' (little-endian float32)");
  if (fortran) npy_fail(name, "Fortran-order arrays are not read (C order only)");
  for (const std::size_t d : out.shape)
    if (__builtin_mul_overflow(out.count, d, &out.count)) npy_fail(name, "the shape's element count overflows");
  std::size_t bytes = 0;
  if (__builtin_mul_overflow(out.count, sizeof(float), &bytes))
    npy_fail(name, "the shape's size in bytes overflows (" + std::to_string(out.count) + " elements)");
  out.data_offset = start + len;
  const std::size_t held = file_size - out.data_offset;
  if (bytes != held)
    npy_fail(name, "the shape needs " + std::to_string(bytes) + " data bytes but the file holds " +
                       std::to_string(held) + (bytes > held ? " (truncated)" : " (trailing bytes)"));
  return out;
}

}  // namespace

NpyArray parse_npy(std::span<const std::byte> bytes, const std::string& name) {
  const NpyLayout l = parse_layout(bytes, bytes.size(), name);
  NpyArray a;
  a.shape = l.shape;
  a.data.resize(l.count);
  if (l.count) std::memcpy(a.data.data(), bytes.data() + l.data_offset, l.count * sizeof(float));
  return a;
}

NpyArray read_npy(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) npy_fail(path, "cannot read: no such file");
  // a regular file only: its size is known before reading (not /dev/zero or a pipe)
  if (!std::filesystem::is_regular_file(status)) npy_fail(path, "cannot read: not a regular file");
  const std::size_t size = std::filesystem::file_size(path, ec);
  if (ec) npy_fail(path, "cannot read: " + ec.message());
  std::ifstream f(path, std::ios::binary);
  if (!f) npy_fail(path, "cannot open for reading");
  // the header first (at most 12 bytes + 1 MiB), checked against the file size before the data
  // are allocated
  std::vector<std::byte> head(std::min(size, 12 + kMaxHeaderBytes));
  f.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  if (f.gcount() != static_cast<std::streamsize>(head.size())) npy_fail(path, "read error in the header");
  const NpyLayout l = parse_layout(head, size, path);
  NpyArray a;
  a.shape = l.shape;
  a.data.resize(l.count);
  const auto bytes = static_cast<std::streamsize>(l.count * sizeof(float));
  f.clear();
  f.seekg(static_cast<std::streamoff>(l.data_offset));
  f.read(reinterpret_cast<char*>(a.data.data()), bytes);
  if (!f || f.gcount() != bytes) npy_fail(path, "read error in the data (the file shrank while being read?)");
  return a;
}

std::optional<std::size_t> first_invalid(std::span<const float> v, double lo, double hi) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!(std::isfinite(v[i]) && v[i] >= lo && v[i] <= hi)) return i;
  return std::nullopt;
}

}  // namespace huygens
