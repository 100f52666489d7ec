// Boundary particles of the container and the obstacles, and the OBJ reader: see huygens/sph/boundary.hpp.
#include "huygens/sph/boundary.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "huygens/sph/mesh_tree.hpp"

namespace huygens {

// ---------------------------------------------------------------------------------------------
// OBJ (v and f lines only)

namespace {

using V3 = std::array<float, 3>;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
float dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

[[noreturn]] void obj_fail(const std::string& name, int line, const std::string& why) {
  throw std::runtime_error(name + (line > 0 ? ":" + std::to_string(line) : "") + ": " + why);
}

// the vertex index of one face token ("a", "a/b", "a//c", "a/b/c"); 1-based, negative from the end
int face_index(const std::string& tok, int nv, const std::string& name, int line) {
  std::size_t used = 0;
  long v = 0;
  try {
    v = std::stol(tok.substr(0, tok.find('/')), &used);
  } catch (const std::exception&) {
    obj_fail(name, line, "face vertex '" + tok + "' is not an index");
  }
  if (used != tok.substr(0, tok.find('/')).size()) obj_fail(name, line, "face vertex '" + tok + "' is not an index");
  const long i = v < 0 ? nv + v : v - 1;
  if (v == 0 || i < 0 || i >= nv)
    obj_fail(name, line,
             "face vertex " + std::to_string(v) + " outside the " + std::to_string(nv) + " vertices so far");
  return static_cast<int>(i);
}

void parse_obj_line(const std::string& text, const std::string& name, int line, SphMesh& m) {
  std::istringstream in(text);
  std::string key;
  if (!(in >> key) || key[0] == '#') return;
  if (key == "vn" || key == "vt" || key == "o" || key == "g" || key == "s" || key == "usemtl" || key == "mtllib")
    return;
  if (key == "v") {
    V3 p{};
    for (float& c : p)
      if (!(in >> c) || !std::isfinite(c)) obj_fail(name, line, "a vertex needs three finite coordinates");
    m.vertices.push_back(p);
    return;
  }
  if (key != "f") obj_fail(name, line, "'" + key + "' lines are not read (only v and f)");
  std::vector<int> f;
  std::string tok;
  while (in >> tok) f.push_back(face_index(tok, static_cast<int>(m.vertices.size()), name, line));
  if (f.size() < 3) obj_fail(name, line, "a face needs at least three vertices");
  for (std::size_t k = 1; k + 1 < f.size(); ++k) m.triangles.push_back({f[0], f[k], f[k + 1]});
}

// closed: every undirected edge belongs to exactly two triangles
void check_closed(const SphMesh& m, const std::string& name) {
  if (m.triangles.empty()) obj_fail(name, 0, "no faces");
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (a == b) obj_fail(name, 0, "a face repeats a vertex");
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  for (const auto& [e, n] : edges)
    if (n != 2)
      obj_fail(name, 0,
               "the mesh is not closed: edge " + std::to_string(e.first + 1) + "-" + std::to_string(e.second + 1) +
                   " belongs to " + std::to_string(n) + " faces (2 expected)");
}

// a closed mesh encloses a volume: V = sum_t a.(b x c) / 6 (divergence theorem); flat or collinear
// vertices enclose none and would be an obstacle without a single boundary particle
void check_volume(const SphMesh& m, const std::string& name) {
  double six_v = 0, extent = 0;
  V3 lo = m.vertices[m.triangles[0][0]], hi = lo;
  for (const auto& t : m.triangles) {
    six_v += dot(m.vertices[t[0]], cross(m.vertices[t[1]], m.vertices[t[2]]));
    for (int c : t)
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], m.vertices[c][a]), hi[a] = std::max(hi[a], m.vertices[c][a]);
  }
  for (int a = 0; a < 3; ++a) extent = std::max(extent, double(hi[a]) - lo[a]);
  if (!(std::abs(six_v) > 1e-6 * extent * extent * extent))
    obj_fail(name, 0, "the mesh encloses no volume (its vertices are flat or on a line)");
}

}  // namespace

