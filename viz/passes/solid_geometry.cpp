#include "solid_geometry.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace huygens {

void append_hull(const ShipPose& s, std::vector<float>& out) {
  constexpr int ns = 24, nz = 6;
  const double freeboard = hull_freeboard(s);
  const double ch = std::cos(s.heading), sh = std::sin(s.heading);
  auto world = [&](double lx, double ly, double z) {  // afloat: sheared onto the plane of float_ship
    out.push_back(static_cast<float>(s.x + ch * lx - sh * ly));
    out.push_back(static_cast<float>(s.y + sh * lx + ch * ly));
    out.push_back(static_cast<float>(z + s.heave + s.slope_along * lx + s.slope_across * ly));
  };
  // half-width at station x in [-L/2, L/2] and height z in [-T, F]: the Wigley hull below the
  // waterline, topsides flaring out by 12 % to the deck (so that they show from above)
  auto half = [&](double lx, double z) {
    const double xi = 2.0 * lx / s.length;
    const double zz = z < 0.0 ? z / s.draft : 0.0, flare = z > 0.0 ? 1.0 + 0.12 * z / freeboard : 1.0;
    return 0.5 * s.beam * (1.0 - xi * xi) * (1.0 - zz * zz) * flare;
  };
  auto px = [&](int i) { return -0.5 * s.length + s.length * i / ns; };
  auto pz = [&](int k) { return -s.draft + (s.draft + freeboard) * k / nz; };
  for (int side = -1; side <= 1; side += 2) {
    for (int i = 0; i < ns; ++i) {
      for (int k = 0; k < nz; ++k) {
        const double x0 = px(i), x1 = px(i + 1), z0 = pz(k), z1 = pz(k + 1);
        const double a = side * half(x0, z0), b = side * half(x1, z0), c = side * half(x1, z1), d = side * half(x0, z1);
        world(x0, a, z0), world(x1, b, z0), world(x1, c, z1);
        world(x0, a, z0), world(x1, c, z1), world(x0, d, z1);
      }
    }
  }
  // deck at the freeboard height, crowned: its centre line 8 % of the beam higher (two faces
  // across, lit differently)
  const double crown = 0.08 * s.beam;
  for (int i = 0; i < ns; ++i) {
    const double x0 = px(i), x1 = px(i + 1), f = freeboard;
    const double w0 = half(x0, f), w1 = half(x1, f);
    const double c0 = f + crown * (1.0 - std::pow(2.0 * x0 / s.length, 2)),
                 c1 = f + crown * (1.0 - std::pow(2.0 * x1 / s.length, 2));
    for (int side = -1; side <= 1; side += 2) {
      world(x0, side * w0, f), world(x1, side * w1, f), world(x1, 0.0, c1);
      world(x0, side * w0, f), world(x1, 0.0, c1), world(x0, 0.0, c0);
    }
  }
}

// The grid points under the ships' waterlines (1 there, else 0): in the ship's frame (lx along
// the heading) a Wigley hull's waterline is |ly| <= B/2 (1 - (2 lx / L)^2), |lx| <= L/2.
void mark_hulls(const GridPlacement& g, std::span<const ShipPose> ships, std::vector<std::uint8_t>& out) {
  out.assign(g.rows * g.cols, 0);
  for (const ShipPose& s : ships) {
    const double ch = std::cos(s.heading), sh = std::sin(s.heading), reach = 0.5 * std::max(s.length, s.beam);
    const auto lo = [&](double v, double v0) { return static_cast<long>(std::floor((v - reach - v0) / g.dx)); };
    const auto hi = [&](double v, double v0) { return static_cast<long>(std::ceil((v + reach - v0) / g.dx)); };
    for (long i = std::max(0L, lo(s.y, g.y0)); i <= std::min(static_cast<long>(g.rows) - 1, hi(s.y, g.y0)); ++i)
      for (long j = std::max(0L, lo(s.x, g.x0)); j <= std::min(static_cast<long>(g.cols) - 1, hi(s.x, g.x0)); ++j) {
        const double dx = g.x(static_cast<std::size_t>(j)) - s.x, dy = g.y(static_cast<std::size_t>(i)) - s.y;
        const double lx = ch * dx + sh * dy, ly = -sh * dx + ch * dy, xi = 2.0 * lx / s.length;
        if (std::abs(xi) <= 1.0 && std::abs(ly) <= 0.5 * s.beam * (1.0 - xi * xi))
          out[static_cast<std::size_t>(i) * g.cols + static_cast<std::size_t>(j)] = 1;
      }
  }
}

