// Inside and distance queries on a triangle mesh: see huygens/sph/mesh_tree.hpp.
#include "huygens/sph/mesh_tree.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace huygens {

namespace {

using V3 = std::array<float, 3>;

constexpr int kLeafTriangles = 8;
// A cluster counts as far beyond beta times its radius (Barill et al. 2018 take beta = 2).
constexpr double kBeta = 2.0;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
float dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// squared distance from p to the box [lo, hi] (0 inside)
float box_dist2(const V3& p, const V3& lo, const V3& hi) {
  float s = 0.f;
  for (int k = 0; k < 3; ++k) {
    const float d = std::max({lo[k] - p[k], 0.f, p[k] - hi[k]});
    s += d * d;
  }
  return s;
}

}  // namespace

double sph_solid_angle(const V3& va, const V3& vb, const V3& vc, const V3& p) {
  const V3 a = sub(va, p), b = sub(vb, p), c = sub(vc, p);
  const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
  const double num = dot(a, cross(b, c));
  const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2.0 * std::atan2(num, den);
}

float sph_triangle_dist2(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const float d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto d2to = [&](const V3& q) { return dot(sub(p, q), sub(p, q)); };
  auto lerp = [](const V3& x, const V3& y, float t) {
    return V3{x[0] + t * (y[0] - x[0]), x[1] + t * (y[1] - x[1]), x[2] + t * (y[2] - x[2])};
  };
  if (d1 <= 0.f && d2 <= 0.f) return d2to(a);
  const V3 bp = sub(p, b);
  const float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.f && d4 <= d3) return d2to(b);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.f && d1 >= 0.f && d3 <= 0.f) return d2to(lerp(a, b, d1 / (d1 - d3)));
  const V3 cp = sub(p, c);
  const float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.f && d5 <= d6) return d2to(c);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.f && d2 >= 0.f && d6 <= 0.f) return d2to(lerp(a, c, d2 / (d2 - d6)));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.f && (d4 - d3) >= 0.f && (d5 - d6) >= 0.f) return d2to(lerp(b, c, (d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const float den = 1.f / (va + vb + vc), v = vb * den, w = vc * den;
  const V3 q{a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w};
  return d2to(q);
}

namespace {

// The winding number is the sum of the solid angles over 4 pi; |sum| > 2 pi: inside, either orientation.
bool exact_inside(const SphMesh& m, const std::vector<std::array<int, 3>>& tris, const V3& p) {
  double omega = 0.0;
  for (const auto& t : tris) omega += sph_solid_angle(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], p);
  return std::fabs(omega) > 2.0 * std::numbers::pi;
}

}  // namespace

bool sph_mesh_inside(const SphMesh& m, const V3& p) { return exact_inside(m, m.triangles, p); }

float sph_mesh_dist2(const SphMesh& m, const V3& p) {
  float best = 1e30f;
  for (const auto& t : m.triangles)
    best = std::min(best, sph_triangle_dist2(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]));
  return best;
}

SphMeshTree::SphMeshTree(const SphMesh& mesh, std::vector<std::array<int, 3>> triangles)
    : mesh_(mesh), given_(std::move(triangles)), tris_(given_) {
  nodes_.reserve(2 * tris_.size() / kLeafTriangles + 2);
  if (!tris_.empty()) build(0, static_cast<int>(tris_.size()));
}

SphMeshTree::SphMeshTree(std::shared_ptr<const SphMesh> mesh) : SphMeshTree(*mesh, mesh->triangles) {
  owner_ = std::move(mesh);
}

