#pragma once
// The plan view (docs/viz.md "Plan view"): a grid's values seen from straight above as a colour
// map in a plot (plot.hpp), the solids and the ships' waterlines grey, NaN values (dry land) sand.
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>

#include "footprints.hpp"
#include "plot.hpp"
#include "solid_geometry.hpp"

namespace huygens {

/// What a plan view shows of `values` (rows x cols of the grid): the quantity and unit on its
/// colour bar (values x unit_scale), a diverging map symmetric about 0 or a sequential one from the
/// minimum (viridis, or white to `hue`), the title, and the pixels left free on the right.
struct PlanRequest {
  std::string quantity, unit, title;
  double unit_scale = 1.0;
  bool diverging = false;
  std::optional<glm::vec3> hue;
  double reserve_right = 0.0;
};

/// Draws the plan view into `target`; the colour range leaves out the solids and the dent under a
/// hull. Returns the plot's rectangle and range.
PlanPlot draw_plan_view(const GridPlacement& g, const Footprints& solids, std::span<const ShipPose> ships,
                        std::span<const float> values, const PlanRequest& rq, const RenderTarget& target);

}  // namespace huygens
