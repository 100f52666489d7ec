#include "huygens/spectral/wind.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace huygens {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDevelopedFetch = 1.7e4;  // g F / U^2 where 22 x^(-1/3) reaches 0.855 (Pierson-Moskowitz)

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// A unit complex Gaussian (E|c|^2 = 1) keyed by (seed, mode indices).
std::complex<double> mode_gaussian(std::uint64_t seed, int mx, int my) {
  const std::uint64_t key =
      (static_cast<std::uint64_t>(static_cast<std::uint32_t>(mx)) << 32) | static_cast<std::uint32_t>(my);
  const std::uint64_t a = splitmix64(splitmix64(seed) ^ key);
  const std::uint64_t b = splitmix64(a);
  const double u1 = (static_cast<double>(a >> 11) + 0.5) * 0x1.0p-53;  // (0, 1)
  const double u2 = static_cast<double>(b >> 11) * 0x1.0p-53;
  const double r = std::sqrt(-std::log(u1));  // sqrt(-2 ln u1) / sqrt(2)
  return {r * std::cos(2.0 * kPi * u2), r * std::sin(2.0 * kPi * u2)};
}

double fetch_ratio(const WindParams& p, const Water& w) {
  return std::min(w.gravity_mps2 * p.fetch_m / (p.speed_mps * p.speed_mps), kDevelopedFetch);
}

}  // namespace

WindParams parse_wind(const JsonIn& j) {
  j.allow_only({"speed_mps", "direction_deg", "seed", "fetch_m", "gamma"});
  WindParams p;
  p.speed_mps = j.number("speed_mps", 0.0, 60.0);
  p.direction_deg = j.number("direction_deg", -360.0, 360.0);
  p.seed = static_cast<std::uint64_t>(j.integer("seed", 0, 9007199254740991LL));
  p.fetch_m = j.number("fetch_m", p.fetch_m, 1.0, 1e7);
  p.gamma = j.number("gamma", p.gamma, 1.0, 10.0);
  return p;
}

double jonswap_peak(const WindParams& p, const Water& w) {
  return 22.0 * w.gravity_mps2 / p.speed_mps * std::pow(fetch_ratio(p, w), -1.0 / 3.0);
}

double jonswap_alpha(const WindParams& p, const Water& w) { return 0.076 * std::pow(fetch_ratio(p, w), -0.22); }

double jonswap(const WindParams& p, const Water& w, double om) {
  if (om <= 0.0 || p.speed_mps <= 0.0) return 0.0;
  const double wp = jonswap_peak(p, w);
  const double s = om <= wp ? 0.07 : 0.09;
  const double r = std::exp(-(om - wp) * (om - wp) / (2.0 * s * s * wp * wp));
  const double q = wp / om;
  return jonswap_alpha(p, w) * w.gravity_mps2 * w.gravity_mps2 * std::pow(om, -5.0) * std::exp(-1.25 * q * q * q * q) *
         std::pow(p.gamma, r);
}

double wind_density(const WindParams& p, const Water& w, double kx, double ky) {
  const double k = std::hypot(kx, ky);
  if (k <= 0.0) return 0.0;
  const double th = p.direction_deg * kPi / 180.0;
  const double c = (kx * std::cos(th) + ky * std::sin(th)) / k;  // cos(theta - theta_w)
  if (c <= 0.0) return 0.0;
  const double d = 2.0 / kPi * c * c;
  return jonswap(p, w, omega(w, k)) * d * group_speed(w, k) / k;
}

WindSea::WindSea(const WindParams& p, const Water& w, int n, double length_m, double dt)
    : n_(n),
      dt_(dt),
      omega_(static_cast<std::size_t>(n) * n),
      w0_(static_cast<std::size_t>(n) * n),
      step_(static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1)),
      phase_(static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1)) {
  const double dk = 2.0 * kPi / length_m;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const std::size_t m = static_cast<std::size_t>(r) * n + c;
      omega_[m] = fill_mode(p, w, dk, c, r, m);
    }
  init_phase(w, dk);
}

WindSea::WindSea(const WindParams& p, const Water& w, int n, double length_m, double dt, WindRows rows)
    : n_(n),
      dt_(dt),
      omega_stride_(n / 2 + 1),
      omega_(static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1)),
      w0_(static_cast<std::size_t>(rows.count) * n),
      step_(static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1)),
      phase_(static_cast<std::size_t>(n / 2 + 1) * (n / 2 + 1)) {
  const double dk = 2.0 * kPi / length_m;
  // transposed rows: row lr holds kx index row0 + lr, column c the ky index c (normal: swapped)
  for (int lr = 0; lr < rows.count; ++lr)
    for (int c = 0; c < n; ++c) {
      const std::size_t m = static_cast<std::size_t>(lr) * n + c;
      if (rows.transposed)
        fill_mode(p, w, dk, rows.row0 + lr, c, m);
      else
        fill_mode(p, w, dk, c, rows.row0 + lr, m);
    }
  const int q = n / 2 + 1;
  for (int r = 0; r < q; ++r)
    for (int c = 0; c < q; ++c) omega_[static_cast<std::size_t>(r) * q + c] = omega(w, std::hypot(dk * c, dk * r));
  init_phase(w, dk);
}

