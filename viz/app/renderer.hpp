#pragma once
// The scene renderer of huygens-viz (docs/design.md 5, docs/viz.md, paper 004 section 4): the
// ground plane, the water surface as a subsampled mesh with per-pixel normals from a
// full-resolution height-difference texture, refraction of the ground (linearised texture
// coordinates or exact Snell per pixel), Fresnel sky reflection and sun glint, depth
// colour and per-channel absorption, and the ship hulls. Everything is drawn into a
// RenderTarget (colour texture + depth buffer); the window blits it to the screen and the
// headless mode reads it back.
//
// Colours are display values (no sRGB conversion), so the render tests can compare pixels
// with closed forms: the water pixel is
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
// tone-mapped once at the end into the 8-bit image: identity up to the knee k, then
// k + (1 - k)(1 - exp(-(x - k)/(1 - k))) (C1, saturates at 1).
#include <algorithm>
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "camera.hpp"
#include "gl.hpp"
#include "huygens/pipeline/render_info.hpp"
#include "refraction.hpp"

namespace huygens {

enum class FresnelModel : int { off = 0, paper = 1, schlick = 2 };
/// How the caustics texture is made (docs/viz.md "Caustics", measured error there):
/// conserving = explicit area per triangle, exact Snell projection of the vertices, float
/// target, float blur (the default, light conserved); mip_paper = the paper's MIP trick in the 8-bit target with the
/// accumulation-buffer blur emulation; mip_float = the MIP trick in a float target; explicit_u8 = explicit area in the
/// 8-bit target (unit light = 32/255, saturates at 8x).
enum class CausticsMode : int { conserving = 0, mip_paper = 1, mip_float = 2, explicit_u8 = 3 };
/// How the scene looks (SceneView::look, chosen from RenderInfo, docs/viz.md "Looks").
/// The kind of picture: the render description's LookRequest itself (the scene's "render.look", else
/// the solver's RenderInfo::default_look), no second enum to map.
using Look = LookRequest;
enum class GroundPattern : int { tiles = 0, checker = 1, uniform = 2 };

/// What the renderer draws and how (all colours are display values in [0, 1]).
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

/// A ship drawn as a Wigley hull y = B/2 (1 - (2x/L)^2)(1 - (z/T)^2) below the waterline.
struct ShipPose {
  /// Centre position (unit: m) and heading from +x toward +y (unit: rad).
  double x = 0.0, y = 0.0, heading = 0.0;
  /// Length, beam, draft (unit: m).
  double length = 1.0, beam = 0.3, draft = 0.05;
  /// Afloat (float_ship): height of the rest waterline (unit: m) and the surface's slope along and
  /// across the heading (unit: 1) the hull is drawn with; 0 = level at the rest level.
  double heave = 0.0, slope_along = 0.0, slope_across = 0.0;
};

/// The drawn hull's freeboard, its deck's height above the waterline (unit: m): 0.08 of its length
/// (small craft carry 0.07-0.1; the 8 m boat of ocean.json 0.64 m: with 0.04 the crests of its
/// sea broke through the deck), at least 0.6 of its draft.
inline double hull_freeboard(const ShipPose& s) { return std::max(0.6 * s.draft, 0.08 * s.length); }

/// A hull afloat on the heights `eta` (rows x cols of `g`, m): the least-squares plane through the
/// surface sampled on rings 0.6 to 0.8 hull lengths from the hull's centre (outside the hull, and
/// a hull does not follow waves much shorter than itself) gives its heave and its slopes along and
/// across the heading (each kept within +-0.3). Ring points outside the grid are left out; with
/// none inside the hull stays level at 0. A drawing aid, not ship dynamics: the solver's hull is
/// a pressure patch moving on its path.
void float_ship(const GridPlacement& g, std::span<const float> eta, ShipPose& s);

/// Where the scene is drawn: a half-float colour buffer + depth renderbuffer (bind()), with
/// `samples` samples per pixel (multisample anti-aliasing: the edges of hulls, solids, the water's
/// outline and the deck are covered in part by each pixel; 1 = none), resolved into the
/// half-float texture hdr() (resolve_scene()); and the 8-bit display image (fbo(), color(),
/// read()) the renderer tone-maps that into.
class RenderTarget {
 public:
  /// Samples per pixel by default (clamped to what the driver offers).
  static constexpr int kDefaultSamples = 4;
  RenderTarget() = default;
  RenderTarget(int width, int height, int samples = kDefaultSamples);
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;
  RenderTarget(RenderTarget&& o) noexcept;
  RenderTarget& operator=(RenderTarget&& o) noexcept;
  int width() const { return w_; }
  int height() const { return h_; }
  /// The 8-bit display image's framebuffer (blit / read from here).
  GLuint fbo() const { return fbo_; }
  const gl::Texture& color() const { return color_; }
  /// Binds the half-float scene framebuffer for drawing.
  void bind() const;
  /// The drawn scene into hdr(): the samples of each pixel averaged (a blit; nothing without
  /// multisampling).
  void resolve_scene() const;
  int samples() const { return samples_; }
  const gl::Texture& hdr() const { return hdr_; }
  GLuint hdr_fbo() const { return hdr_fbo_; }
  /// RGBA8 pixels, top row first.
  gl::Image8 read() const;