SphMesh sph_parse_obj(const std::string& text, const std::string& name) {
  SphMesh m;
  std::istringstream in(text);
  std::string l;
  int line = 0;
  while (std::getline(in, l)) parse_obj_line(l, name, ++line, m);
  check_closed(m, name);
  check_volume(m, name);
  return m;
}

SphMesh sph_read_obj(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file + ": cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  return sph_parse_obj(s.str(), file);
}

bool SphObstacle::blocks(float x, float y, float z, float margin) const {
  const float e = margin;
  switch (type) {
    case Type::box:
      return x > min_m[0] - e && x < max_m[0] + e && y > min_m[1] - e && y < max_m[1] + e && z > min_m[2] - e &&
             z < max_m[2] + e;
    case Type::cylinder: {
      const float dx = x - centre_m[0], dy = y - centre_m[1];
      const float r = radius_m + e;
      return dx * dx + dy * dy < r * r && z > z0_m - e && z < z1_m + e;
    }
    case Type::sphere: {
      const float dx = x - sphere_centre_m[0], dy = y - sphere_centre_m[1], dz = z - sphere_centre_m[2];
      const float r = radius_m + e;
      return dx * dx + dy * dy + dz * dz < r * r;
    }
    case Type::mesh:
      if (!(x > min_m[0] - e && x < max_m[0] + e && y > min_m[1] - e && y < max_m[1] + e && z > min_m[2] - e &&
            z < max_m[2] + e))
        return false;
      if (!tree || &tree->mesh() != mesh.get())
        throw std::logic_error("a mesh obstacle is made by SphObstacle::set_mesh (its tree must be its mesh's)");
      // within e of the surface: some face nearer than e; deeper than -e: no face at -e or nearer
      if (e >= 0.f) return tree->inside({x, y, z}) || tree->nearer_than({x, y, z}, e * e);
      return tree->inside({x, y, z}) && !tree->nearer_than({x, y, z}, std::nextafter(e * e, 1e30f));
  }
  return false;
}

void SphObstacle::set_mesh(SphMesh placed) {
  type = Type::mesh;
  min_m = {1e30f, 1e30f, 1e30f};
  max_m = {-1e30f, -1e30f, -1e30f};
  for (const auto& v : placed.vertices)
    for (int a = 0; a < 3; ++a) {
      min_m[a] = std::min(min_m[a], v[a]);
      max_m[a] = std::max(max_m[a], v[a]);
    }
  mesh = std::make_shared<const SphMesh>(std::move(placed));
  tree = std::make_shared<const SphMeshTree>(mesh);
}

// ---------------------------------------------------------------------------------------------
// sampling

int sph_boundary_layers(float h, float dx) { return std::max(1, static_cast<int>(std::ceil(h / dx - 1e-3f))); }

