#pragma once
// Paper 004's margin cutoff (section 3): after each propagation the field is multiplied by
//   h(p) h(q),  h(i) = 1 - (d/M - 1)^2  for d = min(i, N-1-i) < M cells, else 1,
// so waves reaching the M-cell margin fade instead of wrapping round the periodic grid. With a
// time constant tau > 0 the factor is (h(p) h(q))^(dt/tau): one paper cutoff per tau seconds
// whatever dt. Applied by HuygensPropagator to the rows its layout holds (rows row0 ...).
#include <cstddef>

namespace huygens {

struct HuygensParams;

/// Fills h[0 .. 2N) with h(i)^e stored twice per cell, interleaved like a complex field (re, im),
/// e = K dt / tau (K = p.round_trip_every; tau = dt when cutoff_time_s = 0): the cutoff of the K
/// steps between two round trips at once; all ones without the paper's absorber.
void fill_cutoff_window(const HuygensParams& p, float* h);

/// The round trip every K steps a scene gets by default (grid.round_trip_every = 0):
///   K = clamp(floor(t_cross / (4 dt)), 1, 8),  t_cross = M dx / c_max,
/// t_cross the time the fastest wave of the grid (c_max, the largest group speed d omega/dk over
/// k = j 2 pi/L, j = 1 .. N/2 sqrt 2) needs to cross the margin of M cells: between two cutoffs no
/// wave moves more than a quarter of the margin. 1 without the cutoff.
int auto_round_trip_every(const HuygensParams& p);

/// Z(r, c) *= h(r) h(c) for the global rows r = row0 ... row0 + rows - 1 of an N-wide complex
/// field z (interleaved re, im) that holds those rows from its start; h from fill_cutoff_window.
/// Rows outside both margins touch only their 2 M margin cells.
void apply_cutoff_rows(float* z, const float* h, int n, int margin, std::ptrdiff_t row0, std::ptrdiff_t rows);

}  // namespace huygens
