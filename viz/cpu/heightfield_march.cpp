#include "heightfield_march.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace huygens {

double BedField::at(glm::dvec2 p) const {
  const double u = std::clamp((p.x - x0) / dx, 0.0, static_cast<double>(cols - 1));
  const double v = std::clamp((p.y - y0) / dx, 0.0, static_cast<double>(rows - 1));
  const std::size_t j = std::min(static_cast<std::size_t>(u), cols > 1 ? cols - 2 : 0);
  const std::size_t i = std::min(static_cast<std::size_t>(v), rows > 1 ? rows - 2 : 0);
  const std::size_t j1 = std::min(j + 1, cols - 1), i1 = std::min(i + 1, rows - 1);
  const double fu = u - static_cast<double>(j), fv = v - static_cast<double>(i);
  const double a = z[i * cols + j], b = z[i * cols + j1], c = z[i1 * cols + j], d = z[i1 * cols + j1];
  return (1.0 - fv) * ((1.0 - fu) * a + fu * b) + fv * ((1.0 - fu) * c + fu * d);
}

namespace {

double height_above(const BedField& bed, const glm::dvec3& P, const glm::dvec3& t, double s) {
  const glm::dvec3 r = P + s * t;
  return r.z - bed.at(glm::dvec2(r));
}

// Where the ray crosses the grid lines of one axis (p + s dir = origin + k dx), s in (0, s_max).
void line_crossings(double p, double dir, double origin, double dx, double s_max, std::vector<double>& out) {
  if (dir == 0.0) return;
  const double a = (p - origin) / dx, b = (p + s_max * dir - origin) / dx;
  for (double k = std::ceil(std::min(a, b)); k <= std::floor(std::max(a, b)); k += 1.0) {
    const double s = (origin + k * dx - p) / dir;
    if (s > 0.0 && s < s_max) out.push_back(s);
  }
}

// Smallest root in [0, 1] of A + B u + C u^2 (A > 0), or -1.
double first_root(double A, double B, double C) {
  if (std::abs(C) <= 1e-14 * (std::abs(A) + std::abs(B))) return B < 0.0 && -A / B <= 1.0 ? -A / B : -1.0;
  const double disc = B * B - 4.0 * A * C;
  if (disc < 0.0) return -1.0;
  const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
  double best = -1.0;
  for (const double u : {q / C, q != 0.0 ? A / q : -1.0})
    if (u >= 0.0 && u <= 1.0 && (best < 0.0 || u < best)) best = u;
  return best;
}

}  // namespace

glm::dvec3 exact_bed_hit(const BedField& bed, const glm::dvec3& P, const glm::dvec3& t, double s_max) {
  std::vector<double> cuts{0.0, s_max};
  line_crossings(P.x, t.x, bed.x0, bed.dx, s_max, cuts);
  line_crossings(P.y, t.y, bed.y0, bed.dx, s_max, cuts);
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double s0 = cuts[k], s1 = cuts[k + 1];
    // h on the piece is the quadratic through its values at u = 0, 1/2, 1 (u = (s - s0) / (s1 - s0))
    const double h0 = height_above(bed, P, t, s0), hm = height_above(bed, P, t, 0.5 * (s0 + s1));
    const double h1 = height_above(bed, P, t, s1);
    if (h0 <= 0.0) return P + s0 * t;
    const double u = first_root(h0, 4.0 * hm - 3.0 * h0 - h1, 2.0 * h1 + 2.0 * h0 - 4.0 * hm);
    if (u >= 0.0) return P + (s0 + u * (s1 - s0)) * t;
  }
  return P + s_max * t;
}

glm::dvec3 shader_bed_hit(const BedField& bed, const glm::dvec3& P, const glm::dvec3& t, const BedMarch& m) {
  const glm::dvec2 g = (glm::dvec2(P) - glm::dvec2(bed.x0, bed.y0)) / bed.dx, dir = glm::dvec2(t) / bed.dx;
  const glm::dvec2 inv = 1.0 / glm::max(glm::abs(dir), glm::dvec2(1e-4));  // s per grid line crossed
  // s at the next grid line of each axis (the DDA of Amanatides & Woo)
  glm::dvec2 next = glm::mix(g - glm::ceil(g) + 1.0, glm::floor(g) + 1.0 - g, glm::step(0.0, dir)) * inv;
  double s0 = 0.0, h0 = height_above(bed, P, t, 0.0);
  if (h0 <= 0.0) return P;
  for (int k = 0; k < m.pieces; ++k) {
    const double s1 = std::min(next.x, next.y);
    next += inv * glm::dvec2(next.x == s1 ? 1.0 : 0.0, next.y == s1 ? 1.0 : 0.0);
    const double hm = height_above(bed, P, t, 0.5 * (s0 + s1)), h1 = height_above(bed, P, t, s1);
    const double u = first_root(h0, 4.0 * hm - 3.0 * h0 - h1, 2.0 * h1 + 2.0 * h0 - 4.0 * hm);
    if (u >= 0.0) return P + (s0 + u * (s1 - s0)) * t;
    s0 = s1, h0 = h1;
  }
  return flat_bed_hit(bed, P + s0 * t, t);
}

glm::dvec3 flat_bed_hit(const BedField& bed, const glm::dvec3& P, const glm::dvec3& t) {
  return P + t * ((bed.at(glm::dvec2(P)) - P.z) / t.z);
}

}  // namespace huygens