namespace {

// A lattice of spacing s_a = (hi_a - lo_a) / round((hi_a - lo_a) / dx) per axis (n_a cells), the
// cell (i, j, k) centred at lo + (i + 1/2, j + 1/2, k + 1/2) s.
struct BoxLattice {
  int n[3];
  float s[3];
  float w;  // a cell's volume / dx^3
  BoxLattice(const V3& lo, const V3& hi, float dx) {
    for (int a = 0; a < 3; ++a) {
      n[a] = std::max(1, static_cast<int>(std::lround((hi[a] - lo[a]) / dx)));
      s[a] = (hi[a] - lo[a]) / n[a];
    }
    w = s[0] * s[1] * s[2] / (dx * dx * dx);
  }
};

// The container walls: the cells of the lattice of [0, L] extended by `layers` cells that lie outside
// [0, L], normal toward the box (edges and corners included).
void sample_container_lattice(const V3& hi, float dx, int layers, SphBoundarySample& out) {
  const BoxLattice g({0.f, 0.f, 0.f}, hi, dx);
  for (int k = -layers; k < g.n[2] + layers; ++k)
    for (int j = -layers; j < g.n[1] + layers; ++j)
      for (int i = -layers; i < g.n[0] + layers; ++i) {
        const int idx[3] = {i, j, k};
        bool out_of_box = false;
        for (int a = 0; a < 3; ++a) out_of_box = out_of_box || idx[a] < 0 || idx[a] >= g.n[a];
        if (!out_of_box) continue;
        const V3 p{(i + 0.5f) * g.s[0], (j + 0.5f) * g.s[1], (k + 0.5f) * g.s[2]};
        V3 nr{};
        for (int a = 0; a < 3; ++a) nr[a] = std::clamp(p[a], 0.f, hi[a]) - p[a];
        const float len = std::sqrt(dot(nr, nr));
        out.add(p[0], p[1], p[2], g.w, nr[0] / len, nr[1] / len, nr[2] / len);
      }
}

// A box obstacle: the cells of its lattice within `layers` dx of an exposed face (a face on or beyond
// a container wall is buried in it, as a mesh's: not a face the depth is measured from; a box with
// every face buried measures from all six), normal out of the nearest exposed faces. A cell in the
// first row of two or three exposed faces lies at a convex edge or corner: one point at its centre
// would stand 0.71 dx from the edge (the faces' rows 0.5 dx from their face), so the cell is split
// into 2 x 2 (x 2 at a corner) sub-cells across those faces, one point of a quarter (eighth) of its
// volume each, the nearest 0.35 dx from the edge as the line of a mesh's 90-degree edge
// (sample_convex_edges); they carry the cell's normal, the bisector of its faces.
void sample_box_obstacle(const V3& lo, const V3& hi, const V3& container, float dx, int layers,
                         SphBoundarySample& out) {
  const BoxLattice g(lo, hi, dx);
  const float eps = 1e-3f * dx;
  bool exposed[3][2];
  bool any = false;
  for (int a = 0; a < 3; ++a) {
    exposed[a][0] = lo[a] > eps;
    exposed[a][1] = hi[a] < container[a] - eps;
    any = any || exposed[a][0] || exposed[a][1];
  }
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) exposed[a][side] = exposed[a][side] || !any;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const int idx[3] = {i, j, k};
        float depth = 1e30f;  // distance to the nearest exposed face (m)
        for (int a = 0; a < 3; ++a) {
          if (exposed[a][0]) depth = std::min(depth, (idx[a] + 0.5f) * g.s[a]);
          if (exposed[a][1]) depth = std::min(depth, (g.n[a] - idx[a] - 0.5f) * g.s[a]);
        }
        if (depth > layers * dx) continue;
        V3 nr{};       // out of the exposed faces at that depth, or of those whose first row it is
        int edge = 0;  // bit a: split across axis a
        for (int a = 0; a < 3; ++a) {
          const bool first_lo = exposed[a][0] && idx[a] == 0, first_hi = exposed[a][1] && idx[a] == g.n[a] - 1;
          if (first_lo || first_hi) edge |= 1 << a;
          if (exposed[a][0] && std::fabs((idx[a] + 0.5f) * g.s[a] - depth) < eps) nr[a] = -1.f;
          if (exposed[a][1] && std::fabs((g.n[a] - idx[a] - 0.5f) * g.s[a] - depth) < eps) nr[a] = 1.f;
        }
        const bool split = edge != 0 && (edge & (edge - 1)) != 0;  // two or three faces
        if (split)
          for (int a = 0; a < 3; ++a)
            if (edge & (1 << a)) nr[a] = exposed[a][0] && idx[a] == 0 ? -1.f : 1.f;
        const float len = std::sqrt(dot(nr, nr));
        const V3 c{lo[0] + (i + 0.5f) * g.s[0], lo[1] + (j + 0.5f) * g.s[1], lo[2] + (k + 0.5f) * g.s[2]};
        const int m = split ? edge : 0;
        const int parts = 1 << std::popcount(static_cast<unsigned>(m));
        for (int q = 0; q < 8; ++q) {
          if ((q & ~m) != 0) continue;  // sub-cell q: bit a set = the upper half along a
          V3 p = c;
          for (int a = 0; a < 3; ++a)
            if (m & (1 << a)) p[a] += ((q >> a) & 1 ? 0.25f : -0.25f) * g.s[a];
          out.add(p[0], p[1], p[2], g.w / parts, nr[0] / len, nr[1] / len, nr[2] / len);
        }
      }
}

