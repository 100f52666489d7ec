#pragma once
// 3D smoothed particle hydrodynamics for paper 000 (section 3: "a speed-optimized 3D SPH
// algorithm comparable to [MCG03]"), after Mueller, Charypar and Gross 2003 (MCG03).
//
// Kernels (h = support radius, r = |x_i - x_j|, all zero for r >= h), MCG03 eq. 20-22:
//   poly6      W(r)       = 315 / (64 pi h^9) (h^2 - r^2)^3           density
//   spiky      grad W(r)  = -45 / (pi h^6) (h - r)^2 (x_i - x_j) / r  pressure force
//   viscosity  lap W(r)   =  45 / (pi h^6) (h - r)                    viscous force
// Density  rho_i = sum_j m W_poly6(r_ij) over neighbours and their wall images (MCG03 eq. 3)
// Pressure (weakly compressible, Tait): p_i = max(0, B ((rho_i/rho0)^7 - 1)), B = rho0 c0^2 / 7.
//   Why Tait rather than predictive-corrective: it is explicit (one density and one force
//   pass per step, no iteration, no global convergence test), so a step is two flat
//   neighbour loops that parallelise and vectorise without synchronisation, and the density
//   error is set a priori by the Mach number: |rho/rho0 - 1| ~ (v/c0)^2, i.e. about 1 % for
//   the default c0 = 10 sqrt(2 g H). The price is a step about 10x shorter than PCISPH's
//   (CFL on c0), which the per-step speed buys back at the paper's 3000-particle scale.
// Forces (symmetric pressure of Monaghan's SPH, MCG03 eq. 10 and 14 with mu = nu rho0):
//   a_i = g - sum_j m (l_i p_i/rho_i^2 + l_j p_j/rho_j^2) grad W_spiky
//           + (nu rho0 / rho_i) sum_j m (v_j - v_i) / rho_j lap W_visc
//           - sum_j m Pi_ij grad W_spiky                (impact viscosity, below)
//   with nu = nu_physical + eps c0 h. The artificial part eps c0 h is needed: poly6 density with
//   a spiky pressure gradient is not energy-consistent and pumps energy at too low a viscosity
//   (measured with the ghost-lattice walls of the first version: growth at eps = 0.002, decay at
//   0.007); default eps = 0.01, scenes may not go below 0.007.
// Impact viscosity (Monaghan 1992, Annu. Rev. Astron. Astrophys. 30, eq. 4.1-4.2, with rho_ij = rho0):
//   Pi_ij = (alpha c0 mu_ij + beta mu_ij^2) / rho0,  mu_ij = h max(0, -v_ij . x_ij) / (r^2 + 0.01 h^2),
//   v_ij = v_i - v_j, x_ij = x_i - x_j: only approaching pairs (and wall images). Defaults alpha = 0,
//   beta = 4: the quadratic term acts where pairs close fast (a wall impact) and vanishes in slow
//   motion (settling) and in the shear of a surge. Why: without it the tip of a dam-break surge
//   (density below rho0, so p = 0, lying on the floor) is thrown up the end wall at twice its speed
//   when its wall images compress it (2.38 sqrt(2 g H) in sph_dam_break.json, against issue 7's
//   bound of 1.5). Measured (docs/sph.md): beta = 4 gives 1.42 and 4.7 % compression instead of
//   9.3 %, the surge front moves by < 0.4 %, the hydrostatic column stays still; the linear term
//   (alpha = 0.1 for 1.47) also slows the surge (wall impact 2.6 % later) and the column's settling.
// Gradient correction l_i = 3 / tr(M_i), M_i = sum_j (m/rho0) (-W'_spiky(r)) r_ij r_ij^T / r (the
//   first-moment tensor of the spiky gradient over the particle's actual neighbours and wall
//   images; Bonet and Lok 1999 in scalar form, kept symmetric in i, j so momentum is conserved).
//   Why: the pressure a plane transmits is p times the moment of the neighbours across it. On the
//   rest lattice M = 0.947 (h = 2 dx), and in the disordered arrangement a settled column takes it
//   is ~0.92 (0.77 deep in a 16 x 16 column): without l, the pressure read from the density over-
//   states rho g z by 1/M (measured +22 % bottom pressure, +22 % gradient in the 6 x 6 x 16
//   column, +30 % in a 16 x 16 one). With l the transmitted pressure equals p for any arrangement.
//   The moment sum is accumulated by the force pass (which has r) and used by the next step's
//   density pass (positions one step older); refresh() and the reference paths compute it fresh.
// Walls: mirror images (see sph.cpp, SphSystem::container_images). For each container plane within
//   h of particle i, every neighbour j has an image reflected across the plane (and across pairs
//   and the triple of planes of different axes at edges and corners) with j's density, the
//   mirrored velocity (free slip) and j's pressure plus the hydrostatic difference rho_j g . (x_j'
//   - x_j) (the wall pressure of Adami, Hu and Adams 2012, eq. 27, for a wall at rest). The images
//   complete the density (a rest lattice has rho0 at walls, edges and corners) and exist only where
//   fluid is: the first version's frozen ghost lattice (tabulated, infinite along the wall) also
//   stood above the free surface and beyond a surge front, and with p_ghost = p_i and the poly6
//   gradient it carried neither the hydrostatic increase nor the spiky kernel of the fluid: the
//   column never came to rest (max speed 0.62 sqrt(g H) over 10 s, 0.1 already at the start).
//   Obstacles (box, vertical cylinder) keep the one-plane ghost tables with their signed distance:
//   density D1(d) and force 2 (p_i/rho_i^2) |grad D1| along the normal.
//   A final position clamp at 0.1 spacing from every wall and obstacle (normal velocity into the
//   wall removed) guarantees that no particle leaves the container.
// Time step (adaptive, every step; conditions on the support radius h):
//   dt = min(cfl h / (c0 + v_max), force sqrt(h / a_max), viscous h^2 / nu, dt_max)
// Integration: symplectic Euler, v += a dt, x += v dt.
// Neighbour search: see sph_grid.hpp (uniform grid, cell = h, counting sort every step).
// 1/r in the neighbour loops: bit-level guess and two Newton steps (relative error < 5e-6), no
// square root or division in the vector loops.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "huygens/common/fft.hpp"
#include "huygens/sph/grid.hpp"
#include "huygens/common/stats.hpp"