 private:
  void release();
  gl::Texture color_, hdr_;
  GLuint depth_ = 0, fbo_ = 0, hdr_fbo_ = 0;
  GLuint ms_fbo_ = 0, ms_color_ = 0;  // the multisampled scene (samples_ > 1)
  int w_ = 0, h_ = 0, samples_ = 1;
};

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
  /// The floor tiles' side (GroundPattern::tiles; unit: m): the 1-2-5 length nearest an eighth of
  /// the visible region's longer side, the tiles square and aligned with the frame's origin, so
  /// the floor is a ruler (a 20 cm tank and a 15 m pool no longer look alike).
  double tile_m() const;

  /// New heights of the visible field (rows x cols, m): mesh by weighted average, differences.
  void set_heights(std::span<const float> eta);
  /// Level subtracted from every height given to set_heights (unit: m; SceneGeometry::height_offset).
  void set_height_offset(double offset) { offset_ = static_cast<float>(offset); }
  void set_ships(std::span<const ShipPose> ships) { ships_.assign(ships.begin(), ships.end()); }
  /// Dye per grid point (rows x cols, in [0, 1]; dye.hpp) that tints the water; empty = none.
  void set_dye(std::span<const float> dye);
  /// Foam per grid point (rows x cols, in [0, 1]; foam.hpp) drawn over the water; empty = none.
  void set_foam(std::span<const float> foam);
  /// The bed under the water (rows x cols, m, the heights' frame before the offset; RenderInfo::
  /// bed_m) for shallow water over terrain: drawn as lit terrain, the water refracted down to it
  /// and left out where it is thinner than kDryDepth (dry land shows). Empty = a flat floor.
  /// Call after set_height_offset and before set_obstacles.
  void set_bed(std::span<const float> bed);
  /// Water thinner than this is not drawn over a bed (unit: m).
  static constexpr float kDryDepth = 0.002f;
  /// Obstacles: drawn as solids, and the heights inside them (a solver leaves them dry or
  /// empty) replaced by the nearest water point's, so the surface closes around them. A mesh
  /// obstacle is drawn as its triangles (lit like the other solids); the water may run over it,
  /// so its heights are only kept from dropping below the mesh's top (a dry column then lies
  /// inside the solid), and the plan view shows its footprint's outline.
  void set_obstacles(std::span<const RenderObstacle> obstacles);
  /// The ambient wind sea (deep_water looks): the flat sea beyond the visible region is shaded with
  /// its slopes at the time set_sea_time gives (the solver's FarSeaSlopes, n x n on its periodic grid, a
  /// mipmapped texture repeated every length_m), so the sea goes on to the horizon.
  void set_ambient_sea(const RenderAmbientSea& sea);
  /// The ambient sea's time (unit: s; the display time of the heights). Its slopes are computed
  /// (one n x n inverse FFT, on this thread) and uploaded by the next render that draws them
  /// (RenderSettings::deep_water and ambient_sea) when the time changed: none while the wind is
  /// switched off.
  void set_sea_time(double t) { sea_request_ = t; }
  /// The time the ambient sea's slopes were last computed for (unit: s; NaN: never).
  double sea_slopes_time() const { return sea_time_; }
  /// Mean square slope of the ambient sea's waves shorter than its grid (unit: 1): Cox & Munk's
  /// for the wind speed, 0.003 + 5.12e-3 U (U in m/s; 1954, clean surface, their wind at 12.5 m
  /// taken as the scene's at 10 m), less the mean square slope the grid resolves (at least 0):
  /// beyond the region its slopes' (spectral), in the region the central differences' of its
  /// heights (region_unresolved_slope_var). The glint of a deep_water picture with the wind on
  /// (ambient_sea) adds it to RenderSettings::slope_var. 0 without a sea.
  double unresolved_slope_var() const { return sea_unresolved_var_; }
  double region_unresolved_slope_var() const { return region_unresolved_var_; }
  /// A particle solver's container, the box (0, 0, 0)-(box_m) (m, before the height offset): its
  /// four side walls from the floor to the lid, pale, each left out while the eye is outside
  /// it (the tank seen through its near walls: a backdrop for a slab seen from the side).
  void set_tank(const std::array<double, 3>& box_m);
  /// Draws `values` (rows x cols, the visible field) as a colour map seen from straight above,
  /// with a colour bar, axes in metres and a title (plan view, docs/viz.md); `diverging` uses
  /// a blue-white-red map symmetric about 0, else a sequential one from the minimum (viridis, or
  /// white to `hue` when one is given).
  void render_plan(std::span<const float> values, const std::string& quantity, double unit_scale,
                   const std::string& unit, bool diverging, const std::string& title, const RenderTarget& target,
                   std::optional<glm::vec3> hue = std::nullopt);
  /// Draw into `target` as seen by `camera`.
  void render(const OrbitCamera& camera, const RenderSettings& settings, const RenderTarget& target);

