#include "plan_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace huygens {

PlanPlot draw_plan_view(const GridPlacement& g, const Footprints& solids, std::span<const ShipPose> ships,
                        std::span<const float> values, const PlanRequest& rq, const RenderTarget& target) {
  const std::size_t R = g.rows, C = g.cols;
  std::vector<std::uint8_t> hull;
  mark_hulls(g, ships, hull);
  // the colour range: symmetric about 0 (heights) or from the minimum (depths), rounded out to
  // the colour bar's ticks
  double lo = 1e300, hi = -1e300;
  for (std::size_t k = 0; k < R * C; ++k) {
    if (solids.solid(k) || !std::isfinite(values[k]) || hull[k]) continue;
    lo = std::min(lo, rq.unit_scale * values[k]);
    hi = std::max(hi, rq.unit_scale * values[k]);
  }
  PlotSpec spec;
  spec.x0_m = g.x0 - 0.5 * g.dx, spec.y0_m = g.y0 - 0.5 * g.dx;  // the corner of cell (0, 0)
  spec.width_m = C * g.dx, spec.height_m = R * g.dx;
  spec.quantity = rq.quantity, spec.unit = rq.unit, spec.title = rq.title;
  plot_range(lo, hi, rq.diverging, spec);
  spec.hue = rq.hue;
  std::vector<std::uint8_t> px(R * C * 4);
  for (std::size_t k = 0; k < R * C; ++k) {
    const glm::vec3 c = solids.solid(k) || hull[k] ? glm::vec3(0.55f)
                        : !std::isfinite(values[k])
                            ? kPlanDryLand
                            : plan_colour((rq.unit_scale * values[k] - spec.lo) / (spec.hi - spec.lo), spec);
    for (int ch = 0; ch < 3; ++ch) px[4 * k + ch] = static_cast<std::uint8_t>(std::lround(255.0f * c[ch]));
    px[4 * k + 3] = 255;
  }
  const PlanPlot plot = plot_layout(target.width(), target.height(), spec, rq.reserve_right);
  draw_plot(plot, spec, px, static_cast<int>(C), static_cast<int>(R), target);
  return plot;
}

}  // namespace huygens
