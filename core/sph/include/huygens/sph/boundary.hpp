#pragma once
// Walls and obstacles of the SPH container [0, Lx] x [0, Ly] x [0, Lz] as boundary particles
// (docs/sph.md "Walls"): dummy particles after Adami, Hu and Adams 2012 (J. Comput. Phys. 231),
// static, K = ceil(h / dx) layers deep so a fluid particle at a wall has a full kernel support.
// Each boundary particle b has a mass m_b = w_b m (m the fluid particle mass, w_b its sampled
// volume over dx^3) and enters the fluid density like a fluid particle. Its pressure is
// extrapolated from the fluid around it (Adami et al. 2012 eq. 27, wall at rest, a_w = 0):
//   p_b = max(0, (sum_f p_f W_bf + g . sum_f rho_f (x_b - x_f) W_bf) / sum_f W_bf)
// with rho_f = max(rho_f, rho0), the density of p_f by the clamped equation of state (the summation
// density of a particle at the free surface is low because its kernel is cut off, not the water)
// and its density from the equation of state inverted (eq. 28): rho_b = rho0 (1 + p_b / B)^(1/gamma).
// Sampling: the container walls and box obstacles on a lattice of spacing ~dx (per axis L / round(L / dx));
// a box's cells at a convex edge (corner) split into 2 x 2 (x 2) points of equal share of the cell;
// cylinders and spheres on rings / Fibonacci spheres of spacing ~dx per layer, meshes by a regular
// area sampling of every triangle (n^2 sub-triangle centroids, n = ceil(longest edge / dx)) offset
// inward along the face normal by (k + 1/2) dx for layer k; a mesh face on a container wall is
// buried in it (not sampled, the other faces' layers run down to the wall).
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace huygens {

/// A closed triangle mesh (vertices in m after placement; triangles as vertex indices).
struct SphMesh {
  std::vector<std::array<float, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// Reads the "v x y z" and "f a b c ..." lines of an OBJ file (faces fan-triangulated; "a/b/c"
/// uses a; negative indices count from the end; comments, blank lines and vn, vt, o, g, s, usemtl,
/// mtllib lines are skipped). Throws std::runtime_error naming the file and line of a bad line, and
/// the file when the mesh is empty or not closed (every edge in exactly two triangles).
SphMesh sph_read_obj(const std::string& file);
/// The same from text (`name` stands for the file in messages).
SphMesh sph_parse_obj(const std::string& text, const std::string& name);

class SphMeshTree;

/// A static rigid obstacle: an axis-aligned box, a vertical cylinder standing on z0_m, a sphere, or
/// a closed triangle mesh.
struct SphObstacle {
  enum class Type { box, cylinder, sphere, mesh };
  Type type = Type::box;
  /// Box lower corner (unit: m).
  std::array<float, 3> min_m{0.f, 0.f, 0.f};
  /// Box upper corner (unit: m).
  std::array<float, 3> max_m{0.f, 0.f, 0.f};
  /// Cylinder axis position x, y (unit: m).
  std::array<float, 2> centre_m{0.f, 0.f};
  /// Sphere centre (unit: m).
  std::array<float, 3> sphere_centre_m{0.f, 0.f, 0.f};
  /// Cylinder or sphere radius (unit: m).
  float radius_m = 0.f;
  /// Cylinder bottom and top heights (unit: m).
  float z0_m = 0.f, z1_m = 0.f;
  /// Mesh, placed (unit: m); min_m / max_m hold its bounding box. Set by set_mesh, with its tree.
  std::shared_ptr<const SphMesh> mesh;
  std::shared_ptr<const SphMeshTree> tree;
  /// Makes this a mesh obstacle: the placed mesh (unit: m), its bounding box and its query tree.
  void set_mesh(SphMesh placed);
  /// True where (x, y, z) lies inside the obstacle or within `margin` of it; a negative margin: deeper
  /// than -margin inside (unit: m).
  bool blocks(float x, float y, float z, float margin) const;
};

/// The boundary particles of a set-up, in any order: positions (m), mass ratios w = m_b / m (1)
/// and unit normals of the surface they sample, pointing into the fluid (1).
struct SphBoundarySample {
  std::vector<float> x, y, z, w, nx, ny, nz;
  std::size_t size() const { return x.size(); }
  void add(float px, float py, float pz, float pw, float n0, float n1, float n2) {
    x.push_back(px);
    y.push_back(py);
    z.push_back(pz);
    w.push_back(pw);
    nx.push_back(n0);
    ny.push_back(n1);
    nz.push_back(n2);
  }
};

/// Number of boundary layers for support h and spacing dx: ceil(h / dx - 1/1000) (unit: 1).
int sph_boundary_layers(float h, float dx);

/// Samples `layers` layers outside the container [0, L]^3 (edges and corners included).
void sph_sample_container(const std::array<float, 3>& container_m, float dx, int layers, SphBoundarySample& out);
/// Samples `layers` layers inside the obstacle's surface, within the container [0, L]^3 (a mesh or box
/// face lying on a container wall is buried in it: not sampled, and not a surface the depth is measured from).
void sph_sample_obstacle(const SphObstacle& o, const std::array<float, 3>& container_m, float dx, int layers,
                         SphBoundarySample& out);

}  // namespace huygens
