#include "huygens/stokes.hpp"

#include <cmath>
#include <numbers>

namespace huygens {

StokesHeight::StokesHeight(const Water& water, int n, double length_m, bool second_order, PlanEffort effort, int margin)
    : n_(n),
      m_(margin),
      second_(second_order),
      k_(static_cast<std::size_t>(n) * n),
      kw_(static_cast<std::size_t>(n) * n),
      sq_(second_order ? static_cast<std::size_t>(n) * n : 0),
      x_(static_cast<std::size_t>(n) * n),
      chi_(second_order ? static_cast<std::size_t>(n) * n : 0),
      chid_(second_order ? static_cast<std::size_t>(n) * n : 0),
      inverse_(n, n, x_.data(), x_.data(), Fft2D::backward, effort) {
  const double dk = 2.0 * std::numbers::pi / length_m;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const double kx = dk * (c < n / 2 ? c : c - n), ky = dk * (r < n / 2 ? r : r - n);
      const double k = std::hypot(kx, ky);
      const std::size_t m = static_cast<std::size_t>(r) * n + c;
      const double om = omega(water, k);
      k_[m] = static_cast<float>(k);
      kw_[m] = k > 0.0 ? static_cast<float>(k / om) : 0.0f;
      if (second_) sq_[m] = static_cast<float>(std::sqrt(0.5 * k));
    }
}

std::size_t StokesHeight::bytes() const {
  return (k_.size() + kw_.size() + sq_.size()) * sizeof(float) +
         (x_.size() + chi_.size() + chid_.size()) * sizeof(cfloat);
}

