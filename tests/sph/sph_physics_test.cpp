// The SPH physics of `huygens validate` at test size: hydrostatic column, Martin & Moyce dam
// break, no leakage. Label physics only (not unit): these are seconds-long runs whose rows are
// physical targets, and the sanitizer build (which runs the unit label) changes the summation
// order, to which a settling column's largest speed is sensitive (docs/sph.md).
#include <gtest/gtest.h>

#include <string>

#include "huygens/validation/reference/martin_moyce.hpp"
#include "huygens/validation/sph_cases.hpp"
#include "sph_test_helpers.hpp"

using namespace huygens;
using huygens::test::expect_rows_pass;

TEST(SphPhysics, HydrostaticColumnShort) {
  // 6 x 6 x 12 column, settled 0.5 s damped + 12.5 s free, held 1 s, from 2 starts (the lattice and the
  // lattice moved by up to 1e-7 m; validate: 6 x 6 x 16, 14 s free, 4 s held, 4 starts): bottom pressure
  // and pressure gradient within 2 % of the weight per area and rho0 g (boundary particles with Adami's
  // extrapolated wall pressure, gradient correction), density error below 1 %, max speed below the
  // surface layer below 1 % of sqrt(g H). The column leaves its start lattice in events of up to ~0.009
  // sqrt(g H) until t ~ 12.5 s at this size; after them the two starts read 0.0052 and 0.0005 (docs/sph.md,
  // "Limits"). ~80 s on one thread.
  expect_rows_pass(sph_hydrostatic_rows(6, 12, 0.5, 12.5, 1.0, SphMethod::wcsph, 2));
}

TEST(SphPhysics, DamBreakFrontCoarse) {
  // 10 particles across the column up to T = 3 (validate: 16 across, T <= 5); the four points at
  // T <= 1.5 are reported rows (EarlyFrontRunsAheadMoreAtFinerResolution)
  expect_rows_pass(sph_dam_break_rows(10, 3.0, martin_moyce_1952()));
}

// DFSPH at the size of DamBreakFrontCoarse (validate: sph_dam_break_dfsph, 16 across, T <= 5): the
// front within 8 % of both series for 1.5 < T <= 3 (the points at T <= 1.5 are reported), and the
// largest mean compression at a step within 6 times the density solve's tolerance, 3e-4 (measured
// 1.9e-4; 5.5e-4 with that tolerance loosened 10 times, which moves no front by more than 0.3 %).
// ~0.3 s on one thread.
TEST(SphPhysics, DamBreakFrontCoarseDfsph) {
  expect_rows_pass(sph_dam_break_rows(10, 3.0, martin_moyce_1952(), SphMethod::dfsph));
}

// Why the Martin & Moyce points at T <= 1.5 are reported, not judged (docs/sph.md, "Limits"): the
// early front of the model (instant release, free-slip floor) runs ahead of every measured point
// there, and further ahead at 16 particles across than at 10 (DFSPH, T = 1.212 of the 1.125 in series:
// +7.3 % and +9.8 %), so refining does not bring it onto the data. ~1.5 s on one thread.
TEST(SphPhysics, EarlyFrontRunsAheadMoreAtFinerResolution) {
  const auto coarse = sph_dam_break_rows(10, kMartinMoyceEarlyT, martin_moyce_1952(), SphMethod::dfsph);
  const auto fine = sph_dam_break_rows(16, kMartinMoyceEarlyT, martin_moyce_1952(), SphMethod::dfsph);
  int early = 0;
  for (std::size_t i = 0; i < coarse.size() && i < fine.size(); ++i) {
    if (coarse[i].quantity.find("front z/a") == std::string::npos) continue;
    ++early;
    EXPECT_FALSE(coarse[i].judged) << coarse[i].quantity;
    EXPECT_GT(coarse[i].measured, coarse[i].expected) << coarse[i].quantity;
    EXPECT_GT(fine[i].measured, coarse[i].measured) << fine[i].quantity;
  }
  EXPECT_EQ(early, 4);
}

