#pragma once
// 3D smoothed particle hydrodynamics of paper 000 section 3, after Mueller, Charypar and Gross
// 2003 (MCG03): a weakly compressible fluid in a closed box, stepped on the CPU.
//   density   rho_i = sum_j m_j W_poly6(r_ij) over fluid and boundary neighbours  (MCG03 eq. 3)
//   pressure  p_i = max(0, B ((rho_i/rho0)^gamma - 1)), B = rho0 c0^2 / gamma      (Tait)
//   force     a_i = g - sum_j m (l_i p_i/rho_i^2 + l_j p_j/rho_j^2 + Pi_ij) grad W_spiky
//                   + (nu rho0 / rho_i) sum_j m (v_j - v_i) / rho_j lap W_visc     (MCG03 eq. 10, 14)
// with nu = nu_physical + eps c0 h, Pi_ij the impact viscosity of Monaghan 1992 eq. 4.1 and
// l_i = 3 / tr(M_i) the gradient correction of Bonet and Lok 1999 (M_i: the spiky gradient's first
// moment, summed by the force pass and used by the next step's density pass). Boundary particles
// (boundary.hpp) are neighbours at rest with the pressure extrapolated from the fluid (Adami, Hu and
// Adams 2012 eq. 27-28), recomputed between the density and force passes. Units: SI (m, s, kg).
// Kernels: kernels.hpp; walls and obstacles: boundary.hpp; pair sums: forces.hpp; neighbour grid:
// grid.hpp; time step: integration.hpp. With SphParams::method = dfsph the pressure comes from the
// divergence-free SPH solver instead (dfsph.hpp: cubic spline kernel, hydrostatic wall pressure). Why each choice, and
// the measurements: docs/sph.md.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "huygens/common/fft.hpp"
#include "huygens/common/stats.hpp"
#include "huygens/sph/boundary.hpp"
#include "huygens/sph/grid.hpp"
#include "huygens/sph/integration.hpp"
#include "huygens/sph/kernels.hpp"
#include "huygens/sph/params.hpp"

namespace huygens {

/// The particle system: immutable parameters, SoA float state, the cell grid, one step.
class SphSystem {
 public:
  /// Places the fluid blocks, sizes every buffer; throws std::invalid_argument on an unusable set-up.
  explicit SphSystem(const SphParams& params, std::size_t dt_history = 4096);

  /// One adaptive step; returns the dt taken (unit: s). Throws NonFiniteError naming the stage.
  double step();

  const SphParams& params() const { return p_; }
  std::size_t count() const { return n_; }
  /// Simulated time (unit: s).
  double time() const { return t_; }
  std::int64_t steps() const { return steps_; }
  /// Particle mass (unit: kg).
  float mass() const { return mass_; }
  /// Support radius h (unit: m).
  float support() const { return h_; }
  /// Speed of sound c0 (unit: m/s).
  float sound_speed() const { return c0_; }
  /// Total kinematic viscosity nu_physical + eps c0 h (unit: m^2/s).
  float viscosity() const { return nu_; }
  const SphKernels& kernels() const { return k_; }
  const SphDtStats& dt_stats() const { return dts_; }
  /// The last dt values, oldest first (at most the history length given at construction) (unit: s).
  std::vector<double> dt_history() const;
  const StageStats& stats() const { return stats_; }
  StageStats& stats() { return stats_; }
  /// DFSPH: Jacobi iterations of the last step's divergence-free and constant-density solves, and
  /// their totals over all steps (unit: 1; 0 with WCSPH).
  int dfsph_divergence_iterations() const { return div_iter_; }
  int dfsph_density_iterations() const { return dens_iter_; }
  /// DFSPH: particles that the wall contact (SphParams::dfsph_contact_range) pushed at the end of the last step's
  /// constant-density solve, and the sum of these counts over all steps (unit: 1; 0 with WCSPH).
  std::size_t dfsph_contacts() const { return contacts_; }
  std::int64_t dfsph_total_contacts() const { return total_contacts_; }
  std::int64_t dfsph_total_iterations() const { return total_iter_; }

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
  /// Boundary particles (walls and obstacles), in the grid's static order: positions (m), mass ratio
  /// m_b / m (1), extrapolated pressure p_b of the last density pass (Pa).
  std::size_t boundary_count() const { return nb_; }
  std::span<const float> boundary_x() const { return {bx_.data(), nb_}; }
  std::span<const float> boundary_y() const { return {by_.data(), nb_}; }
  std::span<const float> boundary_z() const { return {bz_.data(), nb_}; }
  std::span<const float> boundary_mass_ratio() const { return {bw_.data(), nb_}; }
  std::span<const float> boundary_pressure() const { return {bp_.data(), nb_}; }

