#pragma once
// A ray under the water meeting the ground heightfield (paper 001, Baboud & Decoret, "Realistic
// water volumes in real-time": the water volume between a ground heightfield and the surface,
// traced per pixel). The bed is given at the grid points (x0 + j dx, y0 + i dx) and read as the
// GPU's linear filter reads its R32F texture: bilinear between the four grid points around
// (x, y), clamped to the edge outside the grid (GL_CLAMP_TO_EDGE).
//
// exact_bed_hit: the first point of the ray R(s) = P + s t (s >= 0) with R_z(s) = b(R_xy(s)),
// exactly: the ray is cut where it crosses the grid lines x = x0 + j dx and y = y0 + i dx; within
// a piece the bilinear bed along the ray is a quadratic in s (u and v linear in s, their product
// quadratic), so h(s) = R_z(s) - b(R_xy(s)) is the quadratic through h at the piece's ends and
// middle, and its smallest root in the piece is solved in closed form.
//
// shader_bed_hit: the mirror of shaders/ground_common.glsl (march_bed): the same pieces, found
// in order along the ray by a grid traversal (Amanatides & Woo 1987: the next x line and the next
// y line, whichever comes first), samples at their ends and middles (at most 0.71 cell apart in
// xy), the first piece whose quadratic has a root in it gives the hit; at most `pieces` pieces,
// then the plane at the bed's height at the last sample (the rule before the march, from there
// on). Sampling alone, every half cell, misses the ray's short dips below the lip of a step one
// cell wide (a half-cell march was up to 24 cells off in xy for the rays of
// HeightfieldMarch.ExactHitOnAStepIsTheClosedForm that graze the lip); the lip is at a grid
// line, which this samples.
#include <cstddef>
#include <glm/glm.hpp>
#include <span>

namespace huygens {

/// The bed at the grid points (row-major, rows x cols), the grid's placement (m).
struct BedField {
  std::span<const float> z;
  std::size_t rows = 0, cols = 0;
  double dx = 1.0, x0 = 0.0, y0 = 0.0;
  /// Bilinear height at (x, y), clamped to the edge outside the grid (m).
  double at(glm::dvec2 p) const;
};

/// The march's parameters, as the shader has them.
struct BedMarch {
  /// Pieces of the ray (between grid lines) at most.
  int pieces = 128;
};

/// First point where the ray P + s t (t going down, s in [0, s_max]) meets the bed, exact; the
/// ray's point at s_max when it does not meet it before. P above the bed.
glm::dvec3 exact_bed_hit(const BedField& bed, const glm::dvec3& P, const glm::dvec3& t, double s_max);

/// The shader's march (shaders/ground_common.glsl, march_bed), in double precision.
glm::dvec3 shader_bed_hit(const BedField& bed, const glm::dvec3& P, const glm::dvec3& t, const BedMarch& m = {});

/// The rule before the march: the plane at the bed's height under P, b(P_xy).
glm::dvec3 flat_bed_hit(const BedField& bed, const glm::dvec3& P, const glm::dvec3& t);

}  // namespace huygens