// Node over tris_[first, first + count): box, centroid, vector area and radius; split at the median
// centroid along the box's longest axis until kLeafTriangles remain.
int SphMeshTree::build(int first, int count) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  Node n;
  n.first = first;
  n.count = count;
  n.lo = {1e30f, 1e30f, 1e30f};
  n.hi = {-1e30f, -1e30f, -1e30f};
  double total = 0.0;
  std::array<double, 3> moment{0, 0, 0}, area{0, 0, 0};
  for (int i = first; i < first + count; ++i) {
    const auto& t = tris_[i];
    const V3 &a = mesh_.vertices[t[0]], &b = mesh_.vertices[t[1]], &c = mesh_.vertices[t[2]];
    const V3 na = cross(sub(b, a), sub(c, a));
    const double len = 0.5 * std::sqrt(static_cast<double>(dot(na, na)));
    total += len;
    for (int k = 0; k < 3; ++k) {
      n.lo[k] = std::min({n.lo[k], a[k], b[k], c[k]});
      n.hi[k] = std::max({n.hi[k], a[k], b[k], c[k]});
      moment[k] += len * (static_cast<double>(a[k]) + b[k] + c[k]) / 3.0;
      area[k] += 0.5 * na[k];
    }
  }
  for (int k = 0; k < 3; ++k) n.centre[k] = total > 0 ? moment[k] / total : 0.5 * (n.lo[k] + n.hi[k]);
  n.area = area;
  for (int i = first; i < first + count; ++i)
    for (int v : tris_[i]) {
      const auto& x = mesh_.vertices[v];
      const double dx = x[0] - n.centre[0], dy = x[1] - n.centre[1], dz = x[2] - n.centre[2];
      n.radius = std::max(n.radius, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  if (count > kLeafTriangles) {
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (n.hi[k] - n.lo[k] > n.hi[axis] - n.lo[axis]) axis = k;
    auto key = [&](const std::array<int, 3>& t) {
      return mesh_.vertices[t[0]][axis] + mesh_.vertices[t[1]][axis] + mesh_.vertices[t[2]][axis];
    };
    const int half = count / 2;
    std::nth_element(tris_.begin() + first, tris_.begin() + first + half, tris_.begin() + first + count,
                     [&](const auto& s, const auto& t) { return key(s) < key(t); });
    n.left = build(first, half);
    n.right = build(first + half, count - half);
  }
  nodes_[id] = n;
  return id;
}

// Sum of the solid angles of the node's triangles seen from p: a far node as its dipole, a near
// leaf exactly, a near inner node as the sum of its children.
double SphMeshTree::winding_sum(int id, const V3& p) const {
  const Node& n = nodes_[id];
  const double rx = n.centre[0] - p[0], ry = n.centre[1] - p[1], rz = n.centre[2] - p[2];
  const double d2 = rx * rx + ry * ry + rz * rz;
  if (d2 > kBeta * kBeta * n.radius * n.radius)
    return (n.area[0] * rx + n.area[1] * ry + n.area[2] * rz) / (d2 * std::sqrt(d2));
  if (n.left < 0) {
    double s = 0.0;
    for (int i = n.first; i < n.first + n.count; ++i) {
      const auto& t = tris_[i];
      s += sph_solid_angle(mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]], p);
    }
    return s;
  }
  return winding_sum(n.left, p) + winding_sum(n.right, p);
}

bool SphMeshTree::inside(const V3& p) const {
  if (nodes_.empty()) return false;
  const double w = std::fabs(winding_sum(0, p)) / (4.0 * std::numbers::pi);
  if (w < 0.25) return false;
  if (w > 0.75) return true;
  return exact_inside(mesh_, given_, p);  // undecided: every triangle exactly, in the given order
}

bool SphMeshTree::nearer(int id, const V3& p, float r2) const {
  const Node& n = nodes_[id];
  // the box's distance can only be below the distance of a triangle in it; a margin of 1e-5 keeps a
  // rounding of the two from pruning a triangle exactly at r2
  if (box_dist2(p, n.lo, n.hi) > r2 * (1.f + 1e-5f)) return false;
  if (n.left < 0) {
    for (int i = n.first; i < n.first + n.count; ++i) {
      const auto& t = tris_[i];
      if (sph_triangle_dist2(p, mesh_.vertices[t[0]], mesh_.vertices[t[1]], mesh_.vertices[t[2]]) < r2) return true;
    }
    return false;
  }
  return nearer(n.left, p, r2) || nearer(n.right, p, r2);
}

bool SphMeshTree::nearer_than(const V3& p, float r2) const { return !nodes_.empty() && nearer(0, p, r2); }

}  // namespace huygens
