// Adaptive time step and symplectic Euler: see huygens/sph/integration.hpp.
#include "huygens/sph/integration.hpp"

#include <algorithm>
#include <cmath>

#include "huygens/sph/grid.hpp"

namespace huygens {

double sph_choose_dt(const SphParams& p, float h_f, float c0, float nu, float vmax, float amax, const char*& limiter) {
  const double h = h_f;
  double dt = p.dt_max_s;
  const char* lim = "dt_max";
  const double dcfl = p.cfl * h / (c0 + vmax);
  if (dcfl < dt) {
    dt = dcfl;
    lim = "cfl";
  }
  if (amax > 0.f) {
    const double df = p.force_factor * std::sqrt(h / amax);
    if (df < dt) {
      dt = df;
      lim = "force";
    }
  }
  if (nu > 0.f) {
    const double dv = p.viscous_factor * h * h / nu;
    if (dv < dt) {
      dt = dv;
      lim = "viscous";
    }
  }
  limiter = lim;
  return dt;
}

void sph_integrate(float damping_ps, float dt, const SphMotion& m) {
  const std::size_t n = m.n;
  const float damp = 1.f / (1.f + damping_ps * dt);
  float* X = m.x;
  float* Y = m.y;
  float* Z = m.z;
  float* VX = m.vx;
  float* VY = m.vy;
  float* VZ = m.vz;
  const float* AX = m.ax;
  const float* AY = m.ay;
  const float* AZ = m.az;
  // symplectic Euler
#pragma omp parallel for simd schedule(static) if (n > kSphParallelLight)
  for (std::size_t i = 0; i < n; ++i) {
    VX[i] = (VX[i] + AX[i] * dt) * damp;
    VY[i] = (VY[i] + AY[i] * dt) * damp;
    VZ[i] = (VZ[i] + AZ[i] * dt) * damp;
    X[i] += VX[i] * dt;
    Y[i] += VY[i] * dt;
    Z[i] += VZ[i] * dt;
  }
}

}  // namespace huygens
