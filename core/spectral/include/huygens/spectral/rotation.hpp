#pragma once
// The per-mode phase factor exp(i phi), phi = -omega(k) dt, of the Huygens step (paper 004
// section 3, eq. 1; docs/huygens.md), used by HuygensPropagator on every layout: its
// table entries (one quadrant of |k|) and the rotation of one spectrum row by them. With phi
// reduced to [-pi, pi] and s the 1/N^2 of the FFT round trip (or 1):
//   complex  a = s cos phi, b = s sin phi:  (x, y) <- (a x - b y, a y + b x)
//   lifting  a = t = tan(phi'/2), b = 2 sin^2(phi'/2) / t, c = sign s, where phi' = phi -+ pi and
//            sign = -1 when |phi| > pi/2 (a rotation by pi is an exact sign flip):
//            (x, y) <- c (x, y); x -= t y; y += b x; x -= t y (three shears of determinant 1, so
//            |Z^| cannot drift in float; b is chosen so that cos(angle) = 1 - b t holds exactly for
//            the rounded t)

namespace huygens {

/// How the per-mode phase factor exp(-i omega dt) is applied.
enum class Rotation { lifting, complex };

/// One mode's table entries (see above; c is used by the lifting only).
struct RotationEntry {
  float a, b, c;
};

/// The entries for phase -omega_dt (rad) and scale s.
RotationEntry rotation_entry(Rotation kind, double omega_dt, double scale);

/// Rotates one row of N complex values (interleaved floats, sr -> zr, which may be the same
/// array) by the quadrant table rows a, b, c: column j reads entry j for j <= N/2, else N - j.
/// `scale` multiplies the entries' scale s (c for the lifting, a and b for complex); a power of
/// two (1/N^2) gives the same bits as a table made with that scale.
void rotate_row(Rotation kind, const float* a, const float* b, const float* c, const float* sr, float* zr, int n,
                float scale = 1.0f);

}  // namespace huygens