double WindSea::fill_mode(const WindParams& p, const Water& w, double dk, int c, int r, std::size_t m) {
  // mode of FFT indices (row r = ky, column c = kx), stored at w0_[m]
  const int n = n_;
  const int mx = fft_signed_index(c, n), my = fft_signed_index(r, n);
  const double kx = dk * mx, ky = dk * my, k = std::hypot(kx, ky);
  const double om = omega(w, k);
  // k = 0 and the Nyquist row and column (their own mirror) carry no wave
  if (k == 0.0 || 2 * c == n || 2 * r == n) return om;
  const double f = wind_density(p, w, kx, ky);
  if (f <= 0.0) return om;
  variance_ += f * dk * dk;
  const double a = std::sqrt(2.0 * f * dk * dk);  // elevation amplitude (unit: m)
  const std::complex<double> z = std::complex<double>(0.0, -om / k) * a * mode_gaussian(p.seed, mx, my);
  w0_[m] = cfloat(z);
  return om;
}

void WindSea::init_phase(const Water& w, double dk) {
  // e^{-i omega dt} on the quadrant of FFT indices (r, c) in [0, N/2]^2: the value of every mode
  // (+-r, +-c), since omega depends on |k| only (and the sign of an integer times dk is exact)
  const int n = n_, q = n / 2 + 1;
  for (int r = 0; r < q; ++r)
    for (int c = 0; c < q; ++c) {
      const int mx = fft_signed_index(c, n), my = fft_signed_index(r, n);
      const double om = omega(w, std::hypot(dk * mx, dk * my));
      step_[static_cast<std::size_t>(r) * q + c] = cfloat(std::exp(std::complex<double>(0.0, -om * dt_)));
      phase_[static_cast<std::size_t>(r) * q + c] = cfloat(1.0f, 0.0f);
    }
}

void WindSea::advance() {
  ++steps_;
  cur_valid_ = false;
  const int n = n_, q = n / 2 + 1;
  if (steps_ % 256 == 0) {
    // exact phases from t (double), so that the repeated float products cannot drift
    const double t = time();
#pragma omp parallel for schedule(static) if (n >= 256)
    for (int r = 0; r < q; ++r)
      for (int c = 0; c < q; ++c) {
        const double om = omega_[static_cast<std::size_t>(r) * omega_stride_ + c];  // |k| of the quadrant cell
        phase_[static_cast<std::size_t>(r) * q + c] = cfloat(std::exp(std::complex<double>(0.0, -om * t)));
      }
    return;
  }
  // complex multiply written out on interleaved floats so GCC vectorises it
  float* ph = reinterpret_cast<float*>(phase_.data());
  const float* st = reinterpret_cast<const float*>(step_.data());
  const std::size_t total = phase_.size();
#pragma omp simd
  for (std::size_t m = 0; m < total; ++m) {
    const float a = ph[2 * m], b = ph[2 * m + 1], x = st[2 * m], y = st[2 * m + 1];
    ph[2 * m] = a * x - b * y;
    ph[2 * m + 1] = a * y + b * x;
  }
}

const cfloat* WindSea::spectrum() const {
  if (cur_valid_) return cur_.data();
  // first call: the buffer exists only for callers of spectrum() (tests, benchmarks); the
  // solver's height pass reads W^(0) and P directly, so a scene never allocates it
  if (!cur_.size()) cur_ = AlignedBuffer<cfloat>(static_cast<std::size_t>(n_) * n_);
  cur_valid_ = true;
  const int n = n_, h = n / 2, q = h + 1;
  // W^(t) = W^(0) P, the quadrant row |r| read forward for columns 0..N/2 and backward above
  const float* w0 = reinterpret_cast<const float*>(w0_.data());
  float* cur = reinterpret_cast<float*>(cur_.data());
  const float* ph = reinterpret_cast<const float*>(phase_.data());
#pragma omp parallel for schedule(static) if (n >= 256)
  for (int r = 0; r < n; ++r) {
    const std::size_t o = 2 * static_cast<std::size_t>(r) * n;
    const float* w = w0 + o;
    float* out = cur + o;
    const float* p = ph + 2 * static_cast<std::size_t>(r <= h ? r : n - r) * q;
#pragma omp simd
    for (int c = 0; c <= h; ++c) {
      const float a = w[2 * c], b = w[2 * c + 1], x = p[2 * c], y = p[2 * c + 1];
      out[2 * c] = a * x - b * y;
      out[2 * c + 1] = a * y + b * x;
    }
#pragma omp simd
    for (int c = h + 1; c < n; ++c) {
      const int j = n - c;
      const float a = w[2 * c], b = w[2 * c + 1], x = p[2 * j], y = p[2 * j + 1];
      out[2 * c] = a * x - b * y;
      out[2 * c + 1] = a * y + b * x;
    }
  }
  return cur_.data();
}

void WindSea::spectrum_at(double t, cfloat* out) const {
  const long long total = static_cast<long long>(w0_.size());
  const cfloat* w0 = w0_.data();
  const double* om = omega_.data();
#pragma omp parallel for schedule(static) if (total > 65536)
  for (long long m = 0; m < total; ++m) {
    if (w0[m] == cfloat(0.0f, 0.0f)) {
      out[m] = cfloat(0.0f, 0.0f);
      continue;
    }
    out[m] = cfloat(std::complex<double>(w0[m]) * std::exp(std::complex<double>(0.0, -om[m] * t)));
  }
}

}  // namespace huygens
