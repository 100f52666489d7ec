#pragma once
// The slopes of the ambient wind sea alone (wind.hpp), first order, on its periodic n x n grid at
// any time t: what the sea looks like beyond the simulated region, where the solver has no grid
// (the viewer's open-ocean look continues the surface with it; docs/viz.md "The sea beyond").
// From paper 004 eq. 3 at first order, eta1 = Re IFFT[i k/omega Z^] with Z^ = W^(0) e^{-i omega t}:
//   (d eta1/dx)^ = i kx (i k/omega) Z^ = -kx k/omega Z^,   likewise y with ky.
// Re IFFT[A] = IFFT[(A(k) + conj A(-k)) / 2] (a real field), and both slopes are real, so one
// inverse transform of X(k) = (kx + i ky) D(k), D(k) = -(k/omega) (Z^(k) - conj Z^(-k)) / 2 gives
// d eta1/dx as its real part and d eta1/dy as its imaginary part.
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "huygens/common/dispersion.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/pipeline/render_info.hpp"
#include "huygens/spectral/wind.hpp"

namespace huygens {

class AmbientSlopes {
 public:
  /// The sea of `wind` on an n x n grid of side length_m (the solver's grid: the same modes, keyed
  /// by their signed indices, so the same sea).
  AmbientSlopes(const WindParams& wind, const Water& water, int n, double length_m,
                PlanEffort effort = PlanEffort::estimate);
  /// Slopes (d eta1/dx, d eta1/dy) at time t (unit: s) at grid point (row r = y, column c = x),
  /// interleaved, row-major: [2 (r n + c) + {0, 1}] (unit: 1), 2 n^2 floats: the transform's own
  /// output (real and imaginary parts), valid until the next call. No allocation.
  std::span<const float> compute(double t);
  /// Mean square slope |grad eta1|^2 over the grid (unit: 1), by Parseval from the modes at
  /// time t: sum over k of |k|^2 |D(k)|^2 (compute's X(k) = (kx + i ky) D(k)); with
  /// `central_differences`, of the slopes (eta(x + dx) - eta(x - dx)) / (2 dx) a grid resolves,
  /// |k|^2 replaced by (sin^2(kx dx) + sin^2(ky dx)) / dx^2. No allocation.
  double mean_square_slope(double t, bool central_differences) const;
  int n() const { return n_; }
  double length_m() const { return length_m_; }

 private:
  int n_;
  double length_m_;
  AlignedBuffer<cfloat> c_;      // -(k/omega) W^(0) per mode (FFTW order)
  std::vector<double> omega_;    // per mode (unit: rad/s)
  std::vector<float> kx_, ky_;   // per column / row (unit: rad/m)
  AlignedBuffer<cfloat> z_, x_;  // Z^(t) scaled by -k/omega, and the transform's input / output
  Fft2D fft_;
};

/// The far sea of a Huygens scene as the viewer reads it (RenderInfo::ambient_sea, FarSeaSlopes):
/// AmbientSlopes built on its first use, on the viewer's thread (its n^2 buffers and FFT plan are
/// taken only by a picture that draws the sea).
class AmbientSeaSlopes : public FarSeaSlopes {
 public:
  AmbientSeaSlopes(const WindParams& wind, const Water& water, int n, double length_m)
      : wind_(wind), water_(water), n_(n), length_m_(length_m) {}
  int n() const override { return n_; }
  double length_m() const override { return length_m_; }
  std::span<const float> compute(double t) override { return slopes().compute(t); }
  double mean_square_slope(bool central_differences) override {
    return slopes().mean_square_slope(0.0, central_differences);  // each mode's amplitude is constant
  }

 private:
  AmbientSlopes& slopes() {
    if (!slopes_) slopes_ = std::make_unique<AmbientSlopes>(wind_, water_, n_, length_m_);
    return *slopes_;
  }
  WindParams wind_;
  Water water_;
  int n_;
  double length_m_;
  std::unique_ptr<AmbientSlopes> slopes_;
};

}  // namespace huygens
