#include "huygens/common/npy.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "huygens/common/npy_read.hpp"

using namespace huygens;

TEST(Npy, RoundTripAndHeaderLayout) {
  const std::string path = ::testing::TempDir() + "/npy_test.npy";
  std::vector<float> v(6);
  for (int i = 0; i < 6; ++i) v[i] = 0.5f * i - 1.0f;
  write_npy(path, v, {2, 3});
  auto a = read_npy(path);
  ASSERT_EQ(a.shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(a.data, v);
  // the data starts at a multiple of 64 bytes, as NumPy writes it
  EXPECT_EQ((std::filesystem::file_size(path) - 6 * sizeof(float)) % 64, 0u);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(Npy, OneDimensionalShapeHasTrailingComma) {
  const std::string path = ::testing::TempDir() + "/npy_1d.npy";
  std::vector<float> v = {1, 2, 3};
  write_npy(path, v, {3});
  std::ifstream f(path, std::ios::binary);
  std::string all((std::istreambuf_iterator<char>(f)), {});
  EXPECT_NE(all.find("'shape': (3, )"), std::string::npos);
  EXPECT_EQ(read_npy(path).shape, std::vector<std::size_t>{3});
}

TEST(Npy, ShapeMismatchThrows) {
  std::vector<float> v(5);
  EXPECT_THROW(write_npy(::testing::TempDir() + "/bad.npy", v, {2, 3}), std::invalid_argument);
}

// ---- the reader refuses every malformed file with NpyError naming the file ----
namespace {
// A .npy image: magic, version major.0, header length (2 bytes for version 1, else 4), the
// dict, then `data_bytes` zero bytes.
std::vector<std::byte> npy_image(const std::string& dict, std::size_t data_bytes = 0, int major = 1) {
  std::string s = "\x93NUMPY";
  s.push_back(static_cast<char>(major));
  s.push_back('\0');
  const std::size_t len = dict.size();
  for (int b = 0; b < (major == 1 ? 2 : 4); ++b) s.push_back(static_cast<char>((len >> (8 * b)) & 0xff));
  s += dict;
  s.append(data_bytes, '\0');
  std::vector<std::byte> out(s.size());
  std::memcpy(out.data(), s.data(), s.size());
  return out;
}
const std::string kDict23 = "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }\n";

// The message of the NpyError parse_npy raises (fails the test when it raises none).
std::string npy_error(const std::vector<std::byte>& bytes) {
  try {
    parse_npy(bytes, "in.npy");
  } catch (const NpyError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no NpyError";
  return "";
}
}  // namespace

TEST(NpyRead, AcceptsVersionsKeyOrderAndQuotes) {
  EXPECT_EQ(parse_npy(npy_image(kDict23, 24), "a.npy").shape, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(parse_npy(npy_image(kDict23, 24, 2), "a.npy").data.size(), 6u);
  const auto a = parse_npy(npy_image(R"({"shape": (), "fortran_order": False, "descr": "<f4"})", 4), "a.npy");
  EXPECT_TRUE(a.shape.empty());  // a 0-d array holds one value
  EXPECT_EQ(a.data.size(), 1u);
  EXPECT_EQ(parse_npy(npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (0, 5)}"), "a.npy").data.size(), 0u);
}

TEST(NpyRead, EachMalformedHeaderNamesTheFileAndTheFault) {
  struct Case {
    std::vector<std::byte> bytes;
    const char* says;
  };
  auto magic = npy_image(kDict23, 24);
  magic[1] = std::byte{'X'};
  auto len_past_end = npy_image(kDict23, 0);
  len_past_end[8] = std::byte{0xff};
  const std::vector<Case> cases = {
      {{}, "too short"},
      {magic, "bad magic"},
      {npy_image(kDict23, 24, 9), "version 9.0"},
      {len_past_end, "runs past the end"},
      {npy_image("garbage", 24), "expected '{'"},
      {npy_image("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", 48), "'<f8'"},
      {npy_image("{'descr': '<f4', 'fortran_order': True, 'shape': (2, 3), }", 24), "Fortran"},
      {npy_image("{'descr': '<f4', 'fortran_order': maybe, 'shape': (2, 3), }", 24), "True or False"},
      {npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (2, x), }", 24), "non-negative integers"},
      {npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (-2, 3), }", 24), "non-negative integers"},
      {npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3}", 24), "expected ')'"},
      {npy_image("{'descr': '<f4', 'fortran_order': False}", 24), "must give"},
      {npy_image("{'descr': '<f4', 'descr': '<f4', 'fortran_order': False, 'shape': (6,)}", 24), "twice"},
      {npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (6,), 'x': 1}", 24), "unknown header key"},
      {npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (6,)} junk", 24), "after the header"},
      {npy_image("{'descr': '<f4", 24), "unterminated"},
      {npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (99999999999999999999,)}"), "64 bits"},
      {npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (4294967296, 4294967296)}"), "count overflows"},
      {npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (4611686018427387904,)}"), "bytes overflows"},
      {npy_image(kDict23, 23), "truncated"},
      {npy_image(kDict23, 25), "trailing bytes"},
  };
  for (const Case& c : cases) {
    const std::string m = npy_error(c.bytes);
    EXPECT_EQ(m.rfind("in.npy: ", 0), 0u) << m;
    EXPECT_NE(m.find(c.says), std::string::npos) << m << " (expected: " << c.says << ")";
  }
}

// A header that claims 2^40 floats (4 TiB) over an empty data section: refused as truncated,
// naming the file, before the data are allocated (an allocation would throw std::bad_alloc).
TEST(NpyRead, LyingHeaderIsRefusedBeforeAllocating) {
  const std::string path = ::testing::TempDir() + "/npy_lying.npy";
  const auto bytes = npy_image("{'descr': '<f4', 'fortran_order': False, 'shape': (1099511627776,)}", 8);
  {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  try {
    read_npy(path);
    FAIL();
  } catch (const NpyError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
}

TEST(NpyRead, MissingFileAndDirectoryAreNpyErrors) {
  EXPECT_THROW(read_npy(::testing::TempDir() + "/no_such_file.npy"), NpyError);
  EXPECT_THROW(read_npy(::testing::TempDir()), NpyError);
}

TEST(NpyRead, FirstInvalidFindsNonFiniteAndOutOfRangeValues) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> ok = {0.f, -1.f, 1.f};
  EXPECT_EQ(first_invalid(ok, -1.0, 1.0), std::nullopt);
  EXPECT_EQ(first_invalid(std::vector<float>{0.f, 0.f, nan, inf}, -1.0, 1.0), 2u);
  EXPECT_EQ(first_invalid(std::vector<float>{0.f, -inf}, -1e30, 1e30), 1u);
  EXPECT_EQ(first_invalid(std::vector<float>{0.5f, 1.5f}, -1.0, 1.0), 1u);
}
