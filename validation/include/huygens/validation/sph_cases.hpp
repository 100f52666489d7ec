#pragma once
// The SPH validation cases as parametrised runs (kernels, hydrostatic column, Martin & Moyce dam
// break, no leakage, heightfield of paper 000 eq. 5-6): `huygens validate` runs the full sizes
// (sph_validation_cases() in validation.hpp), the tests run cheaper but meaningful ones.
#include <vector>

#include "huygens/sph/params.hpp"
#include "huygens/validation/reference/martin_moyce.hpp"
#include "huygens/validation/validation.hpp"

namespace huygens {

/// Kernel normalisation and antisymmetry at the default spacing (support_factor 2).
std::vector<ValidationRow> sph_kernel_rows(float support_factor = 2.0f);

/// Hydrostatic column of nx x nx x nz particles: settle (velocity damping) for settle_s, relax freely
/// for relax_s (the particles leave the cubic start lattice for a stable packing), then run free for
/// hold_s and check bottom pressure, pressure gradient, density error and stillness (the largest speed
/// of the particles below the surface layer, every step of the hold). Run from `starts` starts: start 0
/// the lattice as placed, start k > 0 the lattice with every coordinate moved by up to 1e-7 m (uniform,
/// seed k); each judged row is the worst start's, and one reported row per start gives its stillness.
/// The starts run in parallel (OpenMP). DFSPH: case "sph_hydrostatic_dfsph", mean density error within
/// 0.1 % (WCSPH 1 %).
std::vector<ValidationRow> sph_hydrostatic_rows(int nx, int nz, double settle_s, double relax_s, double hold_s,
                                                SphMethod method = SphMethod::wcsph, int starts = 4);

/// Up to this T = t sqrt(2 g / a) the Martin & Moyce points are reported rows, not judged: the model's
/// instant release on a free-slip floor runs ahead of the measured early front, and more so at finer
/// resolution (docs/sph.md, "Limits").
inline constexpr double kMartinMoyceEarlyT = 1.5;

/// Surge front of a dam break (column a x 2a, `na` particles across a) against the measured
/// points (martin_moyce_1952(), both series) up to T_end = t sqrt(2 g / a): reported up to
/// kMartinMoyceEarlyT, then 8 % up to T = 3, 10 % up to T = 5. DFSPH: case "sph_dam_break_dfsph", same
/// points and tolerances, plus the largest mean compression mean(max(0, rho/rho0 - 1)) at a step within
/// 6 dfsph_density_error.
std::vector<ValidationRow> sph_dam_break_rows(int na, double T_end, const std::vector<MartinMoycePoint>& measured,
                                              SphMethod method = SphMethod::wcsph);

/// No leakage over t_end seconds of a dam break at `na` particles across the column, in a box
/// container_len a long: inside the container, finite, max speed (every step) < 1.5 sqrt(2 g H).
std::vector<ValidationRow> sph_leakage_rows(int na, double t_end, float container_len);

/// No particle centre leaves the container, with either method: a dam break (column a wide and aspect a high,
/// `na` particles across a, 4 layers thick, box container_len a long and 4 a high) over t_end seconds, every
/// step: the largest distance of a centre beyond a container face (in spacings; negative: the closest any centre
/// came to a face, from inside), the most centres beyond a face at a step, non-finite. Case "sph_no_leakage_dfsph"
/// with DFSPH.
std::vector<ValidationRow> sph_containment_rows(int na, float aspect, float container_len, double t_end,
                                                SphMethod method);

/// No particle enters an obstacle: a dam break (spacing dx, m) onto a wedge read as an OBJ mesh,
/// a sphere, a vertical cylinder and a box, all boundary particles, over t_end seconds.
std::vector<ValidationRow> sph_obstacle_rows(float dx, double t_end);

/// Heightfield extraction: a settled flat pool (height = volume / area within half a spacing)
/// and a tilted lattice (slope of the extracted surface).
std::vector<ValidationRow> sph_heightfield_rows(int n, int depth, double settle_s, float slope);

}  // namespace huygens
