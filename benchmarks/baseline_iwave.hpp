#pragma once
// Baseline for the Huygens core: iWave (Tessendorf 2004, "Interactive Water Surfaces", Game
// Programming Gems 4), a local convolution approximating deep-water gravity dispersion.
// Linear deep-water gravity waves obey eta_tt = -g sqrt(-lap) eta (omega^2 = g k). iWave
// replaces the vertical-derivative operator sqrt(-lap) by a 13 x 13 convolution kernel G
// (P = 6 cells each way) built from its Hankel representation with a Gaussian taper:
//   G(r) = (dq / 2 pi) sum_{n=1}^{10000} q_n^2 exp(-sigma q_n^2) J0(q_n r),   q_n = n dq, dq = 0.001,
// r in cells, sigma = 1 cell^2, so that the symbol of G is about k exp(-sigma k^2) (k in rad/cell),
// and (G * eta) / dx ~ sqrt(-lap) eta. Tessendorf normalises G(0,0) = 1 (G0 = sum q_n^2
// exp(-sigma q_n^2)) and absorbs the scale into his gravity constant; we keep the physical scale
// (dq / 2 pi) so that omega^2 ~ g k for long waves. Truncation to 13 x 13 leaves sum G != 0
// (Tessendorf's kernel: the k = 0 mode oscillates at omega^2 = g sum G / dx); the `zero_sum` option
// subtracts the sum from G(0,0), which makes long waves worse (the far tail of the exact kernel,
// -1/(2 pi r^3), carries most of the symbol |k| for wavelengths beyond the kernel) and the symbol
// negative near k dx = pi/2 (exponential growth): off by default, kept for the comparison table.
// Update (his eq. with damping alpha, leapfrog in time):
//   eta^{n+1} = [eta^n (2 - alpha dt) - eta^{n-1} - g dt^2 (G * eta^n) / dx] / (1 + alpha dt).
// Stable for g dt^2 max_k Ghat(k) / dx <= 4 (refused otherwise). Gravity only: no surface tension.
#include <span>
#include <string>
#include <vector>

#include "huygens/common/fft.hpp"

namespace huygens::bench {

/// Parameters of iWave (fixed at construction).
struct IwaveParams {
  /// Cells per side N (unit: cells); >= 13.
  int n = 256;
  /// Side length L of the periodic grid (unit: m).
  double length_m = 8.0;
  /// Time step (unit: s).
  double dt = 1.0 / 60.0;
  /// Gravitational acceleration (unit: m/s^2).
  double gravity = 9.81;
  /// Damping alpha (unit: 1/s); 0 for the accuracy comparisons.
  double damping = 0.0;
  /// Kernel half width P (unit: cells); 6 gives Tessendorf's 13 x 13.
  int half = 6;
  /// Gaussian taper sigma of the kernel (unit: cell^2).
  double taper = 1.0;
  /// Subtract sum G from G(0,0) so that the k = 0 mode is still (unit: bool); not Tessendorf's.
  bool zero_sum = false;
};

/// The (2P+1)^2 kernel, row-major, in cells (symbol ~ k exp(-taper k^2), k in rad/cell).
std::vector<double> iwave_kernel(const IwaveParams& p);
/// Symbol of the kernel along x at k (unit: rad/cell): sum G(i, j) cos(k i).
double iwave_symbol(const std::vector<double>& kernel, int half, double k_cells);
/// Why `p` cannot be used (stability limit included), or empty.
std::string iwave_params_error(const IwaveParams& p);

class IwaveSolver {
 public:
  explicit IwaveSolver(const IwaveParams& p);
  /// Sets eta(0) and eta_t(0) (N*N values each, rows = y; unit: m, m/s).
  void init(std::span<const float> eta0, std::span<const float> etadot0);
  void step();
  std::span<const float> eta() const { return cur_.span(); }
  double time() const { return t_; }

 private:
  void convolve(const float* in, float* out);  // out = G * in (periodic)

  IwaveParams p_;
  double t_ = 0;
  std::vector<float> g_;  // kernel
  AlignedBuffer<float> prev_, cur_, next_, pad_, conv_;
};

}  // namespace huygens::bench
