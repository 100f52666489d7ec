// The SPH neighbour grid (huygens/sph/grid.hpp): the counting sort groups every particle in its
// cell, the 9 row ranges around a cell hold exactly the particles of its 27 neighbour cells, and
// the per-thread gather copies them with the bottom layer first (or falls back to the ranges).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "huygens/sph/grid.hpp"

using namespace huygens;

namespace {

struct Cloud {
  std::vector<float> x, y, z;
};

// n particles uniformly in [0, lx] x [0, ly] x [0, lz] (fixed seed)
Cloud random_cloud(std::size_t n, float lx, float ly, float lz) {
  Cloud c;
  std::uint32_t s = 12345;
  auto rnd = [&]() { return (s = s * 1664525u + 1013904223u) / 4294967296.f; };
  for (std::size_t i = 0; i < n; ++i) {
    c.x.push_back(lx * rnd());
    c.y.push_back(ly * rnd());
    c.z.push_back(lz * rnd());
  }
  return c;
}

}  // namespace

TEST(SphGrid, CountingSortGroupsEveryParticleInItsCell) {
  SphGrid g({1.f, 0.5f, 0.7f}, 0.1f, 1000);
  const Cloud c = random_cloud(1000, 1.f, 0.5f, 0.7f);
  g.build(c.x.data(), c.y.data(), c.z.data(), 1000);
  std::vector<int> seen(1000, 0);
  for (std::size_t cell = 0; cell < g.cells(); ++cell)
    for (std::uint32_t k = g.start(cell); k < g.start(cell + 1); ++k) {
      const std::uint32_t o = g.order()[k];
      ++seen[o];
      EXPECT_EQ(g.index(g.ix(c.x[o]), g.iy(c.y[o]), g.iz(c.z[o])), cell);
    }
  for (int v : seen) EXPECT_EQ(v, 1);
  EXPECT_EQ(g.start(g.cells()), 1000u);
  // stable: within a cell the original order is kept
  for (std::size_t cell = 0; cell < g.cells(); ++cell)
    for (std::uint32_t k = g.start(cell) + 1; k < g.start(cell + 1); ++k) EXPECT_LT(g.order()[k - 1], g.order()[k]);
}

TEST(SphGrid, PointsOutsideAreClampedToTheBorderCells) {
  const SphGrid g({1.f, 0.5f, 0.7f}, 0.1f, 1);
  EXPECT_EQ(g.nx(), 10);
  EXPECT_EQ(g.ny(), 5);
  EXPECT_EQ(g.nz(), 7);
  EXPECT_EQ(g.ix(-0.3f), 0);
  EXPECT_EQ(g.ix(1.f), 9);
  EXPECT_EQ(g.iz(0.25f), 2);
}

TEST(SphGrid, RowsAroundACellHoldExactlyItsNeighbourCells) {
  SphGrid g({0.5f, 0.4f, 0.3f}, 0.1f, 2000);
  const Cloud c = random_cloud(2000, 0.5f, 0.4f, 0.3f);
  g.build(c.x.data(), c.y.data(), c.z.data(), 2000);
  for (const auto& cell : {std::array<int, 3>{0, 0, 0}, {2, 1, 1}, {4, 3, 2}, {2, 0, 2}}) {
    std::vector<std::uint32_t> got;
    int rows = 0, last_kz = -1;
    g.for_each_row(cell[0], cell[1], cell[2], [&](std::uint32_t b, std::uint32_t e, int kz) {
      EXPECT_GE(kz, last_kz);  // layer by layer from below
      last_kz = kz;
      ++rows;
      for (std::uint32_t k = b; k < e; ++k) got.push_back(g.order()[k]);
      return true;
    });
    std::vector<std::uint32_t> want;
    for (std::uint32_t i = 0; i < 2000; ++i)
      if (std::abs(g.ix(c.x[i]) - cell[0]) <= 1 && std::abs(g.iy(c.y[i]) - cell[1]) <= 1 &&
          std::abs(g.iz(c.z[i]) - cell[2]) <= 1)
        want.push_back(i);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want) << "cell " << cell[0] << " " << cell[1] << " " << cell[2];
    const int ny = std::min(cell[1] + 1, g.ny() - 1) - std::max(cell[1] - 1, 0) + 1;
    const int nz = std::min(cell[2] + 1, g.nz() - 1) - std::max(cell[2] - 1, 0) + 1;
    EXPECT_EQ(rows, ny * nz);
  }
  // stopping early
  int calls = 0;
  EXPECT_FALSE(g.for_each_row(2, 1, 1, [&](std::uint32_t, std::uint32_t, int) { return ++calls < 2; }));
  EXPECT_EQ(calls, 2);
}

