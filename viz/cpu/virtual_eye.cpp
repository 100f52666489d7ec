#include "virtual_eye.hpp"

#include <algorithm>
#include <cmath>

#include "refraction.hpp"

namespace huygens {

glm::dvec3 reflected_eye(const glm::dvec3& eye, double h) { return {eye.x, eye.y, 2.0 * h - eye.z}; }

glm::dvec3 nearest_waterline_point(const glm::dvec3& eye, const glm::dvec3& lo, const glm::dvec3& hi, double h) {
  const glm::dvec2 foot(eye), axis = 0.5 * (glm::dvec2(lo) + glm::dvec2(hi)), d = axis - foot;
  const bool inside = foot.x >= lo.x && foot.x <= hi.x && foot.y >= lo.y && foot.y <= hi.y;
  if (inside || glm::dot(d, d) == 0.0) return {inside ? foot : axis, h};
  // the segment foot -> axis enters the box's footprint at the largest of the slab entries
  double s = 0.0;
  for (int k = 0; k < 2; ++k)
    if (d[k] != 0.0) s = std::max(s, std::min((lo[k] - foot[k]) / d[k], (hi[k] - foot[k]) / d[k]));
  return {foot + std::clamp(s, 0.0, 1.0) * d, h};
}

glm::dvec3 refracted_eye(const glm::dvec3& eye, const glm::dvec3& a, double index) {
  const glm::dvec3 v = glm::normalize(a - eye), t = refract_dir(v, glm::dvec3(0.0, 0.0, 1.0), 1.0 / index);
  return a - glm::length(eye - a) * glm::normalize(t);
}

glm::dvec3 refracted_ray_through(const glm::dvec3& eye, const glm::dvec3& b, double h, double index) {
  const glm::dvec2 foot_b(b), foot_e(eye);
  auto t_at = [&](double u) {
    const glm::dvec3 q(foot_b + u * (foot_e - foot_b), h);
    return refract_dir(glm::normalize(q - eye), glm::dvec3(0.0, 0.0, 1.0), 1.0 / index);
  };
  // reach(u): the distance from q(u) to b's foot less how far the refracted ray from q(u) runs
  // horizontally down to b's depth: -run < 0 at b's foot, > 0 at the eye's foot (a vertical ray),
  // growing in between (q moves away from b while its view ray steepens); its root is bisected
  auto reach = [&](double u) {
    const glm::dvec3 t = t_at(u);
    const double run = glm::length(glm::dvec2(t)) * (h - b.z) / -t.z;
    return u * glm::length(foot_e - foot_b) - run;
  };
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 60; ++k) (reach(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
  return glm::normalize(t_at(0.5 * (lo + hi)));
}

}  // namespace huygens