bool StokesHeight::compute(const cfloat* zhat, float zscale, const cfloat* extra, float* eta, float* etadot) {
  const int n = n_;
  cfloat* X = x_.data();
  cfloat* C = chi_.data();
  cfloat* D = chid_.data();
  const float* K = k_.data();
  const float* KW = kw_.data();
  const float* SQ = sq_.data();
  const bool sec = second_;
  const int m0 = m_, v = n - 2 * m_;

  // spectra: X = H[i k/omega Y] + i H[k Y]; chi^ = i (k/omega) sqrt(k/2) Y; chidot^ = k sqrt(k/2) Y.
  // With y = Y(k) = (a, b) and w = Y(-k) = (c, d) on interleaved floats:
  //   X = (-(m (b + d) + k (b - d)) / 2, (m (a - c) + k (a + c)) / 2),  m = k/omega,
  //   chi^ = m s (-b, a),  chidot^ = k s (a, b),  s = sqrt(k/2).
  const float* zf = reinterpret_cast<const float*>(zhat);
  const float* ef = reinterpret_cast<const float*>(extra);
  float* xf = reinterpret_cast<float*>(X);
  float* cf = reinterpret_cast<float*>(C);
  float* df = reinterpret_cast<float*>(D);
  const float zs = zscale;
  const bool has_extra = extra != nullptr;
#pragma omp parallel for schedule(static) if (n >= 256)
  for (int r = 0; r < n; ++r) {
    const int mr = (n - r) % n;
    const std::size_t o = static_cast<std::size_t>(r) * n, mo = static_cast<std::size_t>(mr) * n;
    const float* zu = zf + 2 * o;
    const float* zw = zf + 2 * mo;
    const float* eu = has_extra ? ef + 2 * o : nullptr;
    const float* ew = has_extra ? ef + 2 * mo : nullptr;
    float* xo = xf + 2 * o;
    const float* kk = K + o;
    const float* mm = KW + o;
    // column 0 is its own mirror; columns 1..n-1 mirror to n - c (a reversed run GCC vectorises)
    auto one = [&](int c, int cn) {
      float a = zs * zu[2 * c], b = zs * zu[2 * c + 1], cc = zs * zw[2 * cn], d = zs * zw[2 * cn + 1];
      if (has_extra) {
        a += eu[2 * c];
        b += eu[2 * c + 1];
        cc += ew[2 * cn];
        d += ew[2 * cn + 1];
      }
      const float m = mm[c], k = kk[c];
      xo[2 * c] = -0.5f * (m * (b + d) + k * (b - d));
      xo[2 * c + 1] = 0.5f * (m * (a - cc) + k * (a + cc));
    };
    one(0, 0);
    if (has_extra) {
#pragma omp simd
      for (int c = 1; c < n; ++c) {
        const int cn = n - c;
        const float a = zs * zu[2 * c] + eu[2 * c], b = zs * zu[2 * c + 1] + eu[2 * c + 1];
        const float cc = zs * zw[2 * cn] + ew[2 * cn], d = zs * zw[2 * cn + 1] + ew[2 * cn + 1];
        const float m = mm[c], k = kk[c];
        xo[2 * c] = -0.5f * (m * (b + d) + k * (b - d));
        xo[2 * c + 1] = 0.5f * (m * (a - cc) + k * (a + cc));
      }
    } else {
#pragma omp simd
      for (int c = 1; c < n; ++c) {
        const int cn = n - c;
        const float a = zs * zu[2 * c], b = zs * zu[2 * c + 1], cc = zs * zw[2 * cn], d = zs * zw[2 * cn + 1];
        const float m = mm[c], k = kk[c];
        xo[2 * c] = -0.5f * (m * (b + d) + k * (b - d));
        xo[2 * c + 1] = 0.5f * (m * (a - cc) + k * (a + cc));
      }
    }
    if (sec) {
      const float* sq = SQ + o;
      float* co = cf + 2 * o;
      float* dq = df + 2 * o;
#pragma omp simd
      for (int c = 0; c < n; ++c) {
        float a = zs * zu[2 * c], b = zs * zu[2 * c + 1];
        if (has_extra) {
          a += eu[2 * c];
          b += eu[2 * c + 1];
        }
        const float ms = mm[c] * sq[c], ks = kk[c] * sq[c];
        co[2 * c] = -ms * b;
        co[2 * c + 1] = ms * a;
        dq[2 * c] = ks * a;
        dq[2 * c + 1] = ks * b;
      }
    }
  }
  inverse_.execute();
  // outputs with a fused non-finite test (x - x is non-zero only for NaN or inf)
  float acc = 0.0f;
  if (!sec) {
#pragma omp parallel for schedule(static) if (n >= 256) reduction(+ : acc)
    for (int r = 0; r < v; ++r) {
      const std::size_t o = static_cast<std::size_t>(r + m0) * n + m0, q = static_cast<std::size_t>(r) * v;
      const float* xs = reinterpret_cast<const float*>(X + o);
#pragma omp simd reduction(+ : acc)
      for (int c = 0; c < v; ++c) {
        eta[q + c] = xs[2 * c];
        etadot[q + c] = xs[2 * c + 1];
        acc += (xs[2 * c] - xs[2 * c]) + (xs[2 * c + 1] - xs[2 * c + 1]);
      }
    }
    return acc == 0.0f;
  }
  inverse_.execute(C, C);
  inverse_.execute(D, D);
#pragma omp parallel for schedule(static) if (n >= 256) reduction(+ : acc)
  for (int r = 0; r < v; ++r) {
    const std::size_t o = static_cast<std::size_t>(r + m0) * n + m0, q = static_cast<std::size_t>(r) * v;
    const float* xs = reinterpret_cast<const float*>(X + o);
    const float* cs = reinterpret_cast<const float*>(C + o);
    const float* ds = reinterpret_cast<const float*>(D + o);
#pragma omp simd reduction(+ : acc)
    for (int c = 0; c < v; ++c) {
      const float cr = cs[2 * c], ci = cs[2 * c + 1], dr = ds[2 * c], di = ds[2 * c + 1];
      const float e = xs[2 * c] + cr * cr - ci * ci, d = xs[2 * c + 1] + 2.0f * (cr * dr - ci * di);
      eta[q + c] = e;
      etadot[q + c] = d;
      acc += (e - e) + (d - d);
    }
  }
  return acc == 0.0f;
}

}  // namespace huygens
