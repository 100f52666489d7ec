#include "footprints.hpp"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <limits>

namespace huygens {

std::vector<std::uint32_t> nearest_outside(std::vector<std::uint8_t> solid, std::size_t R, std::size_t C) {
  std::vector<std::uint32_t> from(R * C);
  std::vector<std::size_t> queue;
  for (std::size_t k = 0; k < R * C; ++k) {
    from[k] = static_cast<std::uint32_t>(k);
    if (!solid[k]) queue.push_back(k);
  }
  if (queue.empty()) return {};
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t k = queue[head], i = k / C, j = k % C;
    const std::size_t nb[4] = {i > 0 ? k - C : k, i + 1 < R ? k + C : k, j > 0 ? k - 1 : k, j + 1 < C ? k + 1 : k};
    for (std::size_t m : nb)
      if (solid[m]) {
        solid[m] = 0;
        from[m] = from[k];
        queue.push_back(m);
      }
  }
  return from;
}

void Footprints::build(const GridPlacement& g, std::span<const RenderObstacle> obstacles, float offset) {
  fill_from_.clear();
  mesh_top_.clear();
  mesh_from_.clear();
  mesh_outline_.clear();
  build_mesh_tops(g, obstacles, offset);
  if (std::any_of(obstacles.begin(), obstacles.end(),
                  [](const RenderObstacle& o) { return o.kind != RenderObstacle::Kind::mesh; }))
    build_fill(g, obstacles);
}

// Per grid point the highest z of the meshes above it (each triangle's plane over the grid points
// its xy projection covers, barycentric weights), the nearest point outside their footprints and
// the footprints' outline.
void Footprints::build_mesh_tops(const GridPlacement& g, std::span<const RenderObstacle> obstacles, float offset) {
  const std::size_t R = g.rows, C = g.cols;
  for (const RenderObstacle& o : obstacles) {
    if (o.kind != RenderObstacle::Kind::mesh) continue;
    if (mesh_top_.empty()) mesh_top_.assign(R * C, -std::numeric_limits<float>::infinity());
    const std::vector<float>& t = o.triangles_m;
    for (std::size_t k = 0; k + 9 <= t.size(); k += 9) {
      const glm::dvec3 a(t[k], t[k + 1], t[k + 2]), b(t[k + 3], t[k + 4], t[k + 5]), c(t[k + 6], t[k + 7], t[k + 8]);
      const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      if (std::abs(det) < 1e-12) continue;  // a vertical face covers no area seen from above
      for (std::size_t i = 0; i < R; ++i)
        for (std::size_t j = 0; j < C; ++j) {
          const double x = g.x(j), y = g.y(i);
          const double wb = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
          const double wc = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
          if (wb < 0.0 || wc < 0.0 || wb + wc > 1.0) continue;
          const double z = a.z + wb * (b.z - a.z) + wc * (c.z - a.z) - offset;
          mesh_top_[i * C + j] = std::max(mesh_top_[i * C + j], static_cast<float>(z));
        }
    }
  }
  if (mesh_top_.empty()) return;
  std::vector<std::uint8_t> footprint(R * C);
  for (std::size_t k = 0; k < R * C; ++k) footprint[k] = std::isfinite(mesh_top_[k]);
  mesh_from_ = nearest_outside(footprint, R, C);
  mesh_outline_.assign(R * C, 0);
  auto in = [&](std::size_t i, std::size_t j) { return std::isfinite(mesh_top_[i * C + j]); };
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t j = 0; j < C; ++j)
      mesh_outline_[i * C + j] = in(i, j) && (i == 0 || j == 0 || i + 1 == R || j + 1 == C || !in(i - 1, j) ||
                                              !in(i + 1, j) || !in(i, j - 1) || !in(i, j + 1));
}

// The grid points inside a box's or cylinder's footprint take the height of the nearest point
// outside all of them.
void Footprints::build_fill(const GridPlacement& g, std::span<const RenderObstacle> obstacles) {
  const std::size_t R = g.rows, C = g.cols;
  std::vector<std::uint8_t> solid(R * C, 0);
  for (std::size_t i = 0; i < R; ++i)
    for (std::size_t j = 0; j < C; ++j) {
      const double x = g.x(j), y = g.y(i);
      for (const RenderObstacle& o : obstacles) {
        if (o.kind == RenderObstacle::Kind::mesh) continue;  // the surface runs over it (mesh_top_)
        const bool in = o.kind == RenderObstacle::Kind::box
                            ? x >= o.min_m[0] && x <= o.max_m[0] && y >= o.min_m[1] && y <= o.max_m[1]
                            : std::hypot(x - o.centre_m[0], y - o.centre_m[1]) <= o.radius_m + 0.5 * g.dx;
        if (in) solid[i * C + j] = 1;
      }
    }
  fill_from_ = nearest_outside(solid, R, C);
}

void Footprints::apply(std::span<float> eta, double dx) const {
  if (!fill_from_.empty())
    for (std::size_t k = 0; k < eta.size(); ++k)
      if (fill_from_[k] != k) eta[k] = eta[fill_from_[k]];
  if (mesh_top_.empty() || mesh_from_.empty()) return;
  const float inset = static_cast<float>(0.25 * dx);
  for (std::size_t k = 0; k < eta.size(); ++k)
    eta[k] = std::max(eta[k], std::min(mesh_top_[k] - inset, eta[mesh_from_[k]]));
}

}  // namespace huygens
