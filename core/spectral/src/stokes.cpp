#include "huygens/spectral/stokes.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>

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
    : StokesHeight(water, length_m, second_order, whole_grid_layout(n, effort), margin) {}

StokesHeight::StokesHeight(const Water& water, double length_m, bool second_order, const GridLayout& layout, int margin)
    : n_(layout.n),
      m_(margin),
      second_(second_order),
      split_(!layout.whole),
      g_(layout),
      vis_(layout.visible(margin)),
      threads_(std::max(1, omp_get_max_threads())) {
  const int n = n_;
  const std::size_t qq = static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1), slab = static_cast<std::size_t>(g_.alloc);
  k_ = AlignedBuffer<float>(qq);
  kw_ = AlignedBuffer<float>(qq);
  if (second_) sq_ = AlignedBuffer<float>(qq);
  if (!split_) scratch_ = AlignedBuffer<float>(static_cast<std::size_t>(threads_) * kScratchRows * n);
  x_ = AlignedBuffer<cfloat>(slab);
  if (split_) b_ = AlignedBuffer<cfloat>(slab);
  if (second_) {
    chi_ = AlignedBuffer<cfloat>(slab);
    chid_ = AlignedBuffer<cfloat>(slab);
  }
  inverse_ = g_.make_transform(x_.data(), x_.data(), Fft2D::backward);
  // quadrant tables: FFT indices (r, c) in [0, N/2]^2 stand for the modes (+-r, +-c) (the sign
  // of an integer times dk is exact, and hypot ignores signs: the values are those of every mode)
  const int q = n / 2 + 1;
  for (int r = 0; r < q; ++r)
    for (int c = 0; c < q; ++c) {
      const double kx = fft_wavenumber(c, n, length_m), ky = fft_wavenumber(r, n, length_m);
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
         (x_.size() + b_.size() + chi_.size() + chid_.size()) * sizeof(cfloat);
}

void StokesHeight::raw_transforms() {
  inverse_->execute();
  if (split_) inverse_->execute(b_.data(), b_.data());
  if (!second_) return;
  inverse_->execute(chi_.data(), chi_.data());
  inverse_->execute(chid_.data(), chid_.data());
}

bool StokesHeight::compute(const cfloat* zhat, float zscale, const cfloat* extra, float* eta, float* etadot) {
  return run(zhat, zscale, extra, nullptr, eta, etadot);
}

bool StokesHeight::compute(const cfloat* zhat, float zscale, const WindSea& wind, float* eta, float* etadot) {
  return run(zhat, zscale, wind.base(), wind.phase_quadrant(), eta, etadot);
}