  RenderTimes times;
  /// The last plan view's plot: its rectangle in pixels (from the image's top-left corner, the
  /// grid's row 0 at the bottom) and the colour bar's range (unit: the plan's unit).
  struct PlanPlot {
    double x0 = 0, y0 = 0, width = 0, height = 0, lo = 0, hi = 1;
  } plan;
  /// Pixels the plan view leaves free on the right (the window's panel) (unit: px).
  double plan_reserve_right = 0.0;

 private:
  void build_surface_mesh();
  void draw_surface(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) const;
  void draw_ships(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp);
  void update_linearisation(const OrbitCamera& camera, float index);
  void build_ground_texture(const RenderSettings& s);
  // uploads a rows x cols field into tex (R32F, linear; made on first use); false if the size is wrong
  bool upload_grid_field(std::span<const float> values, gl::Texture& tex) const;
  void draw_solids(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp);
  void add_mesh_solids(std::span<const RenderObstacle> obstacles);
  void add_prism_solids(std::span<const RenderObstacle> obstacles);
  void upload_frame(const OrbitCamera& camera, const RenderSettings& s);
  static void reset_scene_state();
  void draw_ground(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp);
  void fill_footprints(std::span<const RenderObstacle> obstacles);
  void draw_tank(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp);
  void draw_terrain(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp);
  void draw_background(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) const;
  void update_sea_slopes(const RenderSettings& s);
  void draw_water_sides(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp);
  // the colours of ship.frag's u_solid
  enum class FlatKind { hull = 0, obstacle = 1, water_side = 2, tank_wall = 3 };
  void draw_flat(const std::vector<float>& tri, FlatKind kind, const OrbitCamera& camera, const RenderSettings& s,
                 const glm::mat4& mvp);
  void tone_map(const RenderSettings& s, const RenderTarget& target);
  void set_common_uniforms(const gl::Program& p, const RenderSettings& s, const OrbitCamera& cam) const;

  GridPlacement grid_;
  double ground_z_;
  int subsample_;
  SurfaceMeshLayout layout_;
  std::vector<float> eta_, mesh_h_, diffs_;
  std::vector<ShipPose> ships_;

  gl::Program surface_prog_, ground_prog_, ship_prog_, background_prog_;
  gl::Texture diffs_tex_, coef_tex_, ground_tex_, flat_light_tex_, dye_tex_, foam_tex_, bed_tex_;
  bool has_dye_ = false, has_foam_ = false, has_bed_ = false;
  GLuint terrain_vao_ = 0, terrain_vbo_ = 0;
  GLuint surface_vao_ = 0, surface_static_vbo_ = 0, surface_h_vbo_ = 0, surface_lin_vbo_ = 0, surface_ibo_ = 0;
  GLsizei surface_index_count_ = 0;
  GLuint ground_vao_ = 0, ground_vbo_ = 0;
  GLuint ship_vao_ = 0, ship_vbo_ = 0;
  std::vector<float> solids_;               // obstacle triangles (x, y, z)
  std::array<double, 3> tank_{};            // set_tank's box (m); 0 = none
  std::vector<std::uint32_t> fill_from_;    // per grid point: the point whose height it shows
  std::vector<float> mesh_top_;             // per grid point: a mesh obstacle's top (m), -inf off it
  std::vector<std::uint32_t> mesh_from_;    // per grid point: the nearest point outside the meshes' footprints
  std::vector<std::uint8_t> mesh_outline_;  // per grid point: on a mesh footprint's outline
  std::shared_ptr<FarSeaSlopes> sea_;       // set_ambient_sea: the solver's
  double sea_time_ = std::numeric_limits<double>::quiet_NaN(), sea_request_ = 0.0;
  std::vector<float> sea_texels_;       // per texel d eta/dx, d eta/dy, their squares' sum, 0
  double sea_unresolved_var_ = 0.0;     // unresolved_slope_var
  double region_unresolved_var_ = 0.0;  // region_unresolved_slope_var
  gl::Texture sea_tex_;                 // RGBA32F sea_texels_, mipmapped, repeated
  gl::Program tone_prog_;
  GLuint empty_vao_ = 0;
  GLuint sea_sampler_ = 0;  // the background's sampler of sea_tex_: trilinear, not anisotropic
  bool heights_dirty_ = true;
  float offset_ = 0.0f;

  // linearisation cache: recomputed when the view rays or the index change
  bool lin_valid_ = false;
  ViewRays lin_view_;
  float lin_index_ = 0.0f;
  int ground_key_ = -1;
  std::unique_ptr<CausticsStage> caustics_;
};

}  // namespace huygens