  /// Positions in particle-id order, interleaved (x, y, z) per particle (count x 3) (unit: m).
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

  /// Indices of the step's stages (passes) in stats(); the stages are disjoint, their times add up to the step's.
  /// neighbours: the cell sort; density: the density pass (DFSPH: with the step's neighbour list and factors);
  /// boundary: WCSPH the boundary particles' pressure, DFSPH the wall contact of the constant-density solve;
  /// forces: WCSPH all forces, DFSPH the non-pressure ones (gravity, viscosity, the walls' hydrostatic push) and
  /// the velocity update; divergence_solve, density_solve: DFSPH's two Jacobi solves (-1 with WCSPH);
  /// integration: dt (WCSPH) and the positions.
  struct StageIds {
    int neighbours = -1, density = -1, forces = -1, integration = -1, boundary = -1;
    int divergence_solve = -1, density_solve = -1;
  };
  const StageIds& stage_ids() const { return sid_; }

 private:
  friend struct SphSystemProbe;  // tests/sph/sph_dfsph_test.cpp: one DFSPH solve on its own
  void place_fluid(std::vector<float>& px, std::vector<float>& py, std::vector<float>& pz, float& top) const;
  void sort_particles();
  /// fresh_moment: compute the gradient correction in this pass (else use the last force pass's).
  void compute_density(bool fresh_moment);
  void compute_forces();
  /// The boundary particles' pressure from the fluid around them (Adami et al. 2012 eq. 27-28).
  void compute_boundary_pressure();
  /// p_b, and l_b p_b / rho_b^2 into bP_[b], from the sums s of sph_wall_range (forces.hpp).
  void set_boundary_pressure(std::size_t b, const float s[6]);
  /// Samples the container walls and the obstacles and sorts them into the grid's static table.
  void place_boundary();
  float pressure_of(float rho) const;
  /// Square of the contact range r_c = wall_contact_range dx of the contact density (unit: m^2).
  float contact_r2() const { return p_.wall_contact_range * p_.wall_contact_range * p_.spacing_m * p_.spacing_m; }
  /// Gradient correction l = 1 / M from the first-moment sum msum = sum (h - r)^2 r (spiky; DFSPH: sum f r^2).
  float gradient_correction(float msum) const {
    if (mvol_ == 0.f) return 1.f;
    const float M = mvol_ * msum;
    return M > kCorrMin ? 1.f / M : 1.f / kCorrMin;
  }
  static constexpr float kCorrMin = 0.5f;
  void allocate(std::size_t n);
  /// Adds dt to the time and the dt statistics.
  void record_dt(double dt);

  // DFSPH (dfsph.hpp, dfsph.cpp)
  /// The DFSPH step: factors, divergence-free solve, advection, constant-density solve, positions.
  double step_dfsph();
  /// rho_i, alpha_i, l_i, the boundary gradient sum gb_i and the walls' hydrostatic push (into ax_, ay_, az_)
  /// at the current positions, and the neighbour list of the step (grown first if it does not fit).
  void dfsph_factors();
  /// One factor pass; false (and nothing usable) when the neighbour list overflowed its capacity.
  bool dfsph_factors_pass();
  /// Stores the factors of particle i from its fluid sums f (sph_dfsph_list_factors) and boundary sums fb
  /// (sph_dfsph_boundary_range, its contact taken at the expected displacement d, m), `near` coincident particles
  /// and nf fluid neighbours.
  void dfsph_store_factors(std::size_t i, const float f[6], const float fb[13], std::uint32_t near, std::uint32_t nf,
                           const float d[3]);
  /// v_i += dt m 48/(pi h^5) (sum_j (K_i + K_j) f x_ij + c K_i gb_i), K = kick_, c = 2 (1 with akinci walls).
  void dfsph_kick(float dt);
  /// The wall contact's Gauss-Seidel step after a kick of the constant-density solve; returns the particles it pushes.
  std::size_t dfsph_contact(float dt);
  /// One Jacobi update of kappa (density: true) or kappa^v from the predicted density or the
  /// divergence of the current velocities, with the Chebyshev weight wc over the previous iterate (in
  /// tkappa_); K = the change / rho into kick_; returns the mean error.
  double dfsph_update(float dt, bool density, float wc = 1.f);
  /// Warm start, then Jacobi iterations until the mean error is below the tolerance; returns them. Timed as the
  /// divergence_solve or density_solve stage (the wall contact's share as the boundary stage).
  int dfsph_solve(float dt, bool density);
  /// dfsph_solve's work, untimed.
  int dfsph_iterate(float dt, bool density);
  /// a = g + the walls' hydrostatic push + the viscous acceleration into ax_, ay_, az_; max |a| and |v|.
  void dfsph_advection_forces();
  /// p_i = rho_i (kappa_i + kappa^v_i) / l_i into p_arr_.
  void dfsph_pressure();

