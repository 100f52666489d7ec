#include "huygens/common/npy.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

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
