#pragma once
// Point queries on a closed triangle mesh (docs/sph.md "Walls"): inside or not, and whether a face
// lies nearer than a distance. Brute force costs one pass over every triangle per point; sampling a
// mesh of T triangles with ~T boundary points then costs T^2 (a 20 480-triangle sphere: 18 s).
// SphMeshTree answers the same two questions in about log T per point:
// - inside: the generalised winding number (Jacobson, Kavan and Sorkine-Hornung 2013) summed over a
//   bounding volume hierarchy, a far cluster C of triangles taken as one dipole (Barill, Dickson,
//   Schmidt, Levin and Jacobson 2018, "Fast winding numbers for soups and clouds", eq. 9, first term):
//     Omega_C(p) ~= A_C . (c_C - p) / |c_C - p|^3,  A_C = sum_t (b - a) x (c - a) / 2,
//   c_C the area-weighted centroid, when |c_C - p| > beta r_C (r_C: the farthest vertex from c_C).
//   The winding number of a closed mesh is an integer, so a sum within 1/4 of it decides; a point
//   whose sum lands between 1/4 and 3/4 is summed exactly over every triangle.
// - nearer: the exact minimum over the triangles whose box is nearer than the distance (the boxes
//   prune; no answer changes).
#include <array>
#include <memory>
#include <vector>

#include "huygens/sph/boundary.hpp"

namespace huygens {

/// Signed solid angle of triangle (a, b, c) seen from p (Van Oosterom and Strackee 1983):
/// tan(Omega/2) = a'.(b' x c') / (|a'||b'||c'| + (a'.b')|c'| + (a'.c')|b'| + (b'.c')|a'|), primes: relative
/// to p (unit: sr; positive where p lies behind the face's counter-clockwise side).
double sph_solid_angle(const std::array<float, 3>& a, const std::array<float, 3>& b, const std::array<float, 3>& c,
                       const std::array<float, 3>& p);
/// Squared distance from p to triangle (a, b, c) (Ericson 2005, Real-Time Collision Detection, 5.1.5) (unit: m^2).
float sph_triangle_dist2(const std::array<float, 3>& p, const std::array<float, 3>& a, const std::array<float, 3>& b,
                         const std::array<float, 3>& c);
/// |winding number| above 1/2 (either orientation), summed over every triangle.
bool sph_mesh_inside(const SphMesh& m, const std::array<float, 3>& p);
/// Smallest squared distance from p to a triangle of m (unit: m^2).
float sph_mesh_dist2(const SphMesh& m, const std::array<float, 3>& p);

/// A bounding volume hierarchy over some triangles of a mesh (kept by reference: the mesh must outlive it).
class SphMeshTree {
 public:
  SphMeshTree(const SphMesh& mesh, std::vector<std::array<int, 3>> triangles);
  /// Over every triangle of a shared mesh, which the tree then keeps alive.
  explicit SphMeshTree(std::shared_ptr<const SphMesh> mesh);
  /// The mesh the tree was built on.
  const SphMesh& mesh() const { return mesh_; }
  /// The answer of sph_mesh_inside over these triangles.
  bool inside(const std::array<float, 3>& p) const;
  /// True when some triangle lies nearer to p than sqrt(r2) (exact, as the minimum of sph_mesh_dist2 < r2).
  bool nearer_than(const std::array<float, 3>& p, float r2) const;

 private:
  struct Node {
    std::array<float, 3> lo, hi;         // box of the node's triangles (m)
    std::array<double, 3> centre, area;  // area-weighted centroid (m) and vector area A_C (m^2)
    double radius = 0;                   // farthest vertex from the centroid (m)
    int first = 0, count = 0;            // triangles [first, first + count) when a leaf
    int left = -1, right = -1;           // children, -1 for a leaf
  };
  int build(int first, int count);
  double winding_sum(int node, const std::array<float, 3>& p) const;
  bool nearer(int node, const std::array<float, 3>& p, float r2) const;

  std::shared_ptr<const SphMesh> owner_;  // set by the shared-mesh constructor
  const SphMesh& mesh_;
  std::vector<std::array<int, 3>> given_, tris_;  // as given, and in the tree's order
  std::vector<Node> nodes_;
};

}  // namespace huygens
