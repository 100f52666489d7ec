#pragma once
// Parameters of the SPH fluid (paper 000 section 3 after Mueller, Charypar and Gross 2003): the
// particle lattice, the weakly compressible Tait fluid p = max(0, B ((rho/rho0)^gamma - 1)),
// B = rho0 c0^2 / gamma, its viscosities, the container, the fluid blocks, the obstacles and the
// adaptive time step. Why each choice: docs/sph.md.
#include <array>
#include <vector>

#include "huygens/sph/boundary.hpp"

namespace huygens {

/// A box of fluid particles placed on a lattice of the particle spacing (cell centres).
struct SphFluidBlock {
  /// Lower corner (unit: m).
  std::array<float, 3> min_m{0.f, 0.f, 0.f};
  /// Upper corner (unit: m).
  std::array<float, 3> max_m{0.1f, 0.1f, 0.1f};
};

/// The pressure solver (unit: choice). wcsph: weakly compressible, pressure from the Tait equation
/// of state, explicit, time step bounded by the sound speed. dfsph: divergence-free SPH of Bender and
/// Koschier 2015 (dfsph.hpp): a divergence-free and a constant-density solve per step, both with warm
/// start, time step bounded by the particle speed.
enum class SphMethod { wcsph, dfsph };

/// The wall pressure of the DFSPH solver (SphParams::dfsph_wall).
enum class SphDfsphWall { akinci, mirror, hydrostatic };

struct SphParams {
  /// Pressure solver (unit: choice; scene key "method": "wcsph" (default) or "dfsph").
  SphMethod method = SphMethod::wcsph;
  /// DFSPH: largest mean predicted compression of the constant-density solve, mean over the
  /// particles of |rho*_i - rho0| / rho0 where kappa_i > 0, else max(0, rho*_i - rho0) / rho0 (Bender and Koschier
  /// 2015 section 4.2 ask 0.01 %; 0.005 % here: at 0.01 % the solve stops with the hydrostatic pressure ~5 % short,
  /// docs/sph.md "DFSPH") (unit: 1).
  float dfsph_density_error = 5e-5f;
  /// DFSPH: largest mean divergence error of the divergence-free solve, mean of max(0, dt Drho_i/Dt) / rho0
  /// (section 4.1; 0.1 %) (unit: 1).
  float dfsph_divergence_error = 1e-3f;
  /// DFSPH: CFL number on the particle spacing, dt <= dfsph_cfl dx / v_max (section 4.3: 0.4) (unit: 1).
  float dfsph_cfl = 0.4f;
  /// DFSPH: relaxation omega of the Jacobi updates, kappa += omega (error) alpha / dt^2 (unit: 1).
  float dfsph_relaxation = 0.5f;
  /// DFSPH: the boundary particle's pressure p_b in the pair term (p_i/rho_i^2 + p_b/rho0^2) of fluid particle i
  /// (dfsph.hpp): akinci, Akinci et al. 2012 eq. 10's single p_i/rho_i^2 (no p_b); mirror, p_b = p_i; hydrostatic,
  /// p_b = p_i + rho0 g . (x_b - x_i), Adami et al. 2012 eq. 27 with the one fluid particle (unit: choice).
  SphDfsphWall dfsph_wall = SphDfsphWall::hydrostatic;
  /// DFSPH: Chebyshev semi-iteration over the Jacobi updates (Wang 2015), the estimated spectral radius rho of the
  /// Jacobi iteration; 0 = plain Jacobi (unit: 1).
  float dfsph_chebyshev_rho = 0.95f;
  /// DFSPH: Jacobi updates from the compression only, kappa += omega max(0, error) alpha / dt^2, so kappa never
  /// decreases within a solve (stable at omega = 1; false: the signed error, kappa >= 0, stable below omega ~0.7:
  /// docs/sph.md "DFSPH") (unit: on/off).
  bool dfsph_compression_only = false;
  /// DFSPH: the share of the last step's kappa and kappa^v a solve starts from (warm start; 1 = all of
  /// it; below 1 the Jacobi noise that the full warm start carries from step to step decays) (unit: 1).
  float dfsph_warm_start = 0.8f;
  /// DFSPH: most Jacobi iterations of either solve in one step (unit: 1).
  int dfsph_max_iterations = 100;
  /// DFSPH: contact range r_c of the walls and obstacles, as a multiple of the spacing (unit: 1; 0 = off). The
  /// constant-density solve also keeps every fluid particle's centre r_c from each boundary particle at the end of the
  /// step, by a push of the wall alone (dfsph.hpp, "Walls"). 0.9: above sqrt(3)/2 = 0.866, the distance from a wall
  /// face to the four first-layer particles around a hollow of the layer, so the contact acts before a centre reaches
  /// the face anywhere on it; 0.8 let centres 0.02-0.08 dx past the floor and the ceiling, 0.87 held them but failed
  /// the hydrostatic column's stillness row (docs/sph.md, "DFSPH at the walls").
  float dfsph_contact_range = 0.9f;
  /// DFSPH: fewest neighbours within the support, fluid and boundary particles, for a particle to take part in the
  /// divergence-free solve (and its warm start) (unit: 1). A spray particle whose only neighbours are boundary
  /// particles at the edge of its support has a gradient sum near 0, so a factor alpha ~3e9 times the bulk's and
  /// a huge kappa^v, which the warm start applied to the next step's steeper gradient: it was thrown across the slab at
  /// a speed that grew until the step went non-finite (docs/sph.md, "DFSPH at the walls"). 20: SPlisHSPlasH's rule for
  /// the same support (4 particle radii) ("in case of particle deficiency do not perform a divergence solve").
  int dfsph_min_neighbours = 20;
  /// Initial particle spacing, the lattice constant of the fluid blocks (unit: m).
  float spacing_m = 0.01f;
  /// Support radius h as a multiple of the spacing (unit: 1). 2.0 keeps the poly6 lattice sum within 1 %.
  float support_factor = 2.0f;
  /// Rest density rho0 (unit: kg/m^3).
  float rest_density_kgpm3 = 1000.f;
  /// Physical kinematic viscosity (unit: m^2/s).
  float viscosity_m2s = 1e-6f;
  /// Artificial viscosity eps: adds eps c0 h to the kinematic viscosity (unit: 1).
  float artificial_viscosity = 0.01f;
  /// Smallest artificial viscosity a scene may ask for (measured stability limit, docs/sph.md) (unit: 1).
  static constexpr float min_artificial_viscosity = 0.007f;
  /// Alpha (linear term) of the impact viscosity Pi_ij of Monaghan 1992 eq. 4.1 (unit: 1).
  float impact_alpha = 0.f;
  /// Beta (quadratic term) of the impact viscosity Pi_ij; 0 with alpha 0 = off (unit: 1).
  float impact_beta = 4.f;
  /// Alpha of the impact viscosity between fluid and boundary particles, on the velocity normal to
  /// the wall only (free slip): stops zero-pressure fluid drifting into a wall (unit: 1).
  float wall_alpha = 0.1f;
  /// Contact range r_c of the contact density, as a multiple of the spacing (unit: 1; 0 = off): a
  /// boundary particle nearer than r_c to a fluid particle compresses it in the pressure of their
  /// pair, by the excess of its kernel value over the one at r_c, on top of rho0 (forces.cpp,
  /// SphSystem::compute_density). 0.87: above sqrt(3)/2 = 0.866, the distance from a wall face to the
  /// four first-layer particles around a hollow of the layer, so it acts before a centre reaches the face
  /// anywhere on it (at 0.8 a particle at rest density sank into a hollow, 0.02 dx below the floor face
  /// after 1 s, docs/sph.md "DFSPH at the walls"); above the 0.71 dx from a 90-degree edge to its corner
  /// particle ("Convex edges"); at 0.9 the settled hydrostatic column (closest approach 0.84 dx) moved.
  float wall_contact_range = 0.87f;
  /// Speed of sound c0 of the Tait equation; 0 = automatic, 10 sqrt(2 g H) with H the fluid height (unit: m/s).
  float sound_speed_mps = 0.f;
  /// Tait exponent gamma (unit: 1).
  float tait_gamma = 7.f;
  /// Gravity vector at start (unit: m/s^2).
  std::array<float, 3> gravity_mps2{0.f, 0.f, -9.81f};
  /// Container size Lx, Ly, Lz; the container is [0, Lx] x [0, Ly] x [0, Lz], closed on all sides (unit: m).
  std::array<float, 3> container_m{0.2f, 0.2f, 0.2f};
  /// CFL number on the support radius (unit: 1).
  float cfl = 0.15f;
  /// Force condition factor (unit: 1).
  float force_factor = 0.18f;
  /// Viscous condition factor (unit: 1).
  float viscous_factor = 0.03f;
  /// Largest time step allowed (unit: s).
  float dt_max_s = 1e-3f;
  /// Scale the spiky pressure gradient by the particle's l_i = 3 / tr(sum_j V grad W (x)(x_j - x_i)), so the
  /// pressure of a linear field is transmitted exactly for any particle arrangement (unit: on/off).
  bool gradient_correction = true;
  /// Velocity damping rate for settling runs, v *= 1 / (1 + damping dt); 0 = physical (unit: 1/s).
  float damping_ps = 0.f;
  /// Fluid blocks placed at start.
  std::vector<SphFluidBlock> fluid;
  /// Static obstacles.
  std::vector<SphObstacle> obstacles;

  /// Support radius h = support_factor spacing (unit: m).
  float support() const { return support_factor * spacing_m; }
};

}  // namespace huygens
