#pragma once
// Time step and integration of the SPH particles (docs/sph.md "Time step"). The step adapts
// every step, on the support radius h (m), sound speed c0 (m/s), kinematic viscosity nu (m^2/s):
//   dt = min(cfl h / (c0 + v_max), force sqrt(h / a_max), viscous h^2 / nu, dt_max)
// (the acoustic CFL, force and viscous conditions; the factors in SphParams). Symplectic Euler
// v += a dt, x += v dt, with v *= 1 / (1 + damping dt) for settling runs. No position clamp: the
// boundary particles (boundary.hpp) keep the fluid inside by their pressure.
#include <cstddef>
#include <cstdint>

#include "huygens/sph/params.hpp"

namespace huygens {

/// Summary of the adaptive time step.
struct SphDtStats {
  /// Last, smallest, largest and summed dt (unit: s).
  double last = 0, min = 0, max = 0, sum = 0;
  std::int64_t count = 0;
  /// Which condition limited the last step: "cfl", "force", "viscous" or "dt_max".
  const char* limiter = "dt_max";
};

/// The particle arrays one integration step changes (positions m, velocities m/s) and reads
/// (accelerations m/s^2), n particles.
struct SphMotion {
  float *x, *y, *z, *vx, *vy, *vz;
  const float *ax, *ay, *az;
  std::size_t n;
};

/// The adaptive dt (unit: s) for support h (m), sound speed c0 (m/s), total viscosity nu (m^2/s),
/// largest speed vmax (m/s) and acceleration amax (m/s^2); `limiter` names the condition that set it.
double sph_choose_dt(const SphParams& p, float h, float c0, float nu, float vmax, float amax, const char*& limiter);

/// One symplectic Euler step of dt (s) with velocity damping `damping_ps` (1/s).
void sph_integrate(float damping_ps, float dt, const SphMotion& m);

}  // namespace huygens
