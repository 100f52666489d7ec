// The height stage on a slab (stokes.hpp, docs/scale.md "Huygens on slabs"): the height couples
// k and -k, which lie on different ranks; beta = (k - k/omega)/2 depends on |k| only, so
//   IFFT[beta conj Y(-k)](x) = conj(IFFT[beta Y](x)),
// and eta + i etadot = i A + i conj(B) with A = IFFT[alpha Y], B = IFFT[beta Y]; as alpha - beta =
// m = k/omega and alpha + beta = k, that is eta1 = -Im IFFT[m Y], etadot1 = Re IFFT[k Y] (no
// difference of the two large k/2 terms is formed). One more transform (one more transpose,
// 8 N^2/P (P-1)/P bytes) instead of exchanging the mirrored slab (8 N^2/P bytes, nearly all of it
// off-rank). Second order (paper 004 eq. 3): chi^ = i m s Y, chidot^ = k s Y, s = sqrt(k/2).
#include <stdexcept>

#include "huygens/spectral/stokes.hpp"

namespace huygens {

namespace {
constexpr int kParallelMin = 256;  // grids below this run the passes on one thread
}  // namespace

void StokesHeight::fill_split(const float* s, float zscale, const float* w0, const float* ph) {
  // Y = zscale Z^ + W^(0) P (wind; ph the quadrant phase); U^ = m Y, V^ = k Y
  const int n = n_, h = n / 2, q = h + 1;
  if (w0 && !ph) throw std::logic_error("StokesHeight: a slab takes the extra spectrum as the wind sea W^(0) P only");
  float *A = reinterpret_cast<float*>(x_.data()), *B = reinterpret_cast<float*>(b_.data());
  float *C = reinterpret_cast<float*>(chi_.data()), *D = reinterpret_cast<float*>(chid_.data());
  const bool sec = second_;
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t lr = 0; lr < g_.krows; ++lr) {
    const int qr = quadrant_index(g_.spectrum_row(lr), n);
    const std::size_t o = 2 * static_cast<std::size_t>(lr) * n, qo = static_cast<std::size_t>(qr) * q;
    const float *tm = kw_.data() + qo, *tk = k_.data() + qo, *ts = sec ? sq_.data() + qo : nullptr;
    for (int c = 0; c < n; ++c) {
      const int j = c <= h ? c : n - c;
      float yr = zscale * s[o + 2 * c], yi = zscale * s[o + 2 * c + 1];
      if (w0) {
        const float wr = w0[o + 2 * c], wi = w0[o + 2 * c + 1], pr = ph[2 * (qo + j)], pi = ph[2 * (qo + j) + 1];
        yr += wr * pr - wi * pi;
        yi += wr * pi + wi * pr;
      }
      const float m = tm[j], k = tk[j];
      A[o + 2 * c] = m * yr;
      A[o + 2 * c + 1] = m * yi;
      B[o + 2 * c] = k * yr;
      B[o + 2 * c + 1] = k * yi;
      if (!sec) continue;
      const float ms = m * ts[j], ks = k * ts[j];
      C[o + 2 * c] = -ms * yi;
      C[o + 2 * c + 1] = ms * yr;
      D[o + 2 * c] = ks * yr;
      D[o + 2 * c + 1] = ks * yi;
    }
  }
}

bool StokesHeight::extract_split(float* eta, float* etadot) const {
  // eta + i etadot = i A + i conj(B) with A = (U + V)/2, B = (V - U)/2: eta = -Im U, etadot = Re V;
  // second order adds Re(chi^2) and Re(2 chi chidot). Fused non-finite test (x - x).
  const int n = n_, m0 = m_, v = n - 2 * m_;
  const float *A = reinterpret_cast<const float*>(x_.data()), *B = reinterpret_cast<const float*>(b_.data());
  const float *C = reinterpret_cast<const float*>(chi_.data()), *D = reinterpret_cast<const float*>(chid_.data());
  const bool sec = second_;
  float acc = 0.0f;
#pragma omp parallel for schedule(static) reduction(+ : acc) if (n >= kParallelMin)
  for (std::ptrdiff_t r = 0; r < vis_.count; ++r) {
    const std::size_t o = 2 * (static_cast<std::size_t>(r + vis_.first) * n + m0);
    float* e = eta + static_cast<std::size_t>(r) * v;
    float* d = etadot + static_cast<std::size_t>(r) * v;
    for (int c = 0; c < v; ++c) {
      float ev = -A[o + 2 * c + 1], dv = B[o + 2 * c];
      if (sec) {
        const float cr = C[o + 2 * c], ci = C[o + 2 * c + 1], dr = D[o + 2 * c], di = D[o + 2 * c + 1];
        ev += cr * cr - ci * ci;
        dv += 2.0f * (cr * dr - ci * di);
      }
      e[c] = ev;
      d[c] = dv;
      acc += (ev - ev) + (dv - dv);
    }
  }
  return acc == 0.0f;
}

}  // namespace huygens