TEST(SphCellGather, CopiesTheFluidAndTheBoundaryCandidates) {
  SphGrid g({0.5f, 0.4f, 0.3f}, 0.1f, 2000);
  const Cloud c = random_cloud(2000, 0.5f, 0.4f, 0.3f);
  g.build(c.x.data(), c.y.data(), c.z.data(), 2000);
  // static particles: another cloud, partly outside the grid (clamped into the edge cells)
  Cloud st = random_cloud(500, 0.7f, 0.4f, 0.3f);
  for (float& x : st.x) x -= 0.1f;
  std::vector<std::uint32_t> so(500);
  g.build_static(st.x.data(), st.y.data(), st.z.data(), 500, so.data());
  std::vector<float> sx(2000), sz(2000), bx(500);
  for (std::size_t k = 0; k < 2000; ++k) {
    sx[k] = c.x[g.order()[k]];
    sz[k] = c.z[g.order()[k]];
  }
  for (std::size_t k = 0; k < 500; ++k) bx[k] = st.x[so[k]];
  SphCellGather gather(2000);
  const float* src[2] = {sx.data(), sz.data()};
  const float* bsrc[1] = {bx.data()};
  SphCellGather::Cursor cur(g, gather, 0, src, 2, bsrc, 1);
  std::vector<float> want_x, want_b;
  g.for_each_row(0, 1, 0, [&](std::uint32_t b, std::uint32_t e, int) {
    want_x.insert(want_x.end(), sx.begin() + b, sx.begin() + e);
    return true;
  });
  g.for_each_row<true>(0, 1, 0, [&](std::uint32_t b, std::uint32_t e, int) {
    want_b.insert(want_b.end(), bx.begin() + b, bx.begin() + e);
    return true;
  });
  int calls = 0;
  std::uint32_t count = 0, bcount = 0;
  const bool gathered = cur.visit(0, 1, 0, [&](bool gath, bool bnd, std::uint32_t b, std::uint32_t e) {
    ++calls;
    EXPECT_TRUE(gath);
    EXPECT_EQ(b, 0u);
    (bnd ? bcount : count) = e;
  });
  EXPECT_TRUE(gathered);
  EXPECT_EQ(calls, 2);
  ASSERT_EQ(count, want_x.size());
  ASSERT_EQ(bcount, want_b.size());
  ASSERT_GT(bcount, 0u);
  for (std::uint32_t k = 0; k < count; ++k) EXPECT_EQ(cur.scratch(0)[k], want_x[k]);
  for (std::uint32_t k = 0; k < bcount; ++k) EXPECT_EQ(cur.scratch(2)[k], want_b[k]);
  // every static particle is in the cell of its clamped coordinates
  for (std::size_t c0 = 0; c0 < g.cells(); ++c0)
    for (std::uint32_t k = g.static_start(c0); k < g.static_start(c0 + 1); ++k)
      EXPECT_EQ(g.index(g.ix(bx[k]), g.iy(st.y[so[k]]), g.iz(st.z[so[k]])), c0);
}

TEST(SphCellGather, FallsBackToTheNineRangesWhenACellOverflows) {
  SphGrid g({0.5f, 0.4f, 0.3f}, 0.1f, 2000);
  const Cloud c = random_cloud(2000, 0.5f, 0.4f, 0.3f);
  g.build(c.x.data(), c.y.data(), c.z.data(), 2000);
  SphCellGather gather(16);  // ~400 candidates around an interior cell
  std::vector<float> sx(2000, 0.f);
  const float* src[1] = {sx.data()};
  SphCellGather::Cursor cur(g, gather, 0, src, 1);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges, want;
  const bool gathered = cur.visit(2, 1, 1, [&](bool gath, bool bnd, std::uint32_t b, std::uint32_t e) {
    EXPECT_FALSE(gath);
    EXPECT_FALSE(bnd);
    ranges.emplace_back(b, e);
  });
  g.for_each_row(2, 1, 1, [&](std::uint32_t b, std::uint32_t e, int) {
    want.emplace_back(b, e);
    return true;
  });
  EXPECT_FALSE(gathered);
  EXPECT_EQ(ranges, want);
  EXPECT_EQ(ranges.size(), 9u);
}