// The invariants of the boundary over 1 s of the validate set-up (8 particles across a, a 4a box;
// validate runs 10 s): no particle leaves the container, nothing goes non-finite, and the maximum
// speed (sampled every step) stays below 1.5 sqrt(2 g H). The speed peaks in the jet up the end wall
// when the surge hits it (t ~ 0.19 s): 1.09 here with the impact viscosity, 1.49 without it. The bound
// is not met everywhere (12 and 24 across in an 8a box: 1.51, 1.54; docs/sph.md).
TEST(SphPhysics, NoLeakageShort) { expect_rows_pass(sph_leakage_rows(8, 1.0, 4.f)); }

// Boundary particles of every obstacle type keep the fluid out without a clamp: a dam break at
// dx = 0.02 m onto a wedge read as an OBJ mesh, a sphere, a cylinder and a box, 0.5 s (validate:
// dx = 0.01 m, 1 s): no particle centre passes the first layer of boundary particles (dx/2 behind
// a surface), nothing goes non-finite. The rows counting centres just beyond a surface are
// reported, not asserted here: zero-pressure water carried over a convex edge (the wedge's
// 64-degree ridge, the cylinder's rim) reaches up to 0.14 dx past the face at dx = 0.01 m, 0.32 dx
// before the contact density (docs/sph.md, "Convex edges").
TEST(SphPhysics, NoParticlePassesAnObstacleShort) {
  int asserted = 0;
  for (const auto& r : sph_obstacle_rows(0.02f, 0.5))
    if (r.quantity.find("first boundary layer") != std::string::npos ||
        r.quantity.find("non-finite") != std::string::npos) {
      EXPECT_TRUE(r.pass) << r.quantity << ": " << r.measured;
      ++asserted;
    }
  EXPECT_EQ(asserted, 3);
}

// DFSPH keeps every particle centre inside the container (no clamp anywhere): a dam break of 10 particles across
// a, columns 2a and a high, in a 4a box, 1 s (the surge, its impact on the end wall, the jet up it and onto the
// ceiling, the return wave onto the back wall), every step. Measured (dx; < 0: the closest any centre came, from
// inside): -0.15 and -0.11. Without the walls' contact in the constant-density solve (dfsph.hpp, "Walls") centres went
// 0.25 and 0.19 dx beyond the ceiling, the end wall and the side walls; without the divergence solve's
// particle-deficiency rule (SphParams::dfsph_min_neighbours) as well, the 2a column's run went non-finite at t =
// 0.46 s. ~3 s on one thread.
TEST(SphPhysics, DfsphKeepsEveryCentreInsideTheContainer) {
  for (const float aspect : {2.f, 1.f}) expect_rows_pass(sph_containment_rows(10, aspect, 4.f, 1.0, SphMethod::dfsph));
}

// The same at 20 across, column 2a high: -0.11 dx (without the contact 0.24 dx beyond the side walls; without either
// change 0.20 dx and non-finite at t = 0.53 s). ~12-25 s on one thread. 16 and 24 across and both columns: `huygens
// validate sph_no_leakage_dfsph`.
TEST(SphPhysics, DfsphKeepsEveryCentreInsideTheContainer20Across) {
  expect_rows_pass(sph_containment_rows(20, 2.f, 4.f, 1.0, SphMethod::dfsph));
}

// WCSPH keeps every particle centre inside the container: 10 across, the column a high, in an 8a box, 1 s. With the
// contact density's range at 0.8 dx (SphParams::wall_contact_range) a particle at rest density (p ~5 Pa) sank into a
// hollow of the floor's first boundary layer, 0.87 dx from its four particles at the face: 0.02 dx below the floor
// face at t = 1 s and still sinking. ~10-20 s on one thread.
TEST(SphPhysics, WcsphKeepsEveryCentreInsideTheContainer) {
  expect_rows_pass(sph_containment_rows(10, 1.f, 8.f, 1.0, SphMethod::wcsph));
}