// ring of radius r at height z, points ~dx apart, each standing for (2 pi r / count) x dz x dr;
// normal (n_radial cos t, n_radial sin t, n_z) into the fluid
void sample_ring(float cx, float cy, float r, float z, float dz, float dr, float dx, float n_radial, float n_z,
                 SphBoundarySample& out) {
  const int cnt = std::max(1, static_cast<int>(std::lround(2.f * std::numbers::pi_v<float> * r / dx)));
  const float w = 2.f * std::numbers::pi_v<float> * r / cnt * dz * dr / (dx * dx * dx);
  for (int q = 0; q < cnt; ++q) {
    const float t = 2.f * std::numbers::pi_v<float> * (q + 0.5f * (std::lround(z / dx) % 2)) / cnt;
    const float c = std::cos(t), sn = std::sin(t);
    out.add(cx + r * c, cy + r * sn, z, w, n_radial * c, n_radial * sn, n_z);
  }
}

void sample_cylinder(const SphObstacle& o, float container_z, float dx, int layers, SphBoundarySample& out) {
  const float R = o.radius_m, H = o.z1_m - o.z0_m, cx = o.centre_m[0], cy = o.centre_m[1];
  const int nz = std::max(1, static_cast<int>(std::lround(H / dx)));
  const float sz = H / nz;
  // the side: `layers` rings per height level, over the whole height; the outer ring's top and bottom
  // levels are the rim, equally near the side and a cap, with both faces' normals (as a box's edge),
  // unless that cap is buried in the floor or the lid (a cylinder standing on the floor has no rim there)
  const bool rim_lo = o.z0_m > 1e-3f * dx, rim_hi = o.z1_m < container_z - 1e-3f * dx;
  for (int k = 0; k < layers && R - (k + 0.5f) * dx > 0.f; ++k)
    for (int j = 0; j < nz; ++j) {
      const bool rim = k == 0 && nz > 1 && ((j == 0 && rim_lo) || (j == nz - 1 && rim_hi));
      const float nr = rim ? std::sqrt(0.5f) : 1.f, nzr = rim ? (j == 0 ? -nr : nr) : 0.f;
      sample_ring(cx, cy, R - (k + 0.5f) * dx, o.z0_m + (j + 0.5f) * sz, sz, dx, dx, nr, nzr, out);
    }
  // the caps inside the side layers: `layers` discs of rings of width rin / round(rin / dx) (a
  // cylinder thinner than the layers gets discs of half a spacing, overlapping the side rings)
  const float rin = std::max(R - layers * dx, std::min(R, 0.5f * dx));
  const int nq = std::max(1, static_cast<int>(std::lround(rin / dx)));
  const float sr = rin / nq;
  for (int k = 0; k < layers && (k + 0.5f) * dx < 0.5f * H; ++k)
    for (const float cap : {1.f, -1.f}) {
      const float z = cap > 0.f ? o.z1_m - (k + 0.5f) * dx : o.z0_m + (k + 0.5f) * dx;
      for (int q = 0; q < nq; ++q) sample_ring(cx, cy, (q + 0.5f) * sr, z, dx, sr, dx, 0.f, cap, out);
    }
}

// Fibonacci spheres of radius R - (k + 1/2) dx, ~one point per dx^2
void sample_sphere(const SphObstacle& o, float dx, int layers, SphBoundarySample& out) {
  const float golden = std::numbers::pi_v<float> * (3.f - std::sqrt(5.f));
  for (int k = 0; k < layers; ++k) {
    const float r = o.radius_m - (k + 0.5f) * dx;
    if (r <= 0.f) break;
    const float area = 4.f * std::numbers::pi_v<float> * r * r;
    const int cnt = std::max(1, static_cast<int>(std::lround(area / (dx * dx))));
    const float w = area / cnt / (dx * dx);
    for (int q = 0; q < cnt; ++q) {
      const float zz = 1.f - 2.f * (q + 0.5f) / cnt, rr = std::sqrt(std::max(0.f, 1.f - zz * zz));
      const float t = golden * q;
      const auto& c = o.sphere_centre_m;
      out.add(c[0] + r * rr * std::cos(t), c[1] + r * rr * std::sin(t), c[2] + r * zz, w, rr * std::cos(t),
              rr * std::sin(t), zz);
    }
  }
}

