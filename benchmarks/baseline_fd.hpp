#pragma once
// Baseline for the Huygens core: the finite-difference linear wave equation a user would
// otherwise pick (Kass and Miller 1990, "Rapid, stable fluid dynamics for computer graphics",
// SIGGRAPH '90, section 3): the linearised shallow-water equation
//   eta_tt = c^2 lap eta,   c = sqrt(g d)  (a single, non-dispersive speed)
// on a periodic N x N grid with the 5-point Laplacian, lap eta ~ (sum of 4 neighbours - 4 eta) / dx^2.
// Two time integrators (both second differences in time, started from eta(0) and eta_t(0) by the
// Taylor step eta(-dt) = eta0 - dt eta_t0 + dt^2/2 c^2 lap eta0):
//   leapfrog     explicit: eta^{n+1} = 2 eta^n - eta^{n-1} + (c dt/dx)^2 lap_h eta^n. Second order,
//                non-dissipative, stable only for c dt / dx <= 1/sqrt(2) (CFL; refused otherwise).
//   kass_miller  Kass and Miller's implicit scheme (their eq. 13-17 with tau = 0): the Laplacian is
//                taken at the new level, (I - a Dxx)(I - a Dyy) eta^{n+1} = 2 eta^n - eta^{n-1},
//                a = (c dt / dx)^2, solved as one x sweep then one y sweep of (cyclic) tridiagonal
//                systems. Unconditionally stable, first order, numerically damped (what they wanted).
// The scheme is not dispersive: every wavelength moves at c (up to the grid's own numerical
// dispersion). That is exact for shallow water, wrong for deep water and capillary waves.
#include <span>
#include <string>

#include "huygens/common/fft.hpp"

namespace huygens::bench {

enum class FdScheme { leapfrog, kass_miller };

/// Parameters of the finite-difference wave equation (fixed at construction).
struct FdParams {
  /// Cells per side N (unit: cells); >= 4.
  int n = 256;
  /// Side length L of the periodic grid (unit: m).
  double length_m = 8.0;
  /// Time step (unit: s).
  double dt = 1.0 / 60.0;
  /// The single wave speed c (unit: m/s); sqrt(g d) in Kass and Miller.
  double speed_mps = 1.0;
  /// Time integrator.
  FdScheme scheme = FdScheme::leapfrog;
};

/// Why `p` cannot be used (including the leapfrog CFL limit), or empty.
std::string fd_params_error(const FdParams& p);
/// Largest stable leapfrog time step dx / (c sqrt 2) (unit: s).
double fd_leapfrog_max_dt(const FdParams& p);

class FdWave {
 public:
  /// Allocates everything; throws std::invalid_argument with fd_params_error().
  explicit FdWave(const FdParams& p);
  /// Sets eta(0) and eta_t(0) (N*N values each, rows = y; unit: m, m/s).
  void init(std::span<const float> eta0, std::span<const float> etadot0);
  void step();
  /// eta at time() (N*N values, unit: m).
  std::span<const float> eta() const { return cur_.span(); }
  double time() const { return t_; }

 private:
  void laplacian_update(const float* cur, const float* prev, float* out, float a) const;
  void solve_columns(float* d);  // (I - a Dyy) x = d along columns, in place
  void transpose(const float* in, float* out) const;

  FdParams p_;
  double t_ = 0;
  AlignedBuffer<float> prev_, cur_, next_, tmp_;
  // cyclic tridiagonal factors (Sherman-Morrison), Kass-Miller only
  AlignedBuffer<float> cp_, inv_, z_, col_;
  float corr_ = 0, beta_over_gamma_ = 0;
};

}  // namespace huygens::bench
