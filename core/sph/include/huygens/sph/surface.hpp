#pragma once
// 2.5D surface extraction of paper 000 (section 3, eq. 5-6): the implicit function
//   phi(x) = sum_i sqrt(1 - r_i^2 / R^2),   r_i = |x - x_i|   (terms with r_i >= R are 0),
// R the iso-radius, and the water surface phi(x) = iso. Instead of marching cubes the surface
// is sampled as ONE height per column of a 2D grid: for each column centre (x, y) the highest
// z with phi(x, y, z) = iso (found by marching down from above the highest particle that
// reaches the column, then bisection). Only particles of the 3 x 3 x 3 neighbour cells of the
// SPH grid (cell = support radius >= R) are visited. The container walls x = 0, lx, y = 0, ly and
// the floor are mirrors, as in the solver: phi includes the mirror images of the particles (the
// evaluation point is mirrored instead), so columns next to a wall do not dip.
// Normals come from central differences of the heights: n = (-dh/dx, -dh/dy, 1) / |...|.
#include <cstddef>
#include <span>
#include <vector>

#include "huygens/sph/grid.hpp"

namespace huygens {

struct SphSurfaceParams {
  /// Column spacing of the heightfield (unit: m).
  float cell_m = 0.01f;
  /// Iso-radius R of eq. 5 (unit: m); must not exceed the grid cell (support radius).
  float radius_m = 0.02f;
  /// Iso value of phi (unit: 1). Use sph_flat_iso() for the value that puts the surface of a flat
  /// particle lattice half a spacing above its top layer.
  float iso = 1.f;
  /// Bisection steps after the march (unit: 1); the height error is below R / 4 / 2^steps.
  int bisections = 8;
};

/// The heightfield: rows = y, cols = x, heights above the floor z = 0 (unit: m; 0 where dry)
/// and unit normals (rows x cols x 3).
struct SphHeightfield {
  std::size_t rows = 0, cols = 0;
  /// Column spacing (unit: m).
  float cell_m = 0;
  /// Container extent of the mirror walls (set by sph_heightfield_init; 0 = no mirror images) (unit: m).
  float lx_m = 0, ly_m = 0;
  std::vector<float> height;
  std::vector<float> normal;
};

/// Iso value for which phi of an infinite flat lattice (spacing `spacing`, top layer at z = 0)
/// crosses iso at z = spacing / 2, averaged over the column position within a lattice cell.
float sph_flat_iso(float radius, float spacing);

/// phi(x, y, z) of eq. 5 by a loop over the particles of the neighbour cells.
float sph_phi(const SphGrid& grid, const float* x, const float* y, const float* z, float radius, float px, float py,
              float pz);

/// Sizes `out` for a domain of lx x ly metres (call once, at construction).
void sph_heightfield_init(const SphSurfaceParams& p, float lx, float ly, SphHeightfield& out);

/// Extracts heights and normals from particles in the grid's sorted order (grid built on
/// exactly these positions). No allocation.
void sph_extract_heightfield(const SphSurfaceParams& p, const SphGrid& grid, const float* x, const float* y,
                             const float* z, SphHeightfield& out);

}  // namespace huygens
