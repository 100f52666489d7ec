// Adaptive time step and symplectic Euler with the no-leakage clamp: see huygens/sph/integration.hpp.
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

namespace {

// no leakage: clamp into [a, b], remove the normal velocity into a wall
inline void clamp_axis(float& p, float& v, float a, float b) {
  if (p < a) {
    p = a;
    v = std::max(v, 0.f);
  }
  if (p > b) {
    p = b;
    v = std::min(v, 0.f);
  }
}

// pushes a particle out to `eps` from every obstacle it is closer to, removing its velocity into it
inline void push_out(const std::vector<SphObstacle>& obstacles, float eps, float& x, float& y, float& z, float& vx,
                     float& vy, float& vz) {
  float nrm[3];
  for (const auto& o : obstacles) {
    if (!o.near(x, y, z, eps)) continue;
    const float d = o.distance(x, y, z, nrm);
    if (d < eps) {
      x += (eps - d) * nrm[0];
      y += (eps - d) * nrm[1];
      z += (eps - d) * nrm[2];
      const float vn = vx * nrm[0] + vy * nrm[1] + vz * nrm[2];
      if (vn < 0.f) {
        vx -= vn * nrm[0];
        vy -= vn * nrm[1];
        vz -= vn * nrm[2];
      }
    }
  }
}

}  // namespace

void sph_integrate(const SphParams& p, float damping_ps, float dt, const SphMotion& m) {
  const std::size_t n = m.n;
  const float damp = 1.f / (1.f + damping_ps * dt);
  const float eps = 0.1f * p.spacing_m;
  const float lo[3] = {eps, eps, eps};
  const float hi[3] = {p.container_m[0] - eps, p.container_m[1] - eps, p.container_m[2] - eps};
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
  const bool obst = !p.obstacles.empty();
#pragma omp parallel for schedule(static) if (n > (obst ? kSphParallelMin : kSphParallelLight))
  for (std::size_t i = 0; i < n; ++i) {
    clamp_axis(X[i], VX[i], lo[0], hi[0]);
    clamp_axis(Y[i], VY[i], lo[1], hi[1]);
    clamp_axis(Z[i], VZ[i], lo[2], hi[2]);
    if (obst) {
      push_out(p.obstacles, eps, X[i], Y[i], Z[i], VX[i], VY[i], VZ[i]);
      clamp_axis(X[i], VX[i], lo[0], hi[0]);
      clamp_axis(Y[i], VY[i], lo[1], hi[1]);
      clamp_axis(Z[i], VZ[i], lo[2], hi[2]);
    }
  }
}

}  // namespace huygens