namespace {

/// Per-thread row scratch (L1-resident): three table rows of N floats, four complex rows.
struct RowScratch {
  float* tm;  // k/omega, N columns
  float* tk;  // k
  float* ts;  // sqrt(k/2)
  float* y0;  // Y row r (2N floats)
  float* y1;  // Y row N - r
  float* w0;  // Y row N - r reversed: Y(-k) for row r
  float* w1;  // Y row r reversed: Y(-k) for row N - r
};

RowScratch row_scratch(float* scr, int n) {
  RowScratch s;
  s.tm = scr;
  s.tk = s.tm + n;
  s.ts = s.tk + n;
  s.y0 = s.ts + n;
  s.y1 = s.y0 + 2 * n;
  s.w0 = s.y1 + 2 * n;
  s.w1 = s.w0 + 2 * n;
  return s;
}

/// Quadrant table rows |r| expanded to N columns: index c up to N/2, N - c above.
inline void expand_tables(const float* km, const float* kk, const float* ks, const RowScratch& s, int n) {
  const int h = n / 2;
#pragma omp simd
  for (int c = 0; c <= h; ++c) {
    s.tm[c] = km[c];
    s.tk[c] = kk[c];
  }
#pragma omp simd
  for (int c = h + 1; c < n; ++c) {
    s.tm[c] = km[n - c];
    s.tk[c] = kk[n - c];
  }
  if (!ks) return;
#pragma omp simd
  for (int c = 0; c <= h; ++c) s.ts[c] = ks[c];
#pragma omp simd
  for (int c = h + 1; c < n; ++c) s.ts[c] = ks[n - c];
}

/// One row of Y = zs Z^ + W^ from the rows zu of Z^ and eu of the sea (null: none); with the
/// sea's phase row p (quadrant row |r|, read forward up to N/2, backward above) W^ = W^(0) P.
inline void load_row(const float* zu, float zs, const float* eu, const float* p, float* y, int n) {
  if (!eu) {
#pragma omp simd
    for (int c = 0; c < 2 * n; ++c) y[c] = zs * zu[c];
    return;
  }
  if (!p) {
#pragma omp simd
    for (int c = 0; c < 2 * n; ++c) y[c] = zs * zu[c] + eu[c];
    return;
  }
  const int h = n / 2;
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

/// dst[c] = src[(N - c) mod N], whole 64-bit complex values (a reversed copy GCC vectorises).
inline void reverse_row(const float* src, float* dst, int n) {
  const Bits64* s = reinterpret_cast<const Bits64*>(src);
  Bits64* d = reinterpret_cast<Bits64*>(dst);
  d[0] = s[0];
#pragma omp simd
  for (int c = 1; c < n; ++c) d[c] = s[n - c];
}

/// Transform inputs of one row from y = Y(k) = (a, b) and w = Y(-k) = (c, d):
///   X = (-(m (b + d) + k (b - d)) / 2, (m (a - c) + k (a + c)) / 2),  m = k/omega;
///   second order: chi^ = m s (-b, a), chidot^ = k s (a, b),  s = sqrt(k/2).
inline void output_row(const float* y, const float* w, const RowScratch& t, float* xo, float* co, float* dq, int n) {
#pragma omp simd
  for (int c = 0; c < n; ++c) {
    const float a = y[2 * c], b = y[2 * c + 1], cc = w[2 * c], d = w[2 * c + 1];
    const float m = t.tm[c], k = t.tk[c];
    xo[2 * c] = -0.5f * (m * (b + d) + k * (b - d));
    xo[2 * c + 1] = 0.5f * (m * (a - cc) + k * (a + cc));
  }
  if (!co) return;
#pragma omp simd
  for (int c = 0; c < n; ++c) {
    const float a = y[2 * c], b = y[2 * c + 1];
    const float ms = t.tm[c] * t.ts[c], ks = t.tk[c] * t.ts[c];
    co[2 * c] = -ms * b;
    co[2 * c + 1] = ms * a;
    dq[2 * c] = ks * a;
    dq[2 * c + 1] = ks * b;
  }
}

}  // namespace

bool StokesHeight::run(const cfloat* zhat, float zscale, const cfloat* extra, const cfloat* extra_phase, float* eta,
                       float* etadot) {
  const float* z = reinterpret_cast<const float*>(zhat);
  const float* ex = reinterpret_cast<const float*>(extra);
  const float* ph = reinterpret_cast<const float*>(extra_phase);
  if (split_)
    fill_split(z, zscale, ex, ph);
  else
    fill_inputs(z, zscale, ex, ph);
  const auto t0 = std::chrono::steady_clock::now();
  raw_transforms();
  fft_ns_ += elapsed_ns(t0);
  if (split_) return extract_split(eta, etadot);
  return second_ ? extract_second_order(eta, etadot) : extract_first_order(eta, etadot);
}

void StokesHeight::fill_inputs(const float* z, float zscale, const float* extra, const float* phase) {
  // One pass over the spectrum by pairs of mirror rows (r, N - r), so that every row of Y and
  // of the sea is read from memory once (formulas at output_row). Y(-k) of row r is row N - r
  // read backwards: both rows and their reversed copies sit in per-thread scratch in L1, with
  // the quadrant table row |r| expanded to N columns; then every loop runs forward, unit stride.
  const int n = n_, h = n / 2, q = h + 1;
  const bool sec = second_;
  float* xf = reinterpret_cast<float*>(x_.data());
  float* cf = reinterpret_cast<float*>(chi_.data());
  float* df = reinterpret_cast<float*>(chid_.data());
  const int threads = std::min(threads_, omp_get_max_threads());
#pragma omp parallel num_threads(threads) if (n >= kParallelMin)
  {
    const RowScratch t =
        row_scratch(scratch_.data() + static_cast<std::size_t>(omp_get_thread_num()) * kScratchRows * n, n);
#pragma omp for schedule(static)
    for (int r = 0; r <= h; ++r) {
      const int rm = (n - r) & (n - 1);
      const bool pair = rm != r;  // a self-mirrored row (r = 0 or N/2) is its own partner
      const std::size_t qo = static_cast<std::size_t>(r) * q;
      const std::size_t o0 = 2 * static_cast<std::size_t>(r) * n, o1 = 2 * static_cast<std::size_t>(rm) * n;
      const float* p = phase ? phase + 2 * qo : nullptr;
      expand_tables(kw_.data() + qo, k_.data() + qo, sec ? sq_.data() + qo : nullptr, t, n);
      load_row(z + o0, zscale, extra ? extra + o0 : nullptr, p, t.y0, n);
      if (pair) load_row(z + o1, zscale, extra ? extra + o1 : nullptr, p, t.y1, n);
      const float* ym = pair ? t.y1 : t.y0;
      reverse_row(ym, t.w0, n);
      if (pair) reverse_row(t.y0, t.w1, n);
      output_row(t.y0, t.w0, t, xf + o0, sec ? cf + o0 : nullptr, sec ? df + o0 : nullptr, n);
      if (pair) output_row(ym, t.w1, t, xf + o1, sec ? cf + o1 : nullptr, sec ? df + o1 : nullptr, n);
    }
  }
}

bool StokesHeight::extract_first_order(float* eta, float* etadot) const {
  // the visible region of X = eta1 + i etadot1, with a fused non-finite test (x - x is
  // non-zero only for NaN or inf)
  const int n = n_, m0 = m_, v = n - 2 * m_;
  const cfloat* X = x_.data();
  float acc = 0.0f;
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

bool StokesHeight::extract_second_order(float* eta, float* etadot) const {
  // eta = Re X + Re(chi^2), etadot = Im X + Re(2 chi chidot) on the visible region, with the
  // fused non-finite test
  const int n = n_, m0 = m_, v = n - 2 * m_;
  const cfloat* X = x_.data();
  const cfloat* C = chi_.data();
  const cfloat* D = chid_.data();
  float acc = 0.0f;
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