// A face all of whose vertices lie on or beyond one wall plane of the container [0, L]^3 (within
// eps) is buried in that wall: the fluid never meets it, and the wall's own layers stand behind it.
bool buried_in_wall(const V3& a, const V3& b, const V3& c, const V3& L, float eps) {
  for (int ax = 0; ax < 3; ++ax) {
    if (a[ax] <= eps && b[ax] <= eps && c[ax] <= eps) return true;
    if (a[ax] >= L[ax] - eps && b[ax] >= L[ax] - eps && c[ax] >= L[ax] - eps) return true;
  }
  return false;
}

// Every exposed triangle (not buried in a container wall) split into n^2 similar sub-triangles
// (n = ceil(longest edge / dx)), one point per sub-triangle centroid, offset inward by (k + 1/2) dx
// along the outward face normal. A point is kept only if it lies inside the mesh and inside the
// container (outside it the wall's layers are the solid) and no other exposed face is nearer than
// its own depth: at convex edges and corners the layers of the faces meeting there would overlap;
// each keeps its own part. Where the mesh stands on a wall (a wedge on the floor), its face there
// is buried: the layers of the faces rising from the wall run down to the wall, as the solid (the
// union of mesh and wall) does, instead of stopping at the bisector of the mesh's edge there.
// The tip of a convex edge: at an edge where two exposed faces meet at interior angle 2 alpha, the
// faces' layer points stop at the bisector, dx/2 deep, i.e. s* = (dx/2)/sin(alpha) from the edge, and
// the kite between the edge and that point (area (dx/2)^2 / tan(alpha) of cross-section: two
// triangles with legs dx/2 and (dx/2)/tan(alpha)) holds solid no point samples. It gets one line of
// points along the edge, ~dx apart, at the kite's centroid on the bisector, (dx/2)(1 + cos^2 alpha) /
// (3 sin alpha) from the edge, weight = the kite's volume per point / dx^3. Edges flatter than 150
// degrees (a quad's diagonal: 180) are left out, as are points outside the mesh or the container.
void sample_convex_edges(const SphMesh& exposed, const SphMesh& m, const SphMeshTree& solid, float orient,
                         const V3& container, float dx, SphBoundarySample& out) {
  std::map<std::pair<int, int>, std::vector<std::size_t>> edges;
  for (std::size_t t = 0; t < exposed.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = exposed.triangles[t][e], b = exposed.triangles[t][(e + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  auto normal = [&](std::size_t t) {
    const auto& tri = exposed.triangles[t];
    const V3 n = cross(sub(m.vertices[tri[1]], m.vertices[tri[0]]), sub(m.vertices[tri[2]], m.vertices[tri[0]]));
    const float l = orient / std::sqrt(dot(n, n));
    return V3{n[0] * l, n[1] * l, n[2] * l};
  };
  for (const auto& [key, faces] : edges) {
    if (faces.size() != 2) continue;
    const V3 n1 = normal(faces[0]), n2 = normal(faces[1]), &a = m.vertices[key.first], &b = m.vertices[key.second];
    const float cos_phi = dot(n1, n2);  // phi = pi - 2 alpha, the angle between the outward normals
    if (cos_phi > std::cos(30.f * std::numbers::pi_v<float> / 180.f)) continue;
    const auto& t2 = exposed.triangles[faces[1]];
    const int far = t2[0] != key.first && t2[0] != key.second   ? t2[0]
                    : t2[1] != key.first && t2[1] != key.second ? t2[1]
                                                                : t2[2];
    if (dot(n1, sub(m.vertices[far], a)) >= 0.f) continue;  // concave: the faces' layers overlap there already
    const V3 bis{-(n1[0] + n2[0]), -(n1[1] + n2[1]), -(n1[2] + n2[2])};  // inward
    const float lb = std::sqrt(dot(bis, bis));
    const float sin_a = std::sqrt(std::max(0.5f * (1.f + cos_phi), 1e-6f)), cos_a2 = 1.f - sin_a * sin_a;
    const float depth = 0.5f * dx * (1.f + cos_a2) / (3.f * sin_a);
    const float len = std::sqrt(dot(sub(b, a), sub(b, a)));
    const int n = std::max(1, static_cast<int>(std::lround(len / dx)));
    const float w = 0.25f * dx * dx * std::sqrt(cos_a2) / sin_a * (len / n) / (dx * dx * dx);
    for (int i = 0; i < n; ++i) {
      const float u = (i + 0.5f) / n;
      const V3 p{a[0] + u * (b[0] - a[0]) + depth * bis[0] / lb, a[1] + u * (b[1] - a[1]) + depth * bis[1] / lb,
                 a[2] + u * (b[2] - a[2]) + depth * bis[2] / lb};
      const bool in_box =
          p[0] > 0.f && p[1] > 0.f && p[2] > 0.f && p[0] < container[0] && p[1] < container[1] && p[2] < container[2];
      if (in_box && solid.inside(p)) out.add(p[0], p[1], p[2], w, -bis[0] / lb, -bis[1] / lb, -bis[2] / lb);
    }
  }
}

void sample_mesh(const SphMesh& m, const V3& container, float dx, int layers, SphBoundarySample& out) {
  double vol = 0;
  for (const auto& t : m.triangles) vol += dot(m.vertices[t[0]], cross(m.vertices[t[1]], m.vertices[t[2]]));
  const float orient = vol >= 0 ? 1.f : -1.f;
  SphMesh exposed{m.vertices, {}};
  for (const auto& t : m.triangles)
    if (!buried_in_wall(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], container, 1e-3f * dx))
      exposed.triangles.push_back(t);
  const SphMeshTree solid(m, m.triangles), faces(m, exposed.triangles);
  sample_convex_edges(exposed, m, solid, orient, container, dx, out);
  for (const auto& t : exposed.triangles) {
    const V3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const V3 ab = sub(b, a), ac = sub(c, a), nn = cross(ab, ac);
    const float len = std::sqrt(dot(nn, nn));
    if (len <= 0.f) continue;
    const V3 nrm{orient * nn[0] / len, orient * nn[1] / len, orient * nn[2] / len};
    const float edge = std::sqrt(std::max({dot(ab, ab), dot(ac, ac), dot(sub(c, b), sub(c, b))}));
    const int n = std::max(1, static_cast<int>(std::ceil(edge / dx)));
    const float w = 0.5f * len / float(n * n) / (dx * dx);
    for (int k = 0; k < layers; ++k)
      for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j)
          for (int up = 0; up < 2; ++up) {
            if (up == 1 && i + j + 2 > n) continue;
            const float f = up ? 2.f / 3.f : 1.f / 3.f;
            const float u = (i + f) / n, v = (j + f) / n, d = (k + 0.5f) * dx;
            const V3 p{a[0] + u * ab[0] + v * ac[0] - d * nrm[0], a[1] + u * ab[1] + v * ac[1] - d * nrm[1],
                       a[2] + u * ab[2] + v * ac[2] - d * nrm[2]};
            const bool in_box = p[0] > 0.f && p[1] > 0.f && p[2] > 0.f && p[0] < container[0] && p[1] < container[1] &&
                                p[2] < container[2];
            if (in_box && !faces.nearer_than(p, d * d * (1.f - 1e-3f)) && solid.inside(p))
              out.add(p[0], p[1], p[2], w, nrm[0], nrm[1], nrm[2]);
          }
  }
}

}  // namespace

void sph_sample_container(const std::array<float, 3>& container_m, float dx, int layers, SphBoundarySample& out) {
  sample_container_lattice(container_m, dx, layers, out);
}

void sph_sample_obstacle(const SphObstacle& o, const std::array<float, 3>& container_m, float dx, int layers,
                         SphBoundarySample& out) {
  switch (o.type) {
    case SphObstacle::Type::box:
      sample_box_obstacle(o.min_m, o.max_m, container_m, dx, layers, out);
      return;
    case SphObstacle::Type::cylinder:
      sample_cylinder(o, container_m[2], dx, layers, out);
      return;
    case SphObstacle::Type::sphere:
      sample_sphere(o, dx, layers, out);
      return;
    case SphObstacle::Type::mesh:
      sample_mesh(*o.mesh, container_m, dx, layers, out);
      return;
  }
}

}  // namespace huygens
