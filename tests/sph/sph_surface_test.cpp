// The SPH heightfield (huygens/sph/surface.hpp; paper 000 eq. 5-6): phi over the grid's
// neighbour cells equals phi over every particle, a flat slab gives a flat field at the height
// sph_flat_iso() promises (half a spacing above the top layer) with vertical normals, and the
// settled and tilted cases of `huygens validate sph_heightfield` at test size.
#include <gtest/gtest.h>

#include <cmath>

#include "huygens/sph/surface.hpp"
#include "huygens/sph/system.hpp"
#include "huygens/validation/sph_cases.hpp"
#include "sph_test_helpers.hpp"

using namespace huygens;
using huygens::test::box_params;
using huygens::test::expect_rows_pass;

TEST(SphSurface, PhiOverTheNeighbourCellsIsPhiOverEveryParticle) {
  SphParams p = box_params(8, 4, 0.01f);
  const SphSystem s(p);
  const float R = s.support();
  for (const auto& q : {std::array<float, 3>{0.031f, 0.042f, 0.035f}, {0.001f, 0.079f, 0.041f}, {0.05f, 0.05f, 0.f}}) {
    double want = 0;
    for (std::size_t i = 0; i < s.count(); ++i) {
      const double dx = q[0] - s.x()[i], dy = q[1] - s.y()[i], dz = q[2] - s.z()[i];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 < double(R) * R) want += std::sqrt(1.0 - r2 / (double(R) * R));
    }
    EXPECT_GT(want, 0.0);
    EXPECT_NEAR(sph_phi(s.grid(), s.x().data(), s.y().data(), s.z().data(), R, q[0], q[1], q[2]), want, 1e-5 * want);
  }
}

TEST(SphSurface, FlatSlabGivesAFlatFieldHalfASpacingAboveItsTopLayer) {
  // static lattice 12 x 12 x 5 (top layer centres at 4.5 dx): every column, walls included (they
  // are mirrors), at the same height (columns above particle centres: one phi profile), within a
  // tenth of a spacing of 5 dx (the iso is averaged over column positions), normals vertical
  const float dx = 0.01f;
  const SphSystem s(box_params(12, 5, dx));
  SphSurfaceParams sp;
  sp.cell_m = dx;
  sp.radius_m = s.support();
  sp.iso = sph_flat_iso(sp.radius_m, dx);
  SphHeightfield hf;
  sph_heightfield_init(sp, 12 * dx, 12 * dx, hf);
  ASSERT_EQ(hf.rows, 12u);
  ASSERT_EQ(hf.cols, 12u);
  sph_extract_heightfield(sp, s.grid(), s.x().data(), s.y().data(), s.z().data(), hf);
  for (std::size_t k = 0; k < hf.rows * hf.cols; ++k) {
    EXPECT_NEAR(hf.height[k], hf.height[0], 1e-3 * dx) << "column " << k;
    EXPECT_NEAR(hf.height[k], 5 * dx, 0.1 * dx) << "column " << k;
    EXPECT_GT(hf.normal[3 * k + 2], 0.99f) << "column " << k;
  }
}

TEST(SphSurface, ALoneParticleLeavesEveryColumnDry) {
  SphParams p = box_params(8, 2, 0.01f);
  SphSystem s(p);
  const std::vector<float> X{0.01f}, Y{0.01f}, Z{0.01f};  // one particle in a corner
  s.set_particles(X, Y, Z);
  SphSurfaceParams sp;
  sp.cell_m = 0.01f;
  sp.radius_m = s.support();
  sp.iso = sph_flat_iso(sp.radius_m, 0.01f);
  SphHeightfield hf;
  sph_heightfield_init(sp, 0.08f, 0.08f, hf);
  sph_extract_heightfield(sp, s.grid(), s.x().data(), s.y().data(), s.z().data(), hf);
  // one particle (and its mirror images) never reaches the iso of a lattice: every column is dry
  for (float v : hf.height) EXPECT_EQ(v, 0.f);
}

TEST(SphSurface, SettledAndTiltedHeightfields) { expect_rows_pass(sph_heightfield_rows(10, 6, 0.3, 0.25f)); }
