#pragma once
// Displayed height from the wave field Z (velocity potential, m^2/s), paper 004 eq. 3
// (docs/design.md 3.4, docs/ocean.md). For one mode Z = a e^{i theta} eq. 3 reads
//   eta = i k/omega a e^{i theta} - a^2 k^3 / (2 omega^2) e^{2 i theta};  for any field:
//   eta1 = Re IFFT[i k/omega Z^],     etadot1 = Re IFFT[k Z^],
//   chi  = IFFT[i k^{3/2} / (sqrt(2) omega) Z^],   chidot = IFFT[k^{3/2}/sqrt(2) Z^],
//   eta = eta1 + Re(chi^2) (m),       etadot = etadot1 + Re(2 chi chidot) (m/s).
// Exact for progressive waves (deep water: A cos theta + (k A^2 / 2) cos 2 theta); a standing
// pattern gets a spurious mean term (docs/ocean.md). First order packs eta1 + i etadot1 into one
// inverse N x N transform; second order adds chi and chidot: 3 transforms, one pass over Z^.
// On a slab (grid_layout.hpp; docs/scale.md) Z^(-k) lies on another rank, so eta1 and etadot1
// are formed apart (stokes_split.cpp): as beta = (k - k/omega)/2 depends on |k| only,
//   IFFT[beta conj Y(-k)](x) = conj(IFFT[beta Y](x)),  so  eta1 = -Im IFFT[(k/omega) Y],
//   etadot1 = Re IFFT[k Y]: 2 transforms at first order, 4 at second, no exchange of mirrored rows.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "huygens/common/dispersion.hpp"
#include "huygens/common/fft.hpp"
#include "huygens/spectral/grid_layout.hpp"
#include "huygens/spectral/wind.hpp"

namespace huygens {

/// The height stage: preallocated buffers and one planned inverse N x N transform.
class StokesHeight {
 public:
  /// n x n grid of side length_m; second_order = false gives first order at 1 transform.
  /// Outputs cover the visible region: rows and columns [margin, n - margin).
  StokesHeight(const Water& water, int n, double length_m, bool second_order, PlanEffort effort = PlanEffort::measure,
               int margin = 0);
  /// The same on a layout: outputs cover the layout's visible rows (GridLayout::visible), v = n -
  /// 2 margin values each; on a slab the split form (2 or 4 transforms, collective).
  StokesHeight(const Water& water, double length_m, bool second_order, const GridLayout& layout, int margin);

  /// Height eta (unit: m) and its rate etadot (unit: m/s), (n - 2 margin)^2 row-major, from the
  /// spectrum Y^ = zscale * zhat + extra (FFTW order; extra may be null). With zhat the
  /// unnormalised forward FFT of the spatial field, zscale = 1/N^2; `extra` (e.g. the wind
  /// sea) is already normalised (its unnormalised inverse FFT is the physical field).
  /// No allocation; transforms_per_call() inverse transforms. Returns false when an output
  /// value is not finite (fused test; the caller raises NonFiniteError naming this stage).
  bool compute(const cfloat* zhat, float zscale, const cfloat* extra, float* eta, float* etadot);
  /// The same with the wind sea as `extra`: its W^(0) P (wind.hpp) is formed inside this
  /// stage's pass over the spectrum, so the sea is read once and never written.
  bool compute(const cfloat* zhat, float zscale, const WindSea& wind, float* eta, float* etadot);

  bool second_order() const { return second_; }
  int transforms_per_call() const { return split_ ? (second_ ? 4 : 2) : (second_ ? 3 : 1); }
  /// Bytes sent to other ranks by one compute() (unit: bytes; 0 on one process).
  std::uint64_t sent_bytes_per_call() const { return transforms_per_call() * inverse_->sent_bytes(); }
  int n() const { return n_; }
  /// Side of the output region (n - 2 margin).
  int visible() const { return n_ - 2 * m_; }
  std::size_t bytes() const;
  /// Wall time spent inside FFTW executions by compute(), summed (unit: ns).
  std::uint64_t fft_ns() const { return fft_ns_; }
  /// Runs the transforms compute() performs (the same plan on the same buffers) and nothing
  /// else: the benchmark's baseline. Overwrites the internal buffers.
  void raw_transforms();

 private:
  bool run(const cfloat* zhat, float zscale, const cfloat* extra, const cfloat* extra_phase, float* eta, float* etadot);
  /// The pass over the spectrum Y^ = zscale Z^ + W^ (interleaved floats; extra null without a
  /// sea, phase the quadrant P when the sea is W^(0) P): writes the transform inputs X, chi^, chidot^.
  void fill_inputs(const float* z, float zscale, const float* extra, const float* phase);
  /// The visible region of the transform outputs into eta, etadot; false when one is not finite.
  bool extract_first_order(float* eta, float* etadot) const;
  bool extract_second_order(float* eta, float* etadot) const;
  /// The slab form: U^ = m Y into x_, V^ = k Y into b_ (and chi^, chidot^) on the layout's rows.
  void fill_split(const float* z, float zscale, const float* extra, const float* phase);
  /// eta = -Im U (+ Re chi^2), etadot = Re V (+ Re 2 chi chidot) on the visible rows held.
  bool extract_split(float* eta, float* etadot) const;

  int n_;
  int m_;
  bool second_;
  bool split_;       // a slab: the split form
  GridLayout g_;     // the rows held
  VisibleRows vis_;  // the visible rows held
  int threads_;      // scratch rows exist for this many threads
  // per-mode tables on one quadrant (N/2+1)^2, index (|row index|, |col index|): they depend on |k| only
  AlignedBuffer<float> k_;        // |k| (unit: rad/m)
  AlignedBuffer<float> kw_;       // k / omega, 0 at k = 0 (unit: s/m)
  AlignedBuffer<float> sq_;       // sqrt(k / 2) (unit: (rad/m)^{1/2}; second order only)
  AlignedBuffer<float> scratch_;  // per thread: 11 N floats of row scratch (L1-resident)
  AlignedBuffer<cfloat> x_;       // packed eta1 + i etadot1 (split: U = IFFT[m Y])
  AlignedBuffer<cfloat> b_;       // split only: V = IFFT[k Y]
  AlignedBuffer<cfloat> chi_;     // chi (second order only)
  AlignedBuffer<cfloat> chid_;    // chidot (second order only)
  std::unique_ptr<GridTransform> inverse_;
  std::uint64_t fft_ns_ = 0;
};

}  // namespace huygens