void float_ship(const GridPlacement& g, std::span<const float> eta, ShipPose& s) {
  // eta at (x, y), bilinear; false outside the grid's points
  const auto at = [&](double x, double y, double& v) {
    const double fx = (x - g.x0) / g.dx, fy = (y - g.y0) / g.dx;
    if (!(fx >= 0.0 && fy >= 0.0 && fx <= g.cols - 1.0 && fy <= g.rows - 1.0)) return false;
    const std::size_t c = std::min(static_cast<std::size_t>(fx), g.cols - 2),
                      r = std::min(static_cast<std::size_t>(fy), g.rows - 2);
    const double tx = fx - c, ty = fy - r;
    const auto e = [&](std::size_t i, std::size_t j) { return static_cast<double>(eta[i * g.cols + j]); };
    v = (1 - ty) * ((1 - tx) * e(r, c) + tx * e(r, c + 1)) + ty * ((1 - tx) * e(r + 1, c) + tx * e(r + 1, c + 1));
    return true;
  };
  // eta = a + b u + c w in the ship's frame (u along the heading, w across), normal equations
  double n = 0, su = 0, sw = 0, se = 0, suu = 0, sww = 0, suw = 0, sue = 0, swe = 0;
  const double ch = std::cos(s.heading), sh = std::sin(s.heading);
  for (const double rho : {0.6, 0.7, 0.8})
    for (int k = 0; k < 48; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / 48, u = rho * s.length * std::cos(phi),
                   w = rho * s.length * std::sin(phi);
      double v = 0.0;
      if (!at(s.x + ch * u - sh * w, s.y + sh * u + ch * w, v)) continue;
      n += 1, su += u, sw += w, se += v, suu += u * u, sww += w * w, suw += u * w, sue += u * v, swe += w * v;
    }
  s.heave = s.slope_along = s.slope_across = 0.0;
  if (n < 3) return;
  const glm::dmat3 m(n, su, sw, su, suu, suw, sw, suw, sww);  // symmetric
  if (std::abs(glm::determinant(m)) < 1e-12 * n * n * n * std::pow(s.length, 4)) return;
  const glm::dvec3 abc = glm::inverse(m) * glm::dvec3(se, sue, swe);
  s.slope_along = std::clamp(abc.y, -0.3, 0.3);
  s.slope_across = std::clamp(abc.z, -0.3, 0.3);
  s.heave = abc.x;
}

void append_mesh_solids(std::span<const RenderObstacle> obstacles, const SolidsFrame& f, std::vector<float>& out) {
  const float off = static_cast<float>(f.offset);
  for (const RenderObstacle& o : obstacles) {
    if (o.kind != RenderObstacle::Kind::mesh) continue;
    const std::vector<float>& t = o.triangles_m;
    for (std::size_t k = 0; k + 9 <= t.size(); k += 9)
      for (int c = 0; c < 3; ++c) out.insert(out.end(), {t[k + 3 * c], t[k + 3 * c + 1], t[k + 3 * c + 2] - off});
  }
}

