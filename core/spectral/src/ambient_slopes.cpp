// The ambient sea's slopes at any time: formulas in ambient_slopes.hpp.
#include "huygens/spectral/ambient_slopes.hpp"

#include <cmath>
#include <complex>
#include <stdexcept>

namespace huygens {

AmbientSlopes::AmbientSlopes(const WindParams& wind, const Water& water, int n, double length_m, PlanEffort effort)
    : n_(n),
      length_m_(length_m),
      c_(static_cast<std::size_t>(n) * n),
      omega_(static_cast<std::size_t>(n) * n),
      kx_(n),
      ky_(n),
      z_(static_cast<std::size_t>(n) * n),
      x_(static_cast<std::size_t>(n) * n),
      fft_(n, n, x_.data(), x_.data(), Fft2D::backward, effort) {
  if (n < 2 || n % 2 != 0 || !(length_m > 0)) throw std::invalid_argument("AmbientSlopes: n even >= 2, length > 0");
  const WindSea sea(wind, water, n, length_m, 1.0);
  for (int i = 0; i < n; ++i) kx_[i] = ky_[i] = static_cast<float>(fft_wavenumber(i, n, length_m));
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const std::size_t m = static_cast<std::size_t>(r) * n + c;
      const double k = std::hypot(double(kx_[c]), double(ky_[r]));
      omega_[m] = omega(water, k);
      const cfloat w0 = sea.base()[m];
      c_[m] = omega_[m] > 0 ? cfloat(std::complex<double>(w0) * (-k / omega_[m])) : cfloat(0.0f, 0.0f);
    }
}

std::span<const float> AmbientSlopes::compute(double t) {
  const int n = n_;
  const long long total = static_cast<long long>(n) * n;
  // Z(k, t) -k/omega, in double for the phase omega t (t may be hours)
#pragma omp parallel for schedule(static) if (total > 65536)
  for (long long m = 0; m < total; ++m)
    z_[m] = c_[m] == cfloat(0.0f, 0.0f) ? c_[m] : cfloat(std::complex<double>(c_[m]) * std::polar(1.0, -omega_[m] * t));
    // X(k) = (kx + i ky) (Z(k) - conj Z(-k)) / 2, -k at index (n - r) mod n, (n - c) mod n
#pragma omp parallel for schedule(static) if (total > 65536)
  for (int r = 0; r < n; ++r) {
    const int rm = (n - r) % n;
    for (int c = 0; c < n; ++c) {
      const std::size_t m = static_cast<std::size_t>(r) * n + c;
      const cfloat d = 0.5f * (z_[m] - std::conj(z_[static_cast<std::size_t>(rm) * n + (n - c) % n]));
      x_[m] = cfloat(kx_[c], ky_[r]) * d;
    }
  }
  fft_.execute();
  // std::complex<float> is two floats, real then imaginary ([complex.numbers.general])
  return {reinterpret_cast<const float*>(x_.data()), 2 * static_cast<std::size_t>(total)};
}

double AmbientSlopes::mean_square_slope(double t, bool central_differences) const {
  const int n = n_;
  const double dx = length_m_ / n;
  const auto z = [&](std::size_t m) { return std::complex<double>(c_[m]) * std::polar(1.0, -omega_[m] * t); };
  const auto k2 = [&](double k) { return central_differences ? std::pow(std::sin(k * dx) / dx, 2) : k * k; };
  double sum = 0.0;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      const std::size_t m = static_cast<std::size_t>(r) * n + c,
                        mm = static_cast<std::size_t>((n - r) % n) * n + (n - c) % n;
      sum += (k2(kx_[c]) + k2(ky_[r])) * std::norm(0.5 * (z(m) - std::conj(z(mm))));
    }
  return sum;
}

}  // namespace huygens
