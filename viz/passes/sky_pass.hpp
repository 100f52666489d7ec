#pragma once
// The sky pass (docs/viz.md "Sky and far sea"): what no geometry covered, drawn last at the far
// plane: the sky, or below the horizon the open sea or the pool's deck going on to it
// (shaders/background.frag). With an ambient wind sea (deep-water looks) the flat sea beyond the
// visible region is shaded with its slopes, computed by the solver's FarSeaSlopes at the display
// time and kept in a mipmapped texture repeated every length_m, so the sea goes on to the horizon.
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "gl.hpp"
#include "huygens/pipeline/render_info.hpp"
#include "shading.hpp"

namespace huygens {

class SkyPass {
 public:
  SkyPass();
  ~SkyPass();
  SkyPass(const SkyPass&) = delete;
  SkyPass& operator=(const SkyPass&) = delete;

  /// The ambient wind sea (WaterRenderer::set_ambient_sea).
  void set_ambient_sea(const RenderAmbientSea& sea);
  /// The ambient sea's time (unit: s; computed by the next update that draws it).
  void set_sea_time(double t) { sea_request_ = t; }
  /// The time the slopes were last computed for (unit: s; NaN: never).
  double sea_slopes_time() const { return sea_time_; }
  /// Cox & Munk's mean square slope for the wind speed, 0.003 + 5.12e-3 U, less what the texture
  /// resolves (beyond the region) and what the region's central differences resolve (unit: 1).
  double unresolved_slope_var() const { return sea_unresolved_var_; }
  double region_unresolved_slope_var() const { return region_unresolved_var_; }
  /// The sea's slopes at the requested time, when this picture draws them and they are not already
  /// there (one n x n inverse FFT on this thread, the upload and the mipmap).
  void update(const RenderSettings& s);
  /// The far sea this picture shades with (deep water with the ambient sea on), else none.
  std::optional<ShadingScene::FarSea> far_sea(const RenderSettings& s) const;
  void draw(const FrameContext& f, const ShadingScene& scene) const;

 private:
  gl::Program prog_;
  GLuint empty_vao_ = 0;
  GLuint sea_sampler_ = 0;  // the background's sampler of sea_tex_: trilinear, not anisotropic
  std::shared_ptr<FarSeaSlopes> sea_;
  double sea_time_ = std::numeric_limits<double>::quiet_NaN(), sea_request_ = 0.0;
  std::vector<float> sea_texels_;  // per texel d eta/dx, d eta/dy, their squares' sum, 0
  double sea_unresolved_var_ = 0.0, region_unresolved_var_ = 0.0;
  gl::Texture sea_tex_;  // RGBA32F sea_texels_, mipmapped, repeated
};

}  // namespace huygens
