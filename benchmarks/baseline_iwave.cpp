#include "baseline_iwave.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <utility>

namespace huygens::bench {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

std::vector<double> iwave_kernel(const IwaveParams& p) {
  const int w = 2 * p.half + 1;
  const double dq = 0.001;
  std::vector<double> g(static_cast<std::size_t>(w) * w);
  std::map<int, double> by_r2;  // G depends on r^2 = i^2 + j^2 only
  for (int i = -p.half; i <= p.half; ++i)
    for (int j = -p.half; j <= p.half; ++j) {
      const int r2 = i * i + j * j;
      auto it = by_r2.find(r2);
      if (it == by_r2.end()) {
        const double r = std::sqrt(static_cast<double>(r2));
        double s = 0;
        for (int n = 1; n <= 10000; ++n) {
          const double q = n * dq;
          s += q * q * std::exp(-p.taper * q * q) * ::j0(q * r);
        }
        it = by_r2.emplace(r2, s * dq / (2 * kPi)).first;
      }
      g[static_cast<std::size_t>(i + p.half) * w + (j + p.half)] = it->second;
    }
  if (p.zero_sum) {
    double sum = 0;
    for (double v : g) sum += v;
    g[static_cast<std::size_t>(p.half) * w + p.half] -= sum;
  }
  return g;
}

double iwave_symbol(const std::vector<double>& kernel, int half, double k_cells) {
  const int w = 2 * half + 1;
  double s = 0;
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j)
      s += kernel[static_cast<std::size_t>(i + half) * w + (j + half)] * std::cos(k_cells * j);
  return s;
}

std::string iwave_params_error(const IwaveParams& p) {
  if (p.half < 1 || p.n < 2 * p.half + 1) return "n must be >= 2 * half + 1";
  if (!(p.length_m > 0) || !(p.dt > 0) || !(p.gravity > 0) || !(p.damping >= 0))
    return "bad length, dt, gravity or damping";
  // leapfrog limit: g dt^2 Ghat(k) / dx <= 4 over the 2D Brillouin zone. Where Ghat < 0 (Tessendorf's
  // kernel: -0.006 at k dx = pi along an axis) the mode grows as exp(sqrt(g |Ghat| / dx) t) whatever
  // dt: slow from rounding noise, reported by iwave_symbol_range(), not refused.
  const auto g = iwave_kernel(p);
  const int w = 2 * p.half + 1;
  double gmax = 0, gmin = 0;
  for (int a = 0; a <= 32; ++a)
    for (int b = 0; b <= a; ++b) {
      double s = 0;
      for (int i = -p.half; i <= p.half; ++i)
        for (int j = -p.half; j <= p.half; ++j)
          s += g[static_cast<std::size_t>(i + p.half) * w + (j + p.half)] * std::cos(kPi / 32 * (a * j + b * i));
      gmax = std::max(gmax, s);
      gmin = std::min(gmin, s);
    }
  (void)gmin;
  if (p.gravity * p.dt * p.dt * gmax / (p.length_m / p.n) > 4.0)
    return "iWave leapfrog unstable: g dt^2 max G^ / dx > 4";
  return {};
}

IwaveSolver::IwaveSolver(const IwaveParams& p) : p_(p) {
  if (auto e = iwave_params_error(p); !e.empty()) throw std::invalid_argument(e);
  for (double v : iwave_kernel(p)) g_.push_back(static_cast<float>(v));
  const std::size_t nn = static_cast<std::size_t>(p.n) * p.n;
  const std::size_t w = static_cast<std::size_t>(p.n + 2 * p.half);
  prev_ = AlignedBuffer<float>(nn);
  cur_ = AlignedBuffer<float>(nn);
  next_ = AlignedBuffer<float>(nn);
  conv_ = AlignedBuffer<float>(nn);
  pad_ = AlignedBuffer<float>(w * w);
}

// periodic padding by P cells, then out[r][c] = sum_{i,j} G[i][j] pad[r + i][c + j]
void IwaveSolver::convolve(const float* in, float* out) {
  const int n = p_.n, h = p_.half, w = n + 2 * h, kw = 2 * h + 1;
  for (int r = 0; r < w; ++r) {
    const float* src = in + static_cast<std::size_t>((r - h + n) % n) * n;
    float* dst = pad_.data() + static_cast<std::size_t>(r) * w;
    std::memcpy(dst + h, src, n * sizeof(float));
    std::memcpy(dst, src + n - h, h * sizeof(float));
    std::memcpy(dst + h + n, src, h * sizeof(float));
  }
  for (int r = 0; r < n; ++r) {
    float* o = out + static_cast<std::size_t>(r) * n;
#pragma omp simd
    for (int c = 0; c < n; ++c) o[c] = 0.0f;
    for (int i = 0; i < kw; ++i) {
      const float* row = pad_.data() + static_cast<std::size_t>(r + i) * w;
      for (int j = 0; j < kw; ++j) {
        const float gij = g_[static_cast<std::size_t>(i) * kw + j];
        const float* s = row + j;
#pragma omp simd
        for (int c = 0; c < n; ++c) o[c] += gij * s[c];
      }
    }
  }
}

void IwaveSolver::init(std::span<const float> eta0, std::span<const float> etadot0) {
  const std::size_t nn = cur_.size();
  if (eta0.size() != nn || etadot0.size() != nn) throw std::invalid_argument("IwaveSolver::init: size is not N*N");
  std::memcpy(cur_.data(), eta0.data(), nn * sizeof(float));
  // eta(-dt) = eta0 - dt etadot0 + dt^2/2 eta_tt(0), eta_tt = -g (G * eta) / dx
  convolve(cur_.data(), conv_.data());
  const float dt = static_cast<float>(p_.dt), f = static_cast<float>(p_.gravity / (p_.length_m / p_.n));
  for (std::size_t i = 0; i < nn; ++i) prev_[i] = eta0[i] - dt * etadot0[i] - 0.5f * dt * dt * f * conv_[i];
  t_ = 0;
}

void IwaveSolver::step() {
  const std::size_t nn = cur_.size();
  convolve(cur_.data(), conv_.data());
  const double ad = p_.damping * p_.dt;
  const float c1 = static_cast<float>((2 - ad) / (1 + ad)), c2 = static_cast<float>(1 / (1 + ad));
  const float c3 = static_cast<float>(p_.gravity * p_.dt * p_.dt / (p_.length_m / p_.n) / (1 + ad));
  const float* e = cur_.data();
  const float* ep = prev_.data();
  const float* cv = conv_.data();
  float* o = next_.data();
#pragma omp simd
  for (std::size_t i = 0; i < nn; ++i) o[i] = c1 * e[i] - c2 * ep[i] - c3 * cv[i];
  std::swap(prev_, cur_);
  std::swap(cur_, next_);
  t_ += p_.dt;
}

}  // namespace huygens::bench