namespace huygens {

/// A box of fluid particles placed on a lattice of the particle spacing (cell centres).
struct SphFluidBlock {
  /// Lower corner (unit: m).
  std::array<float, 3> min{0.f, 0.f, 0.f};
  /// Upper corner (unit: m).
  std::array<float, 3> max{0.1f, 0.1f, 0.1f};
};

/// A static rigid obstacle: an axis-aligned box, or a vertical cylinder standing on z0.
struct SphObstacle {
  enum class Type { box, cylinder };
  Type type = Type::box;
  /// Box lower corner (unit: m).
  std::array<float, 3> min{0.f, 0.f, 0.f};
  /// Box upper corner (unit: m).
  std::array<float, 3> max{0.f, 0.f, 0.f};
  /// Cylinder axis position x, y (unit: m).
  std::array<float, 2> centre{0.f, 0.f};
  /// Cylinder radius (unit: m).
  float radius = 0.f;
  /// Cylinder bottom and top heights (unit: m).
  float z0 = 0.f, z1 = 0.f;
  /// Signed distance (unit: m; negative inside) and outward unit normal at p.
  float distance(float px, float py, float pz, float n[3]) const;
};

struct SphParams {
  /// Initial particle spacing, the lattice constant of the fluid blocks (unit: m).
  float spacing = 0.01f;
  /// Support radius h as a multiple of the spacing (unit: 1). 2.0 keeps the poly6 lattice sum within 1 %.
  float support_factor = 2.0f;
  /// Rest density rho0 (unit: kg/m^3).
  float rest_density = 1000.f;
  /// Physical kinematic viscosity (unit: m^2/s).
  float viscosity = 1e-6f;
  /// Artificial viscosity eps: adds eps c0 h to the kinematic viscosity (unit: 1).
  float artificial_viscosity = 0.01f;
  /// Smallest artificial viscosity a scene may ask for (measured stability limit, see above) (unit: 1).
  static constexpr float min_artificial_viscosity = 0.007f;
  /// Monaghan's alpha (linear term) of the approaching-pairs impact viscosity Pi_ij (see above) (unit: 1).
  float impact_alpha = 0.f;
  /// Monaghan's beta (quadratic term) of the impact viscosity Pi_ij; 0 with alpha 0 = off (unit: 1).
  float impact_beta = 4.f;
  /// Speed of sound c0 of the Tait equation; 0 = automatic, 10 sqrt(2 g H) with H the fluid height (unit: m/s).
  float sound_speed = 0.f;
  /// Tait exponent gamma (unit: 1).
  float tait_gamma = 7.f;
  /// Gravity vector at start (unit: m/s^2).
  std::array<float, 3> gravity{0.f, 0.f, -9.81f};
  /// Container size Lx, Ly, Lz; the container is [0, Lx] x [0, Ly] x [0, Lz], closed on all sides (unit: m).
  std::array<float, 3> container{0.2f, 0.2f, 0.2f};
  /// CFL number on the support radius (unit: 1).
  float cfl = 0.15f;
  /// Force condition factor (unit: 1).
  float force_factor = 0.18f;
  /// Viscous condition factor (unit: 1).
  float viscous_factor = 0.03f;
  /// Largest time step allowed (unit: s).
  float dt_max = 1e-3f;
  /// Scale the spiky pressure gradient by the particle's l_i = 3 / tr(sum_j V grad W (x)(x_j - x_i)), so the
  /// pressure of a linear field is transmitted exactly for any particle arrangement (unit: on/off).
  bool gradient_correction = true;
  /// Velocity damping rate for settling runs, v *= 1 / (1 + damping dt) (unit: 1/s); 0 = physical.
  float damping = 0.f;
  /// Fluid blocks placed at start.
  std::vector<SphFluidBlock> fluid;
  /// Static obstacles.
  std::vector<SphObstacle> obstacles;

