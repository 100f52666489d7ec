#include "huygens/huygens/stokes.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

namespace huygens {

namespace {
std::uint64_t elapsed_ns(std::chrono::steady_clock::time_point t0) {
  return static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0).count());
}
// one complex float moved as a unit (may alias the float data)
using Bits64 = std::uint64_t __attribute__((may_alias));
// grids below this size run the passes on one thread (a fork costs more than the pass)
constexpr int kParallelMin = 256;
// scratch floats per thread, in units of N: three table rows + four complex rows
constexpr int kScratchRows = 11;
}  // namespace

StokesHeight::StokesHeight(const Water& water, int n, double length_m, bool second_order, PlanEffort effort, int margin)
    : n_(n),
      m_(margin),
      second_(second_order),
      threads_(std::max(1, omp_get_max_threads())),
      k_(static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1)),
      kw_(static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1)),
      sq_(second_order ? static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1) : 0),
      scratch_(static_cast<std::size_t>(threads_) * kScratchRows * n),
      x_(static_cast<std::size_t>(n) * n),
      chi_(second_order ? static_cast<std::size_t>(n) * n : 0),
      chid_(second_order ? static_cast<std::size_t>(n) * n : 0),
      inverse_(n, n, x_.data(), x_.data(), Fft2D::backward, effort) {
  // quadrant tables: FFT indices (r, c) in [0, N/2]^2 stand for the modes (+-r, +-c) (the sign
  // of an integer times dk is exact, and hypot ignores signs: the values are those of every mode)
  const double dk = 2.0 * std::numbers::pi / length_m;
  const int q = n / 2 + 1;
  for (int r = 0; r < q; ++r)
    for (int c = 0; c < q; ++c) {
      const double kx = dk * (c < n / 2 ? c : c - n), ky = dk * (r < n / 2 ? r : r - n);
      const double k = std::hypot(kx, ky);
      const std::size_t m = static_cast<std::size_t>(r) * q + c;
      const double om = omega(water, k);
      k_[m] = static_cast<float>(k);
      kw_[m] = k > 0.0 ? static_cast<float>(k / om) : 0.0f;
      if (second_) sq_[m] = static_cast<float>(std::sqrt(0.5 * k));
    }
}

std::size_t StokesHeight::bytes() const {
  return (k_.size() + kw_.size() + sq_.size() + scratch_.size()) * sizeof(float) +
         (x_.size() + chi_.size() + chid_.size()) * sizeof(cfloat);
}

void StokesHeight::raw_transforms() {
  inverse_.execute();
  if (!second_) return;
  inverse_.execute(chi_.data(), chi_.data());
  inverse_.execute(chid_.data(), chid_.data());
}

bool StokesHeight::compute(const cfloat* zhat, float zscale, const cfloat* extra, float* eta, float* etadot) {
  return run(zhat, zscale, extra, nullptr, eta, etadot);
}

bool StokesHeight::compute(const cfloat* zhat, float zscale, const WindSea& wind, float* eta, float* etadot) {
  return run(zhat, zscale, wind.base(), wind.phase_quadrant(), eta, etadot);
}

