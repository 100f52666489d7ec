#pragma once
// The scene renderer of huygens-viz (docs/design.md 5, docs/viz.md "Passes", paper 004 section 4):
// one frame runs the passes of viz/passes/ in order into a RenderTarget (a half-float colour
// texture + depth buffer; the window blits its 8-bit image to the screen and the headless mode
// reads it back):
//   upload     the view's refraction coefficients, the floor's pattern, the far sea's slopes, heights
//   caustics   the light under the surface into a texture (caustics_stage.hpp)
//   surface    the water with refraction, reflection, glint, absorption, and its sides (surface_pass)
//   solids     hulls, obstacles, tank walls (solids_pass)
//   ground     the floor and deck, or the terrain (ground_pass)
//   sky        what nothing covered: the sky, the far sea, the deck to the horizon (sky_pass)
//   tone map   the half-float scene into the 8-bit image (tone_map_pass)
// The plan view (plan_pass) draws instead of all of these. The settings every pass reads are in
// render_settings.hpp; the scene's look fills them (looks.hpp).
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "camera.hpp"
#include "flat_drawer.hpp"
#include "footprints.hpp"
#include "gl.hpp"
#include "ground_pass.hpp"
#include "huygens/pipeline/render_info.hpp"
#include "plot.hpp"
#include "refraction.hpp"
#include "render_settings.hpp"
#include "render_target.hpp"
#include "sky_pass.hpp"
#include "solid_geometry.hpp"
#include "solids_pass.hpp"
#include "surface_pass.hpp"
#include "tone_map_pass.hpp"
#include "traced_solids.hpp"
#include "virtual_eye_maps.hpp"

namespace huygens {

/// Wall time of each render pass of the last frame (unit: ms; measured with glFinish
/// when `RenderTimes::enabled`; `ship` includes the obstacles' solids, `tonemap` the final
/// pass into the 8-bit image). `prepare` is the CPU part of set_heights (weighted-average
/// mesh heights and the full-resolution height differences), always measured.
struct RenderTimes {
  bool enabled = false;
  double prepare = 0, upload = 0, caustics = 0, ground = 0, surface = 0, ship = 0, tonemap = 0;
  /// The same passes in process CPU time (all threads, llvmpipe's included; unit: ms): on a
  /// shared machine steadier than the wall times above, which wait for other programs too.
  struct Cpu {
    double upload = 0, caustics = 0, ground = 0, surface = 0, ship = 0, tonemap = 0;
  } cpu;
};

class CausticsStage;  // wraps the caustics pass (viz/gl/caustics.hpp) when it is built

class WaterRenderer {
 public:
  /// `grid`: the visible heightfield's placement; `ground_z` < 0 the ground height (m).
  WaterRenderer(const GridPlacement& grid, double ground_z, int subsample);
  ~WaterRenderer();

  const GridPlacement& grid() const { return grid_; }
  double ground_z() const { return ground_z_; }
  int subsample() const { return subsample_; }
  /// The floor tiles' side (GroundPass::tile_m; unit: m).
  double tile_m() const { return ground_.tile_m(); }

