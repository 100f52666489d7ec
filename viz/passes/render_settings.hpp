#pragma once
// What the scene renderer draws and how (docs/viz.md): one struct of switches and colours that
// every pass reads. A look (viz/app/looks.hpp) fills it; the scene's "render" block and the
// window's panel change it.
//
// Colours are given as sRGB values and decoded to linear radiance on input (srgb.hpp); the passes
// shade in linear radiance and the tone map pass encodes sRGB once at the end, so the render tests
// compare pixels with closed forms in linear light put through the same encoding. The water pixel is
//   C = (1 - F) [ G T + W (1 - T) ] + F S(r) + g L,   T = exp(-a_rgb d),
// G the lit ground colour at the refracted ground point (W alone for deep water with no
// floor), d the path length in the water, W the water colour, S(r) the sky in the reflected
// direction r (uniform, or a horizon-to-zenith gradient), L the sun colour, F either the
// paper's f = clamp(1 - 2.5 n.v) or Schlick's F0 + (1 - F0)(1 - n.v)^5,
// F0 = ((index-1)/(index+1))^2 (paper 003), and g the glint: the paper's clamp(100 n.h - 98.95)
// (h the half vector between the viewer and the sun) or the sun reflected by the facets of the
// surface's slope spread, g = E_sun F(h.v) D(h) G1 G1 / (4 n.v) (Beckmann's D of the unresolved,
// per-pixel and mipmap slope variance; shaders/ground_common.glsl, glint).
// Everything is drawn in a half-float target (no clamping: caustics and glints exceed 1) and
// tone-mapped once at the end into the 8-bit image (tone_map_pass.hpp).
#include <glm/glm.hpp>

#include "huygens/pipeline/render_info.hpp"

