#include "huygens/spectral/cutoff.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "huygens/common/dispersion.hpp"
#include "huygens/spectral/propagator.hpp"

namespace huygens {

void fill_cutoff_window(const HuygensParams& p, float* h) {
  const int n = p.n, m = p.margin;
  // K steps of (h h)^(dt/tau) (or of the paper's h h, tau = dt) in one go: the factors of the K
  // skipped cutoffs multiply, (h h)^(K dt/tau); exact for a field that does not move in K dt
  const double e = (p.cutoff_time_s > 0 ? p.dt_s / p.cutoff_time_s : 1.0) * std::max(1, p.round_trip_every);
  for (int i = 0; i < n; ++i) {
    double w = 1.0;
    if (p.absorber == Absorber::paper_quadratic) {
      if (i < m)
        w = 1.0 - std::pow(static_cast<double>(i) / m - 1.0, 2);
      else if (i >= n - m)
        w = 1.0 - std::pow(static_cast<double>(n - 1 - i) / m - 1.0, 2);
    }
    if (e != 1.0) w = std::pow(w, e);
    h[2 * static_cast<std::size_t>(i)] = h[2 * static_cast<std::size_t>(i) + 1] = static_cast<float>(w);
  }
}

void apply_cutoff_rows(float* z, const float* h, int n, int margin, std::ptrdiff_t row0, std::ptrdiff_t rows) {
  const int m = margin;
#pragma omp parallel for schedule(static) if (n >= 256)
  for (std::ptrdiff_t lr = 0; lr < rows; ++lr) {
    const std::ptrdiff_t r = row0 + lr;
    float* row = z + 2 * static_cast<std::size_t>(lr) * n;
    const float hr = h[2 * r];
    if (r < m || r >= n - m) {
#pragma omp simd
      for (int c = 0; c < 2 * n; ++c) row[c] *= hr * h[c];
    } else {
#pragma omp simd
      for (int c = 0; c < 2 * m; ++c) row[c] *= h[c];
#pragma omp simd
      for (int c = 2 * (n - m); c < 2 * n; ++c) row[c] *= h[c];
    }
  }
}

int auto_round_trip_every(const HuygensParams& p) {
  if (p.absorber == Absorber::off || p.margin < 1) return 1;
  // the fastest group speed on the grid's wavenumbers (deep water: the longest wave; with
  // surface tension or finite depth the maximum may lie elsewhere, so scan |k| = j dk)
  const double dk = 2.0 * std::numbers::pi / p.length_m, h = 1e-4;
  double cmax = 0.0;
  const int jmax = static_cast<int>(std::ceil(0.5 * std::sqrt(2.0) * p.n));
  for (int j = 1; j <= jmax; ++j) {
    const double k = j * dk;
    cmax = std::max(cmax, (omega(p.water, k * (1 + h)) - omega(p.water, k * (1 - h))) / (2 * h * k));
  }
  if (!(cmax > 0)) return 1;
  const double t_cross = p.margin * p.length_m / p.n / cmax;
  const double k = std::floor(t_cross / (4.0 * p.dt_s));
  return static_cast<int>(std::clamp(k, 1.0, 8.0));
}

}  // namespace huygens
