#pragma once
// Walls and obstacles of the SPH container [0, Lx] x [0, Ly] x [0, Lz] (docs/sph.md "Walls").
// Container walls are mirror images: for each plane within h of particle i, every neighbour j has
// an image x_j' reflected across it (and across each pair and the triple of planes of different
// axes at edges and corners) carrying j's density, its mirrored velocity (free slip) and
//   p_j' = p_j + rho_j g . (x_j' - x_j)     (Adami, Hu and Adams 2012 eq. 27, wall at rest).
// With d = x_i - x_j' = o + s X_j (s_a = +1 on reflected axes, else -1) the image's pressure term
// is P_j' = p_j'/rho_j^2 = P_j + (G0 + gs . X_j) / rho_j, G0 = sum_a 2 g_a w_a, gs_a = -2 g_a.
// Obstacles (box, vertical cylinder) use a tabulated one-plane ghost lattice on their signed
// distance d: density D1(d) = m sum W_poly6, force 2 (p_i/rho_i^2) |dD1/dd| along the normal.
#include <array>
#include <vector>

#include "huygens/sph/kernels.hpp"

namespace huygens {

/// A static rigid obstacle: an axis-aligned box, or a vertical cylinder standing on z0_m.
struct SphObstacle {
  enum class Type { box, cylinder };
  Type type = Type::box;
  /// Box lower corner (unit: m).
  std::array<float, 3> min_m{0.f, 0.f, 0.f};
  /// Box upper corner (unit: m).
  std::array<float, 3> max_m{0.f, 0.f, 0.f};
  /// Cylinder axis position x, y (unit: m).
  std::array<float, 2> centre_m{0.f, 0.f};
  /// Cylinder radius (unit: m).
  float radius_m = 0.f;
  /// Cylinder bottom and top heights (unit: m).
  float z0_m = 0.f, z1_m = 0.f;
  /// Signed distance (unit: m; negative inside) and outward unit normal at p.
  float distance(float px, float py, float pz, float n[3]) const;
  /// False when (x, y, z) is farther than `margin` (unit: m) from the bounding box (then the signed
  /// distance exceeds margin too): skips distance() for most particles.
  bool near(float x, float y, float z, float margin) const {
    const bool box = type == Type::box;
    const float x0 = box ? min_m[0] : centre_m[0] - radius_m, x1 = box ? max_m[0] : centre_m[0] + radius_m;
    const float y0 = box ? min_m[1] : centre_m[1] - radius_m, y1 = box ? max_m[1] : centre_m[1] + radius_m;
    const float zl = box ? min_m[2] : z0_m, zh = box ? max_m[2] : z1_m;
    return x > x0 - margin && x < x1 + margin && y > y0 - margin && y < y1 + margin && z > zl - margin &&
           z < zh + margin;
  }
};

/// A mirror image of the neighbours across container planes: d = o + s X_j (unit: m; s: 1).
struct SphImage {
  float o[3], s[3];
  /// Hydrostatic pressure of the image: P_j' = P_j + (G0 + gs . X_j) / rho_j (G0: m^2/s^2, gs: m/s^2).
  float G0, gs[3];
  /// 1 if the image is reflected across the floor z = 0 (its partners lie in the bottom cell layer).
  int floor;
};

/// The particle itself as an "image": d = x_i - X_j.
inline SphImage sph_self_image(float x, float y, float z) {
  SphImage im{};
  im.o[0] = x;
  im.o[1] = y;
  im.o[2] = z;
  return im;
}

/// The mirror images (at most 7) for a particle at (x, y, z) in a container of `container_m`
/// with walls within `h` (unit: m), for gravity `g` (unit: m/s^2); returns their count.
int sph_container_images(float x, float y, float z, float h, const std::array<float, 3>& container_m,
                         const std::array<float, 3>& g, SphImage* out);

/// The obstacles' ghost-lattice density and pressure force, tabulated over the signed distance.
class SphObstacleWalls {
 public:
  SphObstacleWalls() = default;
  /// Tables for particles of mass `mass` (unit: kg) on a lattice of `spacing` (unit: m).
  SphObstacleWalls(const std::vector<SphObstacle>& obstacles, const SphKernels& k, float spacing, float mass);
  bool empty() const { return obstacles_.empty(); }
  /// Adds D1(d) of every obstacle within h of (x, y, z) to rho (unit: kg/m^3).
  void add_density(float x, float y, float z, float& rho) const {
    if (!obstacles_.empty()) add_density_near(x, y, z, rho);
  }
  /// Adds P |dD1/dd| along each near obstacle's normal (P = l p / rho^2: m^5/(kg s^2); a: m/s^2).
  void add_force(float x, float y, float z, float P, float& ax, float& ay, float& az) const {
    if (P > 0.f && !obstacles_.empty()) add_force_near(x, y, z, P, ax, ay, az);
  }

 private:
  // the checks above inline (most scenes have no obstacle), the table look-ups out of line
  void add_density_near(float x, float y, float z, float& rho) const;
  void add_force_near(float x, float y, float z, float P, float& ax, float& ay, float& az) const;
  std::vector<SphObstacle> obstacles_;
  float h_ = 0.f;
  int n1_ = 0;
  float inv1_ = 0.f;
  std::vector<float> d1_, f1_;
};

}  // namespace huygens
