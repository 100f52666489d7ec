#pragma once
// Plots drawn by the viewer for people who measure (docs/viz.md "Plan view", "Particle view"): an
// image of exact values placed in a rectangle that keeps the physical aspect, axes in metres, a
// colour bar in physical units and a title. The plan view draws the grid's values seen from
// above; the particle view draws a particle solver's particles seen from the side, coloured by
// speed.
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "huygens/pipeline/render_info.hpp"
#include "render_target.hpp"

namespace huygens {

/// A plot's rectangle in pixels (from the image's top-left corner; a plan view's grid row 0 at the
/// bottom) and its colour bar's range (unit: the plot's unit).
struct PlanPlot {
  double x0 = 0, y0 = 0, width = 0, height = 0, lo = 0, hi = 1;
};

/// The plot's colour map at t in [0, 1] (diverging: blue-white-red, else viridis).
glm::vec3 plan_colour(double t, bool diverging);
/// The plan view's colour of a NaN value (dry land over terrain): a sand tone outside both maps.
inline const glm::vec3 kPlanDryLand(0.80f, 0.72f, 0.55f);

/// A "nice" step (1, 2 or 5 times a power of ten) giving about `n` intervals over `range`.
double nice_step(double range, int n);

/// What a plot shows: the image's extent in metres, the axis names, and the colour bar.
struct PlotSpec {
  /// Lower-left corner of the image and its size (unit: m).
  double x0_m = 0, y0_m = 0, width_m = 1, height_m = 1;
  /// Axis names, e.g. "x (m)" and "y (m)".
  std::string x_label = "x (m)", y_label = "y (m)";
  /// The colour bar: quantity, unit, range [lo, hi] (unit: the plot's unit), tick step, map.
  std::string quantity, unit;
  double lo = 0, hi = 1, step = 0.2;
  bool diverging = false;
  /// A single-hue map from white (0) to this colour (1) instead (the dye).
  std::optional<glm::vec3> hue;
  std::string title;
};

/// The plot's own map at t in [0, 1]: white to spec.hue where a hue is set (the dye, in the colour
/// the perspective view tints the water with), else plan_colour(t, spec.diverging).
glm::vec3 plan_colour(double t, const PlotSpec& spec);

/// Where a plot goes in a W x H image (pixels from the top-left corner): the rectangle keeping
/// the aspect of width_m x height_m, leaving `reserve_right` pixels free on the right.
PlanPlot plot_layout(int W, int H, const PlotSpec& spec, double reserve_right);

/// The colour bar right of a plot (pixels from the top-left corner): its rectangle, as tall as
/// the plot, or, beside a plot too short for its tick labels (a 32:1 slab: 35 px at 1280x720),
/// the height that spaces the labels kTickPitch text scales apart, centred on the plot and kept
/// inside the image between the title's and the x axis' margins.
struct ColourBar {
  double x = 0, y = 0, width = 0, height = 0;
};
/// Vertical distance between two tick labels of the colour bar, in text scales: a glyph is 7
/// units high, so labels nearer than that overlap.
inline constexpr double kTickPitch = 12.0;
ColourBar colour_bar_layout(const PlanPlot& rect, const PlotSpec& spec, int H);

/// The colour bar's range of values in [lo, hi] rounded out to nice ticks (symmetric about 0
/// when `diverging`); sets spec.lo, hi and step.
void plot_range(double lo, double hi, bool diverging, PlotSpec& spec);

/// Draws the plot into `target`: white background, the RGBA image (iw x ih, row 0 at the bottom)
/// stretched over `rect`, the frame, axes with ticks in metres, the colour bar and the title.
void draw_plot(const PlanPlot& rect, const PlotSpec& spec, const std::vector<std::uint8_t>& rgba, int iw, int ih,
               const RenderTarget& target);

/// A caption in the top-left corner of `target`'s image: white text on a dark band, the text
/// scale as the plots' (glyphs ~7 px high up to 450 px of image height). Returns its width (px).
double draw_caption(const std::string& text, const RenderTarget& target);
/// The width (px) draw_caption would give `text` in an image `height` px high.
double caption_width(const std::string& text, int height);

/// A particle solver's particles (x, y, z, speed per particle: Solver::particles()) seen from the
/// side (-y), as discs of `radius_m` coloured by speed, nearer particles over farther ones and
/// shaded darker with distance, the obstacles as grey silhouettes at their depth (a mesh as its
/// triangles, lit, and the outline of its projection drawn over the particles in front of it),
/// inside the container box (0, 0, 0)-(box_m) drawn as the plot's frame. Returns the plot's
/// rectangle.
PlanPlot render_particles(std::span<const float> particles, const std::array<double, 3>& box_m, double radius_m,
                          std::span<const RenderObstacle> obstacles, const std::string& title, double reserve_right,
                          const RenderTarget& target);

}  // namespace huygens
