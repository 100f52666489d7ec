#include "huygens/spectral/cutoff.hpp"

#include <cmath>

#include "huygens/spectral/propagator.hpp"

namespace huygens {

void fill_cutoff_window(const HuygensParams& p, float* h) {
  const int n = p.n, m = p.margin;
  for (int i = 0; i < n; ++i) {
    double w = 1.0;
    if (p.absorber == Absorber::paper_quadratic) {
      if (i < m)
        w = 1.0 - std::pow(static_cast<double>(i) / m - 1.0, 2);
      else if (i >= n - m)
        w = 1.0 - std::pow(static_cast<double>(n - 1 - i) / m - 1.0, 2);
    }
    if (p.cutoff_time_s > 0) w = std::pow(w, p.dt_s / p.cutoff_time_s);
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

}  // namespace huygens
