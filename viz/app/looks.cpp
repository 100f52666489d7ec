#include "looks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "scene_view.hpp"

namespace huygens {

namespace {

// Open ocean (paper 003): no floor, the deep water's colour, the sky and the sun's glint on the
// sea's facets, the waves shorter than the grid included (Cox & Munk's slope variance less what
// the grid resolves: SkyPass::unresolved_slope_var); the sun ahead of the viewer, 35 degrees up, so
// its glitter path lies in the view.
void ocean_look(const SceneView&, const OrbitCamera& camera, RenderSettings& s) {
  s.deep_water = true;
  s.pool_deck = true;  // the sea around the region, to the horizon (background.frag beyond it)
  s.caustics = false;
  s.water_colour = glm::vec3(0.03f, 0.16f, 0.25f);
  // the sun's irradiance over the sky's radiance: a display choice, a fifth to a tenth of a clear
  // day's 10-20 sr, so the tone map keeps the glitter path's structure
  s.sun_irradiance = 2.0f;
  const double az = camera.yaw + std::numbers::pi, el = 35.0 * (std::numbers::pi / 180.0);
  s.sun_dir = glm::vec3(static_cast<float>(std::cos(el) * std::cos(az)),
                        static_cast<float>(std::cos(el) * std::sin(az)), static_cast<float>(std::sin(el)));
}

// A basin with a floor (pool, pond, shallow water): the deck around it, caustics on the floor.
void basin_look(const SceneView& view, const OrbitCamera&, RenderSettings& s) {
  s.pool_deck = !view.slab;  // a slab is seen from the side: its profile, not a pool
  if (view.slab) {
    // seen from the side: a plain floor (tiles 8 across the slab's thin side are stripes) and no
    // caustics (the floor under a slab is seen edge-on)
    s.ground = GroundPattern::uniform;
    s.caustics = false;
  }
  if (!view.bed.empty()) {
    // water over terrain: shaded by its depth (absorption), dry land shows; no dye tint (--view dye
    // shows it) and no caustics (their mesh assumes a flat floor)
    s.dye = false;
    s.caustics = false;
  }
}

// A particle solver's tank: a basin where the particles left the floor dry, its water dyed as a lab
// does (centimetres of clear water barely tint the floor, so the absorption is scaled to show the
// water at rest in the colour of the pool look's 3 m: a_rgb kDeepGround / rest level, at least a_rgb).
void sph_look(const SceneView& view, const OrbitCamera& camera, RenderSettings& s) {
  basin_look(view, camera, s);
  s.hide_dry = true;
  if (view.height_offset > 0.0)
    s.absorb_rgb *= static_cast<float>(std::max(1.0, SceneView::kDeepGround / view.height_offset));
}

constexpr LookUnit kLooks[] = {
    {Look::pool, "pool", "a floor with tiles and caustics, a deck around the water", basin_look},
    {Look::ocean, "ocean", "open sea to the horizon, no floor, sky reflection and sun glint", ocean_look, true},
    {Look::shallow, "shallow", "a basin or terrain under shallow water, dry land shown", basin_look},
    // a particle solver's narrow tank (sph_wedge, 3:1) is a slab too: its dam break reads from the side
    {Look::sph, "sph", "a particle tank: dry floor where the particles left, lab-dyed water", sph_look, false, 2.5},
};

}  // namespace

std::span<const LookUnit> look_units() { return kLooks; }

const LookUnit& look_unit(Look look) {
  for (const LookUnit& u : kLooks)
    if (u.look == look) return u;
  throw std::logic_error("look_unit: a LookRequest without its LookUnit (viz/app/looks.cpp)");
}

}  // namespace huygens