bool StokesHeight::run(const cfloat* zhat, float zscale, const cfloat* extra, const cfloat* extra_phase, float* eta,
                       float* etadot) {
  const int n = n_, h = n / 2, q = h + 1;
  const bool sec = second_;
  const int m0 = m_, v = n - 2 * m_;
  const float zs = zscale;
  const bool has_extra = extra != nullptr;
  const float* zf = reinterpret_cast<const float*>(zhat);
  const float* ef = reinterpret_cast<const float*>(extra);
  const float* esf = reinterpret_cast<const float*>(extra_phase);
  float* xf = reinterpret_cast<float*>(x_.data());
  float* cf = reinterpret_cast<float*>(chi_.data());
  float* df = reinterpret_cast<float*>(chid_.data());
  const float* KQ = k_.data();
  const float* MQ = kw_.data();
  const float* SQ = sq_.data();
  float* scratch = scratch_.data();
  const int threads = std::min(threads_, omp_get_max_threads());

  // One pass over the spectrum, by pairs of mirror rows (r, N - r) so that every row of Y and
  // of the wind is read from memory once:
  //   Y = zscale Z^ + W^ (W^ = W^(0) P(|k|) for the wind sea, formed here),
  //   X = H[i k/omega Y] + i H[k Y],  chi^ = i (k/omega) sqrt(k/2) Y,  chidot^ = k sqrt(k/2) Y.
  // With y = Y(k) = (a, b) and w = Y(-k) = (c, d) on interleaved floats:
  //   X = (-(m (b + d) + k (b - d)) / 2, (m (a - c) + k (a + c)) / 2),  m = k/omega,
  //   chi^ = m s (-b, a),  chidot^ = k s (a, b),  s = sqrt(k/2).
  // Y(-k) of row r is row N - r read backwards: the two rows and their reversed copies (whole
  // 64-bit complex values, which GCC vectorises) sit in per-thread scratch in L1, with the
  // quadrant table row |r| expanded to N columns; then every loop runs forward, unit stride.
#pragma omp parallel num_threads(threads) if (n >= kParallelMin)
  {
    float* scr = scratch + static_cast<std::size_t>(omp_get_thread_num()) * kScratchRows * n;
    float* tm = scr;         // k/omega, N columns
    float* tk = tm + n;      // k
    float* ts = tk + n;      // sqrt(k/2)
    float* y0 = ts + n;      // Y row r (2N floats)
    float* y1 = y0 + 2 * n;  // Y row N - r
    float* w0 = y1 + 2 * n;  // Y row N - r reversed: Y(-k) for row r
    float* w1 = w0 + 2 * n;  // Y row r reversed: Y(-k) for row N - r
#pragma omp for schedule(static)
    for (int r = 0; r <= h; ++r) {
      const int rm = (n - r) & (n - 1);
      const bool pair = rm != r;
      const std::size_t qo = static_cast<std::size_t>(r) * q;
      // table row |r| on N columns: index c up to N/2, N - c above
      {
        const float *km = MQ + qo, *kk = KQ + qo, *ks = sec ? SQ + qo : nullptr;
#pragma omp simd
        for (int c = 0; c <= h; ++c) {
          tm[c] = km[c];
          tk[c] = kk[c];
        }
#pragma omp simd
        for (int c = h + 1; c < n; ++c) {
          tm[c] = km[n - c];
          tk[c] = kk[n - c];
        }
        if (sec) {
#pragma omp simd
          for (int c = 0; c <= h; ++c) ts[c] = ks[c];
#pragma omp simd
          for (int c = h + 1; c < n; ++c) ts[c] = ks[n - c];
        }
      }
      // Y rows
      for (int side = 0; side < (pair ? 2 : 1); ++side) {
        const std::size_t o = 2 * static_cast<std::size_t>(side == 0 ? r : rm) * n;
        const float* zu = zf + o;
        float* y = side == 0 ? y0 : y1;  // side 1 only for a pair
        if (!has_extra) {
#pragma omp simd
          for (int c = 0; c < 2 * n; ++c) y[c] = zs * zu[c];
        } else if (!esf) {
          const float* eu = ef + o;
#pragma omp simd
          for (int c = 0; c < 2 * n; ++c) y[c] = zs * zu[c] + eu[c];
        } else {
          // the wind sea W^(0) P, P on the quadrant row |r| (forward up to N/2, backward above)
          const float* eu = ef + o;
          const float* p = esf + 2 * qo;
#pragma omp simd
          for (int c = 0; c <= h; ++c) {
            const float a = eu[2 * c], b = eu[2 * c + 1], x = p[2 * c], s = p[2 * c + 1];
            y[2 * c] = zs * zu[2 * c] + (a * x - b * s);
            y[2 * c + 1] = zs * zu[2 * c + 1] + (a * s + b * x);
          }
#pragma omp simd
          for (int c = h + 1; c < n; ++c) {
            const int j = n - c;
            const float a = eu[2 * c], b = eu[2 * c + 1], x = p[2 * j], s = p[2 * j + 1];
            y[2 * c] = zs * zu[2 * c] + (a * x - b * s);
            y[2 * c + 1] = zs * zu[2 * c + 1] + (a * s + b * x);
          }
        }
      }
      // a self-mirrored row (r = 0 or N/2) is its own partner
      const float* ym = pair ? y1 : y0;
      float* wm = pair ? w1 : w0;
      // reversed copies: w[c] = y[(N - c) mod N] as whole complex values
      for (int side = 0; side < (pair ? 2 : 1); ++side) {
        const Bits64* src = reinterpret_cast<const Bits64*>(side == 0 ? ym : y0);
        Bits64* dst = reinterpret_cast<Bits64*>(side == 0 ? w0 : w1);
        dst[0] = src[0];
#pragma omp simd
        for (int c = 1; c < n; ++c) dst[c] = src[n - c];
      }
      // outputs, both rows
      for (int side = 0; side < (pair ? 2 : 1); ++side) {
        const std::size_t o = 2 * static_cast<std::size_t>(side == 0 ? r : rm) * n;
        const float* y = side == 0 ? y0 : ym;
        const float* w = side == 0 ? w0 : wm;
        float* xo = xf + o;
#pragma omp simd
        for (int c = 0; c < n; ++c) {
          const float a = y[2 * c], b = y[2 * c + 1], cc = w[2 * c], d = w[2 * c + 1];
          const float m = tm[c], k = tk[c];
          xo[2 * c] = -0.5f * (m * (b + d) + k * (b - d));
          xo[2 * c + 1] = 0.5f * (m * (a - cc) + k * (a + cc));
        }
        if (sec) {
          float* co = cf + o;
          float* dq = df + o;
#pragma omp simd
          for (int c = 0; c < n; ++c) {
            const float a = y[2 * c], b = y[2 * c + 1];
            const float ms = tm[c] * ts[c], ks = tk[c] * ts[c];
            co[2 * c] = -ms * b;
            co[2 * c + 1] = ms * a;
            dq[2 * c] = ks * a;
            dq[2 * c + 1] = ks * b;
          }
        }
      }
    }
  }
  auto t0 = std::chrono::steady_clock::now();
  inverse_.execute();
  if (sec) {
    inverse_.execute(chi_.data(), chi_.data());
    inverse_.execute(chid_.data(), chid_.data());
  }
  fft_ns_ += elapsed_ns(t0);

  // outputs over the visible region only, with a fused non-finite test (x - x is non-zero only
  // for NaN or inf)
  const cfloat* X = x_.data();
  const cfloat* C = chi_.data();
  const cfloat* D = chid_.data();
  float acc = 0.0f;
  if (!sec) {
#pragma omp parallel for schedule(static) if (n >= kParallelMin) reduction(+ : acc)
    for (int r = 0; r < v; ++r) {
      const std::size_t o = static_cast<std::size_t>(r + m0) * n + m0, qv = static_cast<std::size_t>(r) * v;
      const float* xs = reinterpret_cast<const float*>(X + o);
      float* e = eta + qv;
      float* dd = etadot + qv;
#pragma omp simd reduction(+ : acc)
      for (int c = 0; c < v; ++c) {
        e[c] = xs[2 * c];
        dd[c] = xs[2 * c + 1];
        acc += (xs[2 * c] - xs[2 * c]) + (xs[2 * c + 1] - xs[2 * c + 1]);
      }
    }
    return acc == 0.0f;
  }
#pragma omp parallel for schedule(static) if (n >= kParallelMin) reduction(+ : acc)
  for (int r = 0; r < v; ++r) {
    const std::size_t o = static_cast<std::size_t>(r + m0) * n + m0, qv = static_cast<std::size_t>(r) * v;
    const float* xs = reinterpret_cast<const float*>(X + o);
    const float* cs = reinterpret_cast<const float*>(C + o);
    const float* ds = reinterpret_cast<const float*>(D + o);
    float* eo = eta + qv;
    float* dd = etadot + qv;
#pragma omp simd reduction(+ : acc)
    for (int c = 0; c < v; ++c) {
      const float cr = cs[2 * c], ci = cs[2 * c + 1], dr = ds[2 * c], di = ds[2 * c + 1];
      const float e = xs[2 * c] + cr * cr - ci * ci, d = xs[2 * c + 1] + 2.0f * (cr * dr - ci * di);
      eo[c] = e;
      dd[c] = d;
      acc += (e - e) + (d - d);
    }
  }
  return acc == 0.0f;
}

}  // namespace huygens
