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
//   C = (1 - F) [ G T + W (1 - T) ] + F S + g L,   T = exp(-a_rgb d),
// G the lit ground colour at the refracted ground point, d the path length in the water,
// W the water colour, S the sky colour, L the sun colour, and F either the paper's
// f = clamp(1 - 2.5 n.v) or Schlick's F0 + (1 - F0)(1 - n.v)^5, F0 = ((index-1)/(index+1))^2,
// g = clamp(100 n.h - 98.95) with h the half vector between the viewer and the sun.
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "camera.hpp"
#include "gl.hpp"
#include "refraction.hpp"

namespace huygens {

enum class FresnelModel : int { off = 0, paper = 1, schlick = 2 };
enum class GroundPattern : int { tiles = 0, checker = 1, uniform = 2 };

/// What the renderer draws and how (all colours are display values in [0, 1]).
struct RenderSettings {
  /// Refractive index of the water (unit: 1).
  float index = 1.333f;
  /// true: exact Snell per pixel; false: the paper's linearised texture coordinates.
  bool exact_refraction = false;
  FresnelModel fresnel = FresnelModel::paper;
  /// Sun glint g = clamp(100 n.h - 98.95).
  bool sun_glint = true;
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
  /// Blur the caustics (accumulation-buffer emulation) when caustics are on.
  bool blur = true;
  /// Blur in a float target instead of the paper's 8-bit accumulation-buffer emulation.
  bool blur_float = false;
  bool draw_water = true;
  bool draw_ship = true;
  GroundPattern ground = GroundPattern::tiles;
  /// Checker/tile squares across the visible region (unit: 1).
  int ground_squares = 8;
  /// Colour of a uniform ground (unit: 1).
  glm::vec3 ground_uniform{0.8f, 0.7f, 0.5f};
  /// Background colour behind everything (unit: 1).
  glm::vec3 clear_colour{0.33f, 0.55f, 0.85f};
};

/// A ship drawn as a Wigley hull y = B/2 (1 - (2x/L)^2)(1 - (z/T)^2) below the waterline.
struct ShipPose {
  /// Centre position (unit: m) and heading from +x toward +y (unit: rad).
  double x = 0.0, y = 0.0, heading = 0.0;
  /// Length, beam, draft (unit: m).
  double length = 1.0, beam = 0.3, draft = 0.05;
};

/// Colour texture (RGBA8) + depth renderbuffer + framebuffer object.
class RenderTarget {
 public:
  RenderTarget() = default;
  RenderTarget(int width, int height);
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;
  RenderTarget(RenderTarget&& o) noexcept;
  RenderTarget& operator=(RenderTarget&& o) noexcept;
  int width() const { return w_; }
  int height() const { return h_; }
  GLuint fbo() const { return fbo_; }
  const gl::Texture& color() const { return color_; }
  void bind() const;
  /// RGBA8 pixels, top row first.
  gl::Image8 read() const;

 private:
  gl::Texture color_;
  GLuint depth_ = 0, fbo_ = 0;
  int w_ = 0, h_ = 0;
};

/// Wall time of each render pass of the last frame (unit: ms; measured with glFinish
/// when `RenderTimes::enabled`). `prepare` is the CPU part of set_heights (weighted-average
/// mesh heights and the full-resolution height differences), always measured.
struct RenderTimes {
  bool enabled = false;
  double prepare = 0, upload = 0, caustics = 0, ground = 0, surface = 0, ship = 0;
};

class CausticsStage;  // wraps the caustics pass (viz/caustics.hpp) when it is built

class WaterRenderer {
 public:
  /// `grid`: the visible heightfield's placement; `ground_z` < 0 the ground height (m).
  WaterRenderer(const GridPlacement& grid, double ground_z, int subsample);
  ~WaterRenderer();

  const GridPlacement& grid() const { return grid_; }
  double ground_z() const { return ground_z_; }
  int subsample() const { return subsample_; }
  /// Texel size of the ground texture (unit: m): the visible width over 512.
  double ground_texel() const;

  /// New heights of the visible field (rows x cols, m): mesh by weighted average, differences.
  void set_heights(std::span<const float> eta);
  /// Level subtracted from every height given to set_heights (unit: m; SceneGeometry::height_offset).
  void set_height_offset(double offset) { offset_ = static_cast<float>(offset); }
  void set_ships(std::span<const ShipPose> ships) { ships_.assign(ships.begin(), ships.end()); }
  /// Draw into `target` as seen by `camera`.
  void render(const OrbitCamera& camera, const RenderSettings& settings, const RenderTarget& target);

  RenderTimes times;

 private:
  void build_surface_mesh();
  void draw_surface(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp) const;
  void draw_ships(const OrbitCamera& camera, const RenderSettings& s, const glm::mat4& mvp);
  void update_linearisation(const OrbitCamera& camera, float index);
  void build_ground_texture(const RenderSettings& s);
  void set_common_uniforms(const gl::Program& p, const RenderSettings& s, const OrbitCamera& cam) const;

  GridPlacement grid_;
  double ground_z_;
  int subsample_;
  SurfaceMeshLayout layout_;
  std::vector<float> eta_, mesh_h_, diffs_;
  std::vector<ShipPose> ships_;

  gl::Program surface_prog_, ground_prog_, ship_prog_;
  gl::Texture diffs_tex_, coef_tex_, ground_tex_, flat_light_tex_;
  GLuint surface_vao_ = 0, surface_static_vbo_ = 0, surface_h_vbo_ = 0, surface_lin_vbo_ = 0, surface_ibo_ = 0;
  GLsizei surface_index_count_ = 0;
  GLuint ground_vao_ = 0, ground_vbo_ = 0;
  GLuint ship_vao_ = 0, ship_vbo_ = 0;
  GLsizei ship_vertex_count_ = 0;
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