  /// New heights of the visible field (rows x cols, m): the offset subtracted, closed around the
  /// solids (Footprints::apply), the mesh by weighted average, the differences.
  void set_heights(std::span<const float> eta);
  /// Level subtracted from every height given to set_heights (unit: m; SceneGeometry::height_offset).
  void set_height_offset(double offset) { offset_ = static_cast<float>(offset); }
  void set_ships(std::span<const ShipPose> ships) { ships_.assign(ships.begin(), ships.end()); }
  /// Dye per grid point (rows x cols, in [0, 1]; dye.hpp) that tints the water; empty = none.
  void set_dye(std::span<const float> dye) { surface_.set_dye(dye); }
  /// Foam per grid point (rows x cols, in [0, 1]; foam.hpp) drawn over the water; empty = none.
  void set_foam(std::span<const float> foam) { surface_.set_foam(foam); }
  /// The bed under the water (rows x cols, m, the heights' frame before the offset; RenderInfo::
  /// bed_m) for shallow water over terrain: drawn as lit terrain, the water refracted down to it
  /// and left out where it is thinner than kDryDepth (dry land shows). Empty = a flat floor.
  /// Call after set_height_offset and before set_obstacles.
  void set_bed(std::span<const float> bed);
  /// Water thinner than this is not drawn over a bed (unit: m).
  static constexpr float kDryDepth = SurfacePass::kDryDepth;
  /// Obstacles: drawn as solids (SolidsPass), and the surface closed around them (Footprints).
  void set_obstacles(std::span<const RenderObstacle> obstacles);
  /// The ambient wind sea (deep_water looks; SkyPass): the flat sea beyond the visible region is
  /// shaded with its slopes at the time set_sea_time gives, so the sea goes on to the horizon.
  void set_ambient_sea(const RenderAmbientSea& sea) { sky_.set_ambient_sea(sea); }
  /// The ambient sea's time (unit: s; the display time of the heights), computed by the next render
  /// that draws it (none while the wind is switched off).
  void set_sea_time(double t) { sky_.set_sea_time(t); }
  /// The time the ambient sea's slopes were last computed for (unit: s; NaN: never).
  double sea_slopes_time() const { return sky_.sea_slopes_time(); }
  /// Mean square slope of the ambient sea's waves shorter than its grid, beyond the region and in
  /// it (SkyPass::unresolved_slope_var; unit: 1; 0 without a sea).
  double unresolved_slope_var() const { return sky_.unresolved_slope_var(); }
  double region_unresolved_slope_var() const { return sky_.region_unresolved_slope_var(); }
  /// A particle solver's container, the box (0, 0, 0)-(box_m) (m, before the height offset): its
  /// four side walls from the floor to the lid, pale, each left out while the eye is outside it.
  void set_tank(const std::array<double, 3>& box_m) { solids_.set_tank(box_m); }
  /// Draws `values` (rows x cols, the visible field) as a colour map seen from straight above,
  /// with a colour bar, axes in metres and a title (plan_pass.hpp).
  void render_plan(std::span<const float> values, const std::string& quantity, double unit_scale,
                   const std::string& unit, bool diverging, const std::string& title, const RenderTarget& target,
                   std::optional<glm::vec3> hue = std::nullopt);
  /// Draw into `target` as seen by `camera`.
  void render(const OrbitCamera& camera, const RenderSettings& settings, const RenderTarget& target);

  RenderTimes times;
  /// The last plan view's plot.
  PlanPlot plan;
  /// Pixels the plan view leaves free on the right (the window's panel) (unit: px).
  double plan_reserve_right = 0.0;

 private:
  SolidsFrame solids_frame() const { return {grid_, ground_z_, offset_, ground_.bed() != nullptr}; }
  ShadingScene shading_scene(const RenderSettings& s) const;
  void upload_frame(const OrbitCamera& camera, const RenderSettings& s);
  static void reset_scene_state();

  GridPlacement grid_;
  double ground_z_;
  int subsample_;
  float offset_ = 0.0f;
  std::vector<float> eta_;  // the visible heights after the offset, closed around the solids
  std::vector<ShipPose> ships_;
  std::vector<ShipPose> afloat_;              // the ships' poses afloat on the last frame's heights
  TracedSolids traced_;                       // the boxes, cylinders and hulls the surface's rays meet
  std::vector<Prism> prisms_;                 // the boxes and cylinders where they are drawn
  std::vector<EyeObject> mesh_objects_;       // the mesh obstacles as paper 000's objects
  std::vector<EyeObject> eye_objects_;        // this frame's objects for the virtual eye maps
  std::unique_ptr<VirtualEyeMaps> eye_maps_;  // made when solid_optics is first virtual_eye
  void build_eye_maps(const OrbitCamera& camera, const RenderSettings& s);
  Footprints footprints_;
  SurfacePass surface_;
  GroundPass ground_;
  FlatDrawer flat_;
  SolidsPass solids_;
  SkyPass sky_;
  ToneMapPass tone_;
  gl::Texture flat_light_tex_;  // the light under a still surface (1) when there are no caustics
  std::unique_ptr<CausticsStage> caustics_;
};

}  // namespace huygens
