#pragma once
// The looks (docs/viz.md "Looks"): the kind of picture a scene is drawn as. Each look is one unit
// here: its name and the render settings it gives a scene's view; the scene's "render.look" or
// the solver's RenderInfo::default_look chooses it. A new look is a LookRequest value (core
// render_info.hpp, with its name in the scene parser) and one LookUnit in looks.cpp.
#include <span>

#include "camera.hpp"
#include "render_settings.hpp"

namespace huygens {

struct SceneView;

struct LookUnit {
  Look look;
  /// The scene's "render.look" name.
  const char* name;
  /// What the look draws, for --help and the docs.
  const char* summary;
  /// Sets what this look changes in `s` (defaults, the sun placed where the camera is) for the
  /// view and its start-up camera.
  void (*settings)(const SceneView& view, const OrbitCamera& camera, RenderSettings& s);
  /// The open sea: the ambient wind sea drawn beyond the region (SceneView::ambient_sea), a followed
  /// ship framed from low with the sea to the horizon.
  bool open_sea = false;
  /// A particle solver's container is a quasi-2D slab when its long side exceeds this many times
  /// its short side (other views: 8).
  double tank_slab_ratio = 8.0;
};

/// Every look, in LookRequest order.
std::span<const LookUnit> look_units();
/// The unit of `look`.
const LookUnit& look_unit(Look look);

}  // namespace huygens