std::vector<Prism> prisms(std::span<const RenderObstacle> obstacles, const SolidsFrame& f) {
  const GridPlacement& g = f.grid;
  const double extent = std::max(g.cols, g.rows) * g.dx;
  const double floor_z = f.ground_z, rise = std::max(0.25 * std::abs(f.ground_z), f.over_terrain ? 0.03 * extent : 0.0);
  auto zr = [&](double z, double fallback) { return std::isfinite(z) ? z - static_cast<float>(f.offset) : fallback; };
  const double gx1 = g.x0 + (g.cols - 1) * g.dx, gy1 = g.y0 + (g.rows - 1) * g.dx;
  std::vector<Prism> out;
  for (const RenderObstacle& o : obstacles) {
    if (o.kind == RenderObstacle::Kind::mesh) continue;  // append_mesh_solids
    Prism p;
    if (o.kind == RenderObstacle::Kind::box) {
      // clipped to the visible region (a wall along the domain's edge stays inside it)
      p.lo = {std::max(o.min_m[0], g.x0 - 0.5 * g.dx), std::max(o.min_m[1], g.y0 - 0.5 * g.dx)};
      p.hi = {std::min(o.max_m[0], gx1 + 0.5 * g.dx), std::min(o.max_m[1], gy1 + 0.5 * g.dx)};
      p.z0 = std::max(zr(o.min_m[2], floor_z), floor_z), p.z1 = zr(o.max_m[2], rise);
      if (p.hi.x <= p.lo.x || p.hi.y <= p.lo.y) continue;
    } else {
      p.cylinder = true;
      p.lo = {o.centre_m[0], o.centre_m[1]}, p.hi = {o.radius_m, 0.0};
      p.z0 = std::max(zr(o.z0_m, floor_z), floor_z), p.z1 = zr(o.z1_m, rise);
    }
    out.push_back(p);
  }
  return out;
}

void append_prism_solids(std::span<const Prism> prisms, std::vector<float>& out) {
  auto tri = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    for (const glm::dvec3& p : {a, b, c})
      out.insert(out.end(), {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  };
  auto wall = [&](glm::dvec2 p, glm::dvec2 q, double z0, double z1) {
    tri({p, z0}, {q, z0}, {q, z1});
    tri({p, z0}, {q, z1}, {p, z1});
  };
  for (const Prism& p : prisms) {
    if (!p.cylinder) {
      const glm::dvec2 c[4] = {p.lo, {p.hi.x, p.lo.y}, p.hi, {p.lo.x, p.hi.y}};
      for (int k = 0; k < 4; ++k) wall(c[k], c[(k + 1) % 4], p.z0, p.z1);
      tri({c[0], p.z1}, {c[1], p.z1}, {c[2], p.z1});
      tri({c[0], p.z1}, {c[2], p.z1}, {c[3], p.z1});
      continue;
    }
    constexpr int n = 48;
    for (int k = 0; k < n; ++k) {
      const double a0 = 2.0 * std::numbers::pi * k / n, a1 = 2.0 * std::numbers::pi * (k + 1) / n;
      const glm::dvec2 a = p.lo + p.hi.x * glm::dvec2(std::cos(a0), std::sin(a0));
      const glm::dvec2 b = p.lo + p.hi.x * glm::dvec2(std::cos(a1), std::sin(a1));
      wall(a, b, p.z0, p.z1);
      tri({p.lo, p.z1}, {a, p.z1}, {b, p.z1});
    }
  }
}

std::vector<float> tank_walls(const std::array<double, 3>& box_m, const SolidsFrame& f, const glm::dvec3& eye) {
  std::vector<float> tri;
  if (box_m[0] <= 0.0) return tri;
  const float X = static_cast<float>(box_m[0]), Y = static_cast<float>(box_m[1]);
  const float z0 = static_cast<float>(f.ground_z), z1 = static_cast<float>(box_m[2]) - static_cast<float>(f.offset);
  auto wall = [&](float ax, float ay, float bx, float by) {
    const float p[4][3] = {{ax, ay, z0}, {bx, by, z0}, {bx, by, z1}, {ax, ay, z1}};
    for (int k : {0, 1, 2, 0, 2, 3}) tri.insert(tri.end(), p[k], p[k] + 3);
  };
  if (eye.y > 0.0) wall(0, 0, X, 0);
  if (eye.y < Y) wall(0, Y, X, Y);
  if (eye.x > 0.0) wall(0, 0, 0, Y);
  if (eye.x < X) wall(X, 0, X, Y);
  return tri;
}

}  // namespace huygens
