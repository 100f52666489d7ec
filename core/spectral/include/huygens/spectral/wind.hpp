#pragma once
// Wind sea (paper 004 section 3: a pseudo-random spectrum added in the Fourier domain;
// docs/design.md 3.3, docs/ocean.md). JONSWAP (Hasselmann et al. 1973):
//   S(omega) = alpha g^2 omega^-5 exp(-5/4 (omega_p/omega)^4) gamma^exp(-(omega-omega_p)^2/(2 s^2 omega_p^2)),
//   s = 0.07 (omega <= omega_p) or 0.09; x = g F / U^2 (at most 1.7e4, the developed sea);
//   omega_p = 22 (g/U) x^(-1/3),  alpha = 0.076 x^(-0.22),  gamma = 3.3;
// direction D(theta) = (2/pi) cos^2(theta - theta_w) downwind only; wavenumber density
// F(kx, ky) = S(omega(k)) D(theta) c_g(k) / k (m^4). A grid mode gets elevation amplitude
// sqrt(2 F dk^2) (m) times a unit complex Gaussian keyed by (seed, mode): same seed, same sea.
// The sea is ambient: W^(k, t) = W^(k, 0) e^{-i omega t} is superposed on the solver's spectrum
// when heights are made, neither absorbed nor decaying, at no N x N transform.
#include <cstdint>
#include <vector>

#include "huygens/common/dispersion.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/common/scene.hpp"

namespace huygens {

/// The scene's `wind` block.
struct WindParams {
  /// Wind speed at 10 m height (unit: m/s); 0 gives a calm sea.
  double speed_mps = 5.0;
  /// Direction the wind blows towards, from +x towards +y (unit: degrees).
  double direction_deg = 0.0;
  /// Seed of the pseudo-random amplitudes and phases (unit: 1).
  std::uint64_t seed = 1;
  /// Fetch, the distance over which the wind has blown (unit: m).
  double fetch_m = 10000.0;
  /// JONSWAP peak enhancement gamma (unit: 1; 1 gives Pierson-Moskowitz's shape).
  double gamma = 3.3;
};

/// Reads the `wind` block: speed_mps, direction_deg, seed (required) and fetch_m, gamma.
WindParams parse_wind(const JsonIn& j);

/// Peak angular frequency omega_p (unit: rad/s).
double jonswap_peak(const WindParams& p, const Water& w);
/// Phillips' constant alpha of the fetch (unit: 1).
double jonswap_alpha(const WindParams& p, const Water& w);
/// Frequency spectrum S(omega) (unit: m^2 s).
double jonswap(const WindParams& p, const Water& w, double om);
/// Wavenumber-plane density F(kx, ky) = S(omega) D(theta) c_g / k (unit: m^4).
double wind_density(const WindParams& p, const Water& w, double kx, double ky);

/// Rows of the spectrum a slab rank holds (slab_fft.hpp): indices [row0, row0 + count) of kx
/// (transposed layout) or of ky (normal layout).
struct WindRows {
  int row0 = 0;
  int count = 0;
  bool transposed = true;
};

/// The ambient wind sea on an n x n grid of side length_m, advanced by steps of dt.
class WindSea {
 public:
  WindSea(const WindParams& p, const Water& w, int n, double length_m, double dt);
  /// The sea of a slab rank: base() holds only `rows` of the spectrum (transposed: row = kx
  /// index, column = ky index; normal: row = ky, column = kx), count x n values; omega is kept on the quadrant only.
  /// spectrum() and spectrum_at() are for the whole grid (the one-process constructor) only; grid_variance() sums this
  /// rank's modes.
  WindSea(const WindParams& p, const Water& w, int n, double length_m, double dt, WindRows rows);

  /// W^(t) for the current time (FFTW order; an unnormalised inverse FFT gives the spatial
  /// wave field in m^2/s): pass as StokesHeight::compute's `extra`. It starts at t = 0; after
  /// the solver's step to t + dt call advance() first, so both describe the same time.
  /// The sea is stored as W^(k, 0) and a phase table P(|k|, t) = e^{-i omega t} on one quadrant
  /// (omega depends on |k| only): W^(t) = W^(0) P. This call writes the product into a buffer
  /// the first time it is asked for after an advance() (one pass; the buffer, N^2 complex, is
  /// allocated by the first call: not inside a solver step); the height stage reads
  /// W^(0) and P directly instead (StokesHeight::compute(..., const WindSea&, ...)), so that a
  /// step with wind moves N^2 complex values of the sea once (a read) instead of three times.
  const cfloat* spectrum() const;
  /// Advances the sea by one step dt: P <- P e^{-i omega dt} on the quadrant ((N/2+1)^2 complex
  /// multiplies); every 256 steps P is recomputed exactly from t, so rounding cannot drift.
  void advance();
  /// Current time (unit: s).
  double time() const { return steps_ * dt_; }
  /// Exact W^(t) for any t into out (n x n; for tests and resets).
  void spectrum_at(double t, cfloat* out) const;
  /// Expected elevation variance of the grid's modes, sum F dk^2 (unit: m^2).
  double grid_variance() const { return variance_; }
  std::size_t bytes() const {
    return (w0_.size() + cur_.size() + step_.size() + phase_.size()) * sizeof(cfloat) + omega_.size() * sizeof(double);
  }

  // ---- the representation (for StokesHeight::compute) ------------------------------------------
  /// W^(k, 0), n x n, FFTW order.
  const cfloat* base() const { return w0_.data(); }
  /// P = e^{-i omega(k) t} at time(), on the quadrant of FFT indices (r, c) in [0, N/2]^2, row
  /// length N/2 + 1: the value of every mode (+-r, +-c).
  const cfloat* phase_quadrant() const { return phase_.data(); }

 private:
  /// Fills w0_[m] for the mode of FFT indices (column c = kx, row r = ky); returns its omega.
  double fill_mode(const WindParams& p, const Water& w, double dk, int c, int r, std::size_t m);
  void init_phase(const Water& w, double dk);

  int n_;
  double dt_;
  int omega_stride_ = n_;  // row length of omega_ (n, or N/2 + 1 when it holds the quadrant only)
  long long steps_ = 0;
  double variance_ = 0;
  std::vector<double> omega_;  // per mode (unit: rad/s)
  AlignedBuffer<cfloat> w0_;
  AlignedBuffer<cfloat> step_;         // e^{-i omega dt}, one quadrant
  AlignedBuffer<cfloat> phase_;        // e^{-i omega t}, one quadrant
  mutable AlignedBuffer<cfloat> cur_;  // W^(t) = W^(0) P, made by the first spectrum() call, rewritten when stale
  mutable bool cur_valid_ = false;
};

}  // namespace huygens
