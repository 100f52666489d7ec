#include "baseline_fd.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

namespace huygens::bench {

std::string fd_params_error(const FdParams& p) {
  if (p.n < 4) return "n must be >= 4";
  if (!(p.length_m > 0) || !(p.dt > 0) || !(p.speed_mps > 0)) return "length, dt and speed must be > 0";
  if (p.scheme == FdScheme::leapfrog && p.dt > fd_leapfrog_max_dt(p) * (1 + 1e-12))
    return "leapfrog unstable: c dt / dx > 1/sqrt(2) (CFL)";
  return {};
}

double fd_leapfrog_max_dt(const FdParams& p) { return p.length_m / p.n / (p.speed_mps * std::sqrt(2.0)); }

FdWave::FdWave(const FdParams& p) : p_(p) {
  if (auto e = fd_params_error(p); !e.empty()) throw std::invalid_argument(e);
  const std::size_t nn = static_cast<std::size_t>(p.n) * p.n;
  prev_ = AlignedBuffer<float>(nn);
  cur_ = AlignedBuffer<float>(nn);
  next_ = AlignedBuffer<float>(nn);
  if (p.scheme == FdScheme::kass_miller) {
    tmp_ = AlignedBuffer<float>(nn);
    // (I - a D2) with periodic ends: diagonal b = 1 + 2a, off-diagonals and corners -a.
    // Sherman-Morrison (Numerical Recipes "cyclic"): gamma = -b, A' = A with b0 -> b - gamma and
    // b_{n-1} -> b - alpha beta / gamma; solve A' y = d and A' z = u, u = (gamma, 0.., alpha).
    const int n = p.n;
    const double a = std::pow(p.speed_mps * p.dt / (p.length_m / n), 2);
    const double b = 1 + 2 * a, off = -a, gamma = -b;
    std::vector<double> diag(n, b);
    diag[0] = b - gamma;
    diag[n - 1] = b - off * off / gamma;
    cp_ = AlignedBuffer<float>(n);
    inv_ = AlignedBuffer<float>(n);
    z_ = AlignedBuffer<float>(n);
    col_ = AlignedBuffer<float>(n);
    std::vector<double> cp(n), inv(n), z(n, 0.0);
    inv[0] = 1 / diag[0];
    cp[0] = off * inv[0];
    for (int i = 1; i < n; ++i) {
      inv[i] = 1 / (diag[i] - off * cp[i - 1]);
      cp[i] = off * inv[i];
    }
    z[0] = gamma;
    z[n - 1] = off;
    z[0] *= inv[0];
    for (int i = 1; i < n; ++i) z[i] = (z[i] - off * z[i - 1]) * inv[i];
    for (int i = n - 2; i >= 0; --i) z[i] -= cp[i] * z[i + 1];
    for (int i = 0; i < n; ++i) {
      cp_[i] = static_cast<float>(cp[i]);
      inv_[i] = static_cast<float>(inv[i]);
      z_[i] = static_cast<float>(z[i]);
    }
    beta_over_gamma_ = static_cast<float>(off / gamma);
    corr_ = static_cast<float>(1 / (1 + z[0] + off * z[n - 1] / gamma));
  }
}

// out = 2 cur - prev + a lap_h cur  (a = (c dt/dx)^2); with cur = prev = eta0 and the factors
// of the Taylor start the same loop gives eta(-dt).
void FdWave::laplacian_update(const float* cur, const float* prev, float* out, float a) const {
  const int n = p_.n;
  for (int r = 0; r < n; ++r) {
    const float* c0 = cur + static_cast<std::size_t>(r) * n;
    const float* up = cur + static_cast<std::size_t>((r + n - 1) % n) * n;
    const float* dn = cur + static_cast<std::size_t>((r + 1) % n) * n;
    const float* pv = prev + static_cast<std::size_t>(r) * n;
    float* o = out + static_cast<std::size_t>(r) * n;
#pragma omp simd
    for (int c = 1; c < n - 1; ++c)
      o[c] = 2.0f * c0[c] - pv[c] + a * (c0[c - 1] + c0[c + 1] + up[c] + dn[c] - 4.0f * c0[c]);
    o[0] = 2.0f * c0[0] - pv[0] + a * (c0[n - 1] + c0[1] + up[0] + dn[0] - 4.0f * c0[0]);
    o[n - 1] = 2.0f * c0[n - 1] - pv[n - 1] + a * (c0[n - 2] + c0[0] + up[n - 1] + dn[n - 1] - 4.0f * c0[n - 1]);
  }
}

void FdWave::init(std::span<const float> eta0, std::span<const float> etadot0) {
  const std::size_t nn = cur_.size();
  if (eta0.size() != nn || etadot0.size() != nn) throw std::invalid_argument("FdWave::init: size is not N*N");
  std::memcpy(cur_.data(), eta0.data(), nn * sizeof(float));
  // eta(-dt) = eta0 - dt etadot0 + dt^2/2 c^2 lap eta0: the update with prev = eta0 gives
  // eta0 + a lap eta0; halve the Laplacian part and subtract dt etadot0
  const float a = static_cast<float>(std::pow(p_.speed_mps * p_.dt / (p_.length_m / p_.n), 2));
  laplacian_update(cur_.data(), cur_.data(), prev_.data(), 0.5f * a);
  const float dt = static_cast<float>(p_.dt);
  for (std::size_t i = 0; i < nn; ++i) prev_[i] -= dt * etadot0[i];
  t_ = 0;
}

void FdWave::transpose(const float* in, float* out) const {
  const int n = p_.n, b = 32;
  for (int r0 = 0; r0 < n; r0 += b)
    for (int c0 = 0; c0 < n; c0 += b)
      for (int r = r0; r < std::min(n, r0 + b); ++r)
        for (int c = c0; c < std::min(n, c0 + b); ++c)
          out[static_cast<std::size_t>(c) * n + r] = in[static_cast<std::size_t>(r) * n + c];
}

// Thomas sweeps down the rows, vectorised across the N independent column systems, then the
// Sherman-Morrison correction x -= (y0 + beta/gamma y_{n-1}) / (1 + z0 + beta/gamma z_{n-1}) z.
void FdWave::solve_columns(float* d) {
  const int n = p_.n;
  const float off = -static_cast<float>(std::pow(p_.speed_mps * p_.dt / (p_.length_m / n), 2));
  auto row = [&](int i) { return d + static_cast<std::size_t>(i) * n; };
  {
    float* r0 = row(0);
    const float m0 = inv_[0];
#pragma omp simd
    for (int c = 0; c < n; ++c) r0[c] *= m0;
  }
  for (int i = 1; i < n; ++i) {
    float* ri = row(i);
    const float* rp = row(i - 1);
    const float m = inv_[i];
#pragma omp simd
    for (int c = 0; c < n; ++c) ri[c] = (ri[c] - off * rp[c]) * m;
  }
  for (int i = n - 2; i >= 0; --i) {
    float* ri = row(i);
    const float* rn = row(i + 1);
    const float cp = cp_[i];
#pragma omp simd
    for (int c = 0; c < n; ++c) ri[c] -= cp * rn[c];
  }
  float* first = row(0);
  const float* last = row(n - 1);
  float* f = col_.data();
#pragma omp simd
  for (int c = 0; c < n; ++c) f[c] = (first[c] + beta_over_gamma_ * last[c]) * corr_;
  for (int i = 0; i < n; ++i) {
    float* ri = row(i);
    const float zi = z_[i];
#pragma omp simd
    for (int c = 0; c < n; ++c) ri[c] -= f[c] * zi;
  }
}

void FdWave::step() {
  const int n = p_.n;
  const std::size_t nn = static_cast<std::size_t>(n) * n;
  const float a = static_cast<float>(std::pow(p_.speed_mps * p_.dt / (p_.length_m / n), 2));
  if (p_.scheme == FdScheme::leapfrog) {
    laplacian_update(cur_.data(), prev_.data(), next_.data(), a);
  } else {
    // rhs = 2 eta^n - eta^{n-1}; the y sweep on the transposed field is the x sweep
    float* rhs = next_.data();
#pragma omp simd
    for (std::size_t i = 0; i < nn; ++i) rhs[i] = 2.0f * cur_[i] - prev_[i];
    transpose(rhs, tmp_.data());
    solve_columns(tmp_.data());  // along x
    transpose(tmp_.data(), rhs);
    solve_columns(rhs);  // along y
  }
  std::swap(prev_, cur_);
  std::swap(cur_, next_);
  t_ += p_.dt;
}

}  // namespace huygens::bench
