#pragma once
// Orbit camera of the visualizer: looks at `target` from `distance` along the direction
// given by yaw (about +z, from +x) and pitch (elevation above the water plane).
// Orthographic mode (for the render tests) uses the same direction with parallel rays.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <span>

#include "refraction.hpp"

namespace huygens {

struct OrbitCamera {
  /// Point looked at (unit: m).
  glm::dvec3 target{0.0, 0.0, 0.0};
  /// Distance from target to eye (unit: m).
  double distance = 10.0;
  /// Heading of the eye around the target, from +x toward +y (unit: rad).
  double yaw = -1.5707963267948966;
  /// Elevation of the eye above the horizontal (unit: rad); pi/2 looks straight down.
  double pitch = 0.9;
  /// Vertical field of view of the perspective camera (unit: rad).
  double fov_y = 0.7853981633974483;
  /// Orthographic camera: parallel rays, `ortho_height` metres visible vertically.
  bool ortho = false;
  /// Height of the orthographic view volume (unit: m).
  double ortho_height = 10.0;
  /// Near and far planes (unit: m).
  double z_near = 0.05, z_far = 500.0;

  glm::dvec3 forward() const {
    return -glm::dvec3(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch));
  }
  glm::dvec3 eye() const { return target - distance * forward(); }
  glm::dvec3 up_hint() const {
    // straight down: use +y as screen-up so the image rows follow the grid rows
    return std::abs(std::sin(pitch)) > 0.9999 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
  }
  glm::dmat4 view() const { return glm::lookAt(eye(), target, up_hint()); }
  glm::dmat4 projection(double aspect) const {
    if (ortho) {
      const double h = 0.5 * ortho_height, w = h * aspect;
      return glm::ortho(-w, w, -h, h, z_near, std::max(z_far, 10.0 * distance));
    }
    return glm::perspective(fov_y, aspect, z_near, std::max(z_far, 10.0 * distance));
  }
  ViewRays rays() const {
    ViewRays r;
    r.eye = eye();
    r.ortho = ortho;
    r.dir = forward();
    return r;
  }
  /// World ray (origin, unit direction) through normalised device coordinates (x, y) in [-1, 1].
  void ray_through(double ndc_x, double ndc_y, double aspect, glm::dvec3& origin, glm::dvec3& dir) const {
    const glm::dmat4 inv = glm::inverse(projection(aspect) * view());
    glm::dvec4 a = inv * glm::dvec4(ndc_x, ndc_y, -1.0, 1.0);
    glm::dvec4 b = inv * glm::dvec4(ndc_x, ndc_y, 1.0, 1.0);
    a /= a.w;
    b /= b.w;
    origin = glm::dvec3(a);
    dir = glm::normalize(glm::dvec3(b) - glm::dvec3(a));
  }
};

/// The smallest distance from `camera.target` (direction and field of view kept) at which every
/// point of `points` projects within `ndc_limit` of the image's centre (|x| and |y| in normalised
/// device coordinates, image aspect `aspect`). Backing away along the view axis moves every point
/// in front of the eye toward the centre (x_ndc = x_view / (z_view tan(fov_y / 2) aspect), z_view
/// growing), so "all inside" is monotone in the distance: bisection.
inline double frame_distance(OrbitCamera camera, std::span<const glm::dvec3> points, double aspect, double ndc_limit) {
  auto fits = [&](double d) {
    camera.distance = d;
    const glm::dmat4 m = camera.projection(aspect) * camera.view();
    for (const glm::dvec3& q : points) {
      const glm::dvec4 p = m * glm::dvec4(q, 1.0);
      if (p.w <= 0.0 || std::abs(p.x) > ndc_limit * p.w || std::abs(p.y) > ndc_limit * p.w) return false;
    }
    return true;
  };
  double lo = 0.0, hi = 1e-3;
  for (int k = 0; k < 80 && !fits(hi); ++k) lo = hi, hi *= 2.0;
  for (int k = 0; k < 60; ++k) (fits(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  return hi;
}

/// The start-up view of a visible region `width` x `height` metres whose corner is at
/// (x0, y0): from the south, 50 degrees above the horizon, the whole region in view.
inline OrbitCamera default_camera(double x0, double y0, double width, double height) {
  OrbitCamera c;
  c.target = glm::dvec3(x0 + 0.5 * width, y0 + 0.5 * height, 0.0);
  c.distance = 1.25 * std::max(width, height);
  c.pitch = 50.0 * 3.14159265358979323846 / 180.0;
  c.yaw = -3.14159265358979323846 / 2.0;
  c.z_far = 20.0 * c.distance;
  return c;
}

}  // namespace huygens
