#pragma once
// Triangles drawn flat-shaded in one colour per kind (shaders/ship.vert, ship.frag): the hulls,
// the obstacles, the water's sides and the tank's walls.
#include <vector>

#include "gl.hpp"
#include "shading.hpp"

namespace huygens {

/// The colours of ship.frag's u_solid.
enum class FlatKind { hull = 0, obstacle = 1, water_side = 2, tank_wall = 3 };

class FlatDrawer {
 public:
  FlatDrawer();
  ~FlatDrawer();
  FlatDrawer(const FlatDrawer&) = delete;
  FlatDrawer& operator=(const FlatDrawer&) = delete;
  /// Draws `tri` (x, y, z per vertex, m) lit by the sun from the camera of `f`.
  void draw(const std::vector<float>& tri, FlatKind kind, const FrameContext& f) const;

 private:
  gl::Program prog_;
  GLuint vao_ = 0, vbo_ = 0;
};

}  // namespace huygens
