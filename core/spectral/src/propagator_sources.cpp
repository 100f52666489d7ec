// The propagator's sources (propagator.hpp, paper 004 section 3; docs/huygens.md): elevations
// released from rest (Gaussian humps, drops) and progressive plane waves, on the layout's rows.
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "huygens/spectral/propagator.hpp"

namespace huygens {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr int kParallelMin = 256;  // grids below this run the passes on one thread
}  // namespace

std::uint64_t HuygensPropagator::reserve_sources() {
  // -omega/k factor and omega on the layout's spectrum rows (|k| is symmetric in kx, ky)
  if (src_.size()) return source_bytes();
  const int n = p_.n;
  src_ = AlignedBuffer<float>(g_.spectrum_size());
  omega_ = AlignedBuffer<float>(g_.spectrum_size());
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t lr = 0; lr < g_.krows; ++lr) {
    const double kr = wavenumber(g_.spectrum_row(lr));
    for (int c = 0; c < n; ++c) {
      const double k = std::hypot(wavenumber(c), kr);
      const double w = omega(p_.water, k);
      const std::size_t i = static_cast<std::size_t>(lr) * n + c;
      src_[i] = k > 0 ? static_cast<float>(w / k) : 0.0f;
      omega_[i] = static_cast<float>(w);
    }
  }
  return source_bytes();
}

void gaussian_axis_factors(cfloat* f, int n, double length_m, double x0_m, double sigma_m, double scale) {
  for (int i = 0; i < n; ++i) {
    const double k = fft_wavenumber(i, n, length_m);
    const double g = scale * std::exp(-0.5 * k * k * sigma_m * sigma_m);
    const double ph = -k * x0_m;
    f[i] = i == n / 2 ? cfloat(static_cast<float>(g * std::cos(ph)), 0.0f)
                      : cfloat(static_cast<float>(g * std::cos(ph)), static_cast<float>(g * std::sin(ph)));
  }
}

void add_gaussian_row(cfloat row, const cfloat* col, const float* w_over_k, const float* om, double age_s, cfloat* sc,
                      int n) {
  const float yr = row.real(), yi = row.imag();
  const float* fx = reinterpret_cast<const float*>(col);
  float* s = reinterpret_cast<float*>(sc);
  if (age_s == 0.0) {
#pragma omp simd
    for (int c = 0; c < n; ++c) {
      // e = fy fx; S += -i (omega/k) e
      const float er = yr * fx[2 * c] - yi * fx[2 * c + 1];
      const float ei = yr * fx[2 * c + 1] + yi * fx[2 * c];
      const float f = w_over_k[c];
      s[2 * c] += f * ei;
      s[2 * c + 1] -= f * er;
    }
    return;
  }
  const float age = static_cast<float>(age_s);
  for (int c = 0; c < n; ++c) {
    const float er = yr * fx[2 * c] - yi * fx[2 * c + 1];
    const float ei = yr * fx[2 * c + 1] + yi * fx[2 * c];
    const float f = w_over_k[c];
    // released age_s ago: the mode has turned by exp(-i omega age)
    const double ph = -static_cast<double>(om[c]) * age;
    const float cr = static_cast<float>(std::cos(ph)), ci = static_cast<float>(std::sin(ph));
    const float ar = f * ei, ai = -f * er;
    s[2 * c] += ar * cr - ai * ci;
    s[2 * c + 1] += ar * ci + ai * cr;
  }
}

void HuygensPropagator::add_gaussian(double x_m, double y_m, double sigma_m, double amplitude_m, double age_s) {
  reserve_sources();  // allocates only on first use (see the header)
  const int n = p_.n;
  const double d = dx();
  const double amp = 2.0 * kPi * sigma_m * sigma_m * amplitude_m / (d * d);
  gaussian_axis_factors(src_x_.data(), n, p_.length_m, x_m, sigma_m, 1.0);
  gaussian_axis_factors(src_y_.data(), n, p_.length_m, y_m, sigma_m, amp);
  // E^ is separable: a spectrum row's factor is fy (rows ky) or fx (transposed: rows kx)
  const cfloat* fr = (g_.transposed ? src_x_ : src_y_).data();
  const cfloat* fc = (g_.transposed ? src_y_ : src_x_).data();
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (std::ptrdiff_t lr = 0; lr < g_.krows; ++lr) {
    const std::size_t o = static_cast<std::size_t>(lr) * n;
    add_gaussian_row(fr[g_.spectrum_row(lr)], fc, src_.data() + o, omega_.data() + o, age_s, s_.data() + o, n);
  }
}

void HuygensPropagator::add_plane_wave(double wavelength_m, double amplitude_m, double direction_deg) {
  // Z = -i a e^{i k.x} on the layout's spatial rows, one forward transform, added to Z^
  const int n = p_.n;
  const double k0 = 2.0 * kPi / wavelength_m;
  const double th = direction_deg * kPi / 180.0;
  const double kx = k0 * std::cos(th), ky = k0 * std::sin(th);
  const double a = omega(p_.water, k0) / k0 * amplitude_m;
  const double d = dx();
  // scratch for the plane wave: the packed-height buffer, or a temporary one without it
  // (construction time only, never inside a step)
  AlignedBuffer<cfloat> tmp;
  if (h_.size() == 0) tmp = AlignedBuffer<cfloat>(z_.size());
  cfloat* hb = h_.size() ? h_.data() : tmp.data();
  for (std::ptrdiff_t lr = 0; lr < g_.rows; ++lr)
    for (int c = 0; c < n; ++c) {
      const double ph = kx * c * d + ky * static_cast<double>(g_.row0 + lr) * d;
      hb[static_cast<std::size_t>(lr) * n + c] =
          cfloat(static_cast<float>(a * std::sin(ph)), static_cast<float>(-a * std::cos(ph)));
    }
  if (!fwd_) fwd_ = g_.make_transform(z_.data(), s_.data(), Fft2D::forward);
  fwd_->execute(hb, z_.data());
  const std::size_t m = g_.spectrum_size();
  for (std::size_t i = 0; i < m; ++i) s_[i] += z_[i];
}

}  // namespace huygens