namespace huygens {

enum class FresnelModel : int { off = 0, paper = 1, schlick = 2 };
/// How the caustics texture is made (docs/viz.md "Caustics", measured error there):
/// conserving = explicit area per triangle, exact Snell projection of the vertices, float
/// target, float blur (the default, light conserved); mip_paper = the paper's MIP trick in the 8-bit target with the
/// accumulation-buffer blur emulation; mip_float = the MIP trick in a float target; explicit_u8 = explicit area in the
/// 8-bit target (unit light = 32/255, saturates at 8x); simple = paper 000's eq. 4 from the heights and
/// normals (viz::simple_caustics, on the CPU).
enum class CausticsMode : int { conserving = 0, mip_paper = 1, mip_float = 2, explicit_u8 = 3, simple = 4 };
/// How the scene looks (SceneView::look, chosen from RenderInfo, docs/viz.md "Looks").
/// The kind of picture: the render description's LookRequest itself (the scene's "render.look", else
/// the solver's RenderInfo::default_look), no second enum to map.
using Look = LookRequest;
enum class GroundPattern : int { tiles = 0, checker = 1, uniform = 2 };
/// How the solids show in the water (docs/viz.md "Solids in and through the water"): not at all
/// (the surface refracts the floor and reflects the sky only), traced exactly per pixel against
/// the boxes, cylinders and hulls (shaders/solids_trace.glsl), or by paper 000's maps from virtual
/// eye points (virtual_eye_maps.hpp; meshes too). Shadows are traced unless off.
enum class SolidOptics : int { off = 0, trace = 1, virtual_eye = 2 };

/// What the renderer draws and how (all colours are sRGB values in [0, 1], decoded on input).
struct RenderSettings {
  /// Refractive index of the water (unit: 1).
  float index = 1.333f;
  /// true: exact Snell per pixel; false: the paper's linearised texture coordinates.
  bool exact_refraction = false;
  FresnelModel fresnel = FresnelModel::schlick;
  /// Open ocean with an ambient sea (WaterRenderer::set_ambient_sea): the sea beyond the region
  /// takes its slopes (false: flat, as when the wind is switched off).
  bool ambient_sea = true;
  /// Sun glint (the sun reflected by the facets of a rough surface, or the paper's
  /// clamp(100 n.h - 98.95)).
  bool sun_glint = true;
  /// The paper's glint g = clamp(100 n.h - 98.95) instead of the rough surface's.
  bool paper_glint = false;
  /// The sun's angular radius (unit: rad).
  float sun_radius_rad = 0.0047f;
  /// The sun's irradiance on a plane facing it over the sky's radiance at the horizon (unit: sr;
  /// a clear day's is of order 10-20). The glint's radiance is E_sun F D G / (4 n.v)
  /// (shaders/ground_common.glsl): bright where the facets that reflect the sun are many.
  float sun_irradiance = 0.011f;
  /// Mean square slope of the waves shorter than the heightfield's grid, which widen the glint
  /// (unit: 1); the open sea adds its own (WaterRenderer::unresolved_slope_var).
  float slope_var = 0.0f;
  /// Sky seen in the reflection: sky_colour at the horizon to sky_zenith overhead
  /// (S = mix(horizon, zenith, sqrt(r_z))); false = the uniform sky_colour.
  bool sky_gradient = true;
  glm::vec3 sky_zenith{0.12f, 0.30f, 0.66f};
  /// Open ocean: no floor, the refracted light is the deep water's colour W.
  bool deep_water = false;
  /// Pool deck at the rest level around the visible region (pool/pond/LBM/SPH looks) and the
  /// walls seen through the water where the refracted ray leaves the floor under the region.
  bool pool_deck = false;
  /// Tone map once at the end (identity up to `tone_knee`, then a soft shoulder to 1); off = clamp.
  bool tone_map = true;
  float tone_knee = 0.8f;
  /// Depth colour and absorption exp(-a_rgb d).
  bool absorption = true;
  /// Absorption coefficients of the water per channel (unit: 1/m).
  glm::vec3 absorb_rgb{0.45f, 0.075f, 0.035f};
  /// Colour the water tends to along a long path (unit: 1).
  glm::vec3 water_colour{0.0f, 0.10f, 0.14f};
  /// Uniform sky colour (unit: 1).
  glm::vec3 sky_colour{0.33f, 0.55f, 0.85f};
  /// Sun colour added by the glint (unit: 1).
  glm::vec3 sun_colour{1.0f, 0.96f, 0.88f};
  /// Direction toward the sun (normalised on use).
  glm::vec3 sun_dir{0.35f, 0.8f, 0.5f};
  /// Ground lighting: ambient + sun * caustics (1 for a flat surface) (unit: 1).
  float ambient = 0.35f, sun_light = 0.65f;
  /// Light the ground with the caustics pass (when it is available).
  bool caustics = true;
  CausticsMode caustics_mode = CausticsMode::conserving;
  /// Caustics mesh vertices per side; 0 = follow the field (~8 cells per dominant wavelength,
  /// up to the grid's resolution, viz::mesh_size_for_field).
  int caustics_mesh = 0;
  /// Blur the caustics ([1 2 1]^2 / 16, paper 004 sec. 6) when caustics are on.
  bool blur = true;
  /// 8-bit modes: blur in float instead of the paper's accumulation-buffer emulation (float
  /// targets always blur in float).
  bool blur_float = false;
  /// Leave out water thinner than WaterRenderer::kDryDepth over the flat floor too (the SPH
  /// look: a column the particles have left is dry, not a film of water on the floor).
  bool hide_dry = false;
  bool draw_water = true;
  bool draw_ship = true;
  /// Obstacles (RenderInfo::obstacles) as solid blocks above the water.
  bool draw_solids = true;
  /// The solids seen through the surface and reflected in it.
  SolidOptics solid_optics = SolidOptics::trace;
  /// Tint the water with the dye the flow carries (set_dye; LBM scenes, paper 002).
  bool dye = true;
  glm::vec3 dye_colour{0.75f, 0.12f, 0.45f};
  /// Foam the flow carries (set_foam; LBM scenes, paper 002 sec. 3.2, foam.hpp) as a white,
  /// rough overlay on the water: C' = mix(C, foam_colour (ambient + sun_light n.l / l_z), a)
  /// (lit like the flat ground where the water is flat), a = clamp(f (0.25 + 1.5 q)), q a fixed
  /// value noise over the grid points (surface.frag).
  bool foam = true;
  glm::vec3 foam_colour{0.95f, 0.96f, 0.97f};
  GroundPattern ground = GroundPattern::tiles;
  /// Checker squares across the visible region; for tiles, the tiles the texture holds, each
  /// WaterRenderer::tile_m() wide (unit: 1).
  int ground_squares = 8;
  /// Colour of a uniform ground (unit: 1).
  glm::vec3 ground_uniform{0.8f, 0.7f, 0.5f};
};

}  // namespace huygens