  float support() const { return support_factor * spacing; }
};

/// The MCG03 kernels (h = support radius). Inline so tests and the brute-force reference use the same code.
struct SphKernels {
  float h, h2;
  float poly6_k;  ///< 315 / (64 pi h^9)
  float spiky_k;  ///< 45 / (pi h^6), magnitude of the spiky gradient and viscosity Laplacian factor
  explicit SphKernels(float support);
  float poly6(float r2) const {
    const float q = h2 - r2;
    return q > 0.f ? poly6_k * q * q * q : 0.f;
  }
  /// Spiky kernel value 15 / (pi h^6) (h - r)^3.
  float spiky(float r) const { return r < h ? spiky_k / 3.f * (h - r) * (h - r) * (h - r) : 0.f; }
  /// dW_spiky/dr = -45 / (pi h^6) (h - r)^2.
  float spiky_dr(float r) const { return r < h ? -spiky_k * (h - r) * (h - r) : 0.f; }
  /// Viscosity kernel value 15 / (2 pi h^3) (-r^3/(2h^3) + r^2/h^2 + h/(2r) - 1).
  float viscosity(float r) const;
  /// Laplacian of the viscosity kernel 45 / (pi h^6) (h - r).
  float viscosity_lap(float r) const { return r < h ? spiky_k * (h - r) : 0.f; }
};

/// A mirror image of the neighbours across container planes (see sph.cpp): d = o + s X_j.
struct SphImage {
  float o[3], s[3];
  /// Hydrostatic pressure of the image: P_j' = P_j + (G0 + gs . X_j) / rho_j.
  float G0, gs[3];
  /// 1 if the image is reflected across the floor z = 0 (its partners lie in the bottom cell layer).
  int floor;
};

/// Summary of the adaptive time step.
struct SphDtStats {
  double last = 0, min = 0, max = 0, sum = 0;
  std::int64_t count = 0;
  /// Which condition limited the last step: "cfl", "force", "viscous" or "dt_max".
  const char* limiter = "dt_max";
};

/// The particle system: immutable parameters, SoA float state, the cell grid, one step.
class SphSystem {
 public:
  /// Places the fluid blocks, sizes every buffer; throws std::invalid_argument on an unusable set-up.
  explicit SphSystem(const SphParams& params, std::size_t dt_history = 4096);

  /// One adaptive step; returns the dt taken (unit: s). Throws NonFiniteError naming the stage.
  double step();

  const SphParams& params() const { return p_; }
  std::size_t count() const { return n_; }
  double time() const { return t_; }
  std::int64_t steps() const { return steps_; }
  float mass() const { return mass_; }
  float support() const { return h_; }
  float sound_speed() const { return c0_; }
  /// Total kinematic viscosity nu_physical + eps c0 h (unit: m^2/s).
  float viscosity() const { return nu_; }
  const SphKernels& kernels() const { return k_; }
  const SphDtStats& dt_stats() const { return dts_; }
  /// The last dt values, oldest first (at most the history length given at construction).
  std::vector<double> dt_history() const;
  const StageStats& stats() const { return stats_; }
  StageStats& stats() { return stats_; }

  // State, in the current (cell-sorted) order. Valid until the next step.
  std::span<const float> x() const { return {x_.data(), n_}; }
  std::span<const float> y() const { return {y_.data(), n_}; }
  std::span<const float> z() const { return {z_.data(), n_}; }
  std::span<const float> vx() const { return {vx_.data(), n_}; }
  std::span<const float> vy() const { return {vy_.data(), n_}; }
  std::span<const float> vz() const { return {vz_.data(), n_}; }
  std::span<const float> density() const { return {rho_.data(), n_}; }
  std::span<const float> pressure() const { return {p_arr_.data(), n_}; }
  /// Per-particle gradient correction l_i = 3 / tr(M_i) of the spiky gradient (unit: 1).
  std::span<const float> gradient_correction() const { return {corr_.data(), n_}; }
  std::span<const std::uint32_t> ids() const { return {id_.data(), n_}; }
  const SphGrid& grid() const { return grid_; }

  /// Positions in particle-id order, interleaved (x, y, z) per particle (count x 3).
  void positions_by_id(std::span<float> out) const;
  /// Largest particle speed (unit: m/s).
  float max_speed() const;