  SphParams p_;
  SphKernels k_;
  float h_, mass_, c0_, B_, nu_;
  float mvol_ = 0;  // (m / rho0) 45 / (pi h^6) / 3 (DFSPH: 48 / (pi h^5) / 3): tr(M) / 3 per unit moment sum
  // impact viscosity Pi_ij = (pik_ + pbk_ mu) mu, mu = max(0, -v_ij . x_ij) / (r^2 + h^2/100):
  // pik_ = alpha c0 h / rho0, pbk_ = beta h^2 / rho0
  float pik_ = 0, pbk_ = 0;
  float pikw_ = 0;  // wall_alpha c0 h / rho0: the linear term between fluid and boundary particles
  std::array<float, 3> g_;
  float damping_;
  std::size_t n_ = 0;
  double t_ = 0;
  std::int64_t steps_ = 0;
  SphGrid grid_;
  SphCellGather gather_;
  SphBoundarySample bsample_;  // the boundary particles as sampled (any order)
  std::size_t nb_ = 0;
  // boundary particles, grid static order: positions, mass ratio, l p / rho^2, pressure, normal
  AlignedBuffer<float> bx_, by_, bz_, bw_, bP_, bp_, bnx_, bny_, bnz_;
  // SoA state (64-byte aligned) and sort buffers.
  // Pc_: l p / rho^2 at the contact density, the P_i of the pairs with boundary particles (forces.cpp)
  AlignedBuffer<float> x_, y_, z_, vx_, vy_, vz_, ax_, ay_, az_, rho_, P_, Pc_, irho_, lirho_, corr_, p_arr_;
  AlignedBuffer<float> tx_, ty_, tz_, tvx_, tvy_, tvz_, tcorr_;
  std::vector<std::uint32_t> id_, tid_;
  // DFSPH per particle (sized by allocate() with method dfsph): alpha, kappa, kappa^v (warm start,
  // sorted with the particle), K = change of kappa / rho of the last update, the boundary gradient
  // sum gb, the error of the last update, the sort buffers of kappa and kappa^v; 1 where the particle
  // takes part in the divergence-free solve, else 0 (SphParams::dfsph_min_neighbours); the wall contact of the
  // step (dfsph.hpp, "Walls"): the predicted excess at v = 0 (cex_, kg/m^3), its change per dt v (cgx_, cgy_,
  // cgz_, kg/m^4, E* = cex - dt cg . v), its change per contact multiplier / dt^2 (ccd_, 0: no contact), and the
  // multiplier Kc (kc_)
  AlignedBuffer<float> alpha_, kappa_, kappav_, kick_, gbx_, gby_, gbz_, err_, tkappa_, tkappav_, dvok_;
  AlignedBuffer<float> cex_, cgx_, cgy_, cgz_, ccd_, kc_;
  // DFSPH neighbour list (dfsph.hpp SphDfsphList): slots [nbeg_[i], nend_[i]) of nj_ (index) and ngx_, ngy_,
  // ngz_ (f x_ij); capacity nlist_ slots (allocate(): 56 per particle at h = 2 dx; doubled when a step overflows it);
  // nflag_: the candidate flags, per thread
  AlignedBuffer<std::uint32_t> nj_, nbeg_, nend_, nflag_;
  AlignedBuffer<float> ngx_, ngy_, ngz_;
  std::size_t nlist_ = 0;
  void dfsph_list_allocate(std::size_t slots);
  int div_iter_ = 0, dens_iter_ = 0;
  std::int64_t total_iter_ = 0;
  std::size_t contacts_ = 0;
  std::int64_t total_contacts_ = 0;
  double dt_prev_ = 0;
  float vmax_ = 0, amax_ = 0;
  SphDtStats dts_;
  std::vector<double> dt_hist_;
  std::size_t dt_head_ = 0;
  StageStats stats_;
  StageIds sid_{};
};

}  // namespace huygens