  // Interaction (UI commands of the pipeline); call between steps.
  /// Sets the gravity vector; tilting or shaking the container is a time-varying gravity (unit: m/s^2).
  void set_gravity(const std::array<float, 3>& g) { g_ = g; }
  const std::array<float, 3>& gravity() const { return g_; }
  /// A drop: particles within `radius` (unit: m) of (x, y, top of the fluid there) get a downward
  /// velocity speed * (1 - r^2/radius^2) (unit: m/s) added.
  void add_velocity_splash(float x, float y, float radius, float speed);
  /// Velocity damping rate for settling (unit: 1/s; 0 = off).
  void set_damping(float rate) { damping_ = rate; }

  /// Replaces the particle set (tests, validation): positions and velocities, in any order.
  void set_particles(std::span<const float> px, std::span<const float> py, std::span<const float> pz);

  /// Sets the velocities of the current particle order (tests, validation) (unit: m/s).
  void set_velocities(std::span<const float> vx, std::span<const float> vy, std::span<const float> vz);

  /// Rebuilds the grid and densities for the current positions without moving anything
  /// (so density(), pressure() and grid() describe the current state).
  void refresh();

  /// Runs neighbour search, density and forces with an O(n^2) all-pairs loop instead of the
  /// grid, writing accelerations to (ax, ay, az) in the current order (benchmark reference).
  void brute_force_accelerations(std::span<float> ax, std::span<float> ay, std::span<float> az, std::span<float> rho);
  /// The grid path's accelerations and densities for the current positions, same layout.
  void grid_accelerations(std::span<float> ax, std::span<float> ay, std::span<float> az, std::span<float> rho);

  /// Indices of the four step stages in stats().
  struct StageIds {
    int neighbours, density, forces, integration;
  };
  const StageIds& stage_ids() const { return sid_; }

 private:
  void sort_particles();
  /// fresh_moment: compute the gradient correction in this pass (else use the last force pass's).
  void compute_density(bool fresh_moment);
  void compute_forces();
  int container_images(float x, float y, float z, SphImage* out) const;
  int gather_cell(int cx, int cy, int cz, const float* const* src, int arrays, float* const* dst,
                  std::uint32_t& floor_end) const;
  float pressure_of(float rho) const;
  /// Gradient correction l = 1 / M from the spiky first-moment sum msum = sum (h - r)^2 r.
  float gradient_correction(float msum) const {
    if (mvol_ == 0.f) return 1.f;
    const float M = mvol_ * msum;
    return M > kCorrMin ? 1.f / M : 1.f / kCorrMin;
  }
  static constexpr float kCorrMin = 0.5f;
  void boundary_density(std::size_t i, float& rho) const;
  void boundary_force(std::size_t i, float P, float& ax, float& ay, float& az) const;
  void integrate(float dt);
  void allocate(std::size_t n);
  double choose_dt();

  SphParams p_;
  SphKernels k_;
  float h_, mass_, c0_, B_, nu_;
  float mvol_ = 0;  // (m / rho0) 45 / (pi h^6) / 3: tr(M) / 3 per unit moment sum
  // impact viscosity Pi_ij = (pik_ + pbk_ mu) mu, mu = max(0, -v_ij . x_ij) / (r^2 + h^2/100):
  // pik_ = alpha c0 h / rho0, pbk_ = beta h^2 / rho0
  float pik_ = 0, pbk_ = 0;
  std::array<float, 3> g_;
  float damping_;
  std::size_t n_ = 0;
  double t_ = 0;
  std::int64_t steps_ = 0;
  SphGrid grid_;
  // SoA state (64-byte aligned) and sort buffers.
  AlignedBuffer<float> x_, y_, z_, vx_, vy_, vz_, ax_, ay_, az_, rho_, P_, irho_, lirho_, corr_, p_arr_;
  AlignedBuffer<float> tx_, ty_, tz_, tvx_, tvy_, tvz_, tcorr_;
  std::vector<std::uint32_t> id_, tid_;
  // per-thread gathered neighbour candidates of one cell (SoA, kScratchArrays arrays per thread)
  static constexpr int kScratchArrays = 9;
  AlignedBuffer<float> scratch_;
  std::size_t scratch_cap_ = 0;
  int scratch_threads_ = 0;
  // Ghost-lattice wall tables (see the header comment): density D and force F for 1, 2, 3 planes.
  struct WallTables {
    int n1 = 0;
    float inv1 = 0;
    std::vector<float> d1, f1;
  } wt_;
  void build_wall_tables();
  float vmax_ = 0, amax_ = 0;
  SphDtStats dts_;
  std::vector<double> dt_hist_;
  std::size_t dt_head_ = 0;
  StageStats stats_;
  StageIds sid_{};
};

}  // namespace huygens
