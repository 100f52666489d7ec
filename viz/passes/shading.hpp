#pragma once
// What every pass of a frame shares (docs/viz.md "Passes"): the frame (camera, settings, the
// camera's view-projection matrix) and the scene the lit programs shade with
// (shaders/ground_common.glsl: the ground's pattern, the caustics' light, the sea beyond the
// region), set by one function so that the ground, the surface and the sky agree.
#include <glm/glm.hpp>
#include <initializer_list>
#include <optional>

#include "camera.hpp"
#include "gl.hpp"
#include "refraction.hpp"
#include "render_settings.hpp"
#include "traced_solids.hpp"
#include "virtual_eye_maps.hpp"

namespace huygens {

/// One frame as every pass sees it.
struct FrameContext {
  const OrbitCamera& camera;
  const RenderSettings& s;
  /// projection * view for the target's aspect.
  glm::mat4 mvp;
};

/// What ground_common.glsl reads besides the settings.
struct ShadingScene {
  /// The visible heightfield's placement and the flat floor's height (unit: m).
  GridPlacement grid;
  double ground_z = 0.0;
  /// The floor tiles' side (unit: m; GroundPass::tile_m).
  double tile_m = 1.0;
  /// The caustics texture on unit 1 over the rectangle origin + extent (m), scaled to 1 for a still
  /// surface (CausticsStage); none: the flat light on unit 1.
  struct Caustics {
    glm::vec2 origin, extent;
    float scale = 1.0f;
  };
  std::optional<Caustics> caustics;
  /// The sea beyond the region (SkyPass::far_sea): its slopes' texture, bound to unit 7, repeated
  /// every length_m from the full grid's origin (n x n texels), and the mean square slopes the
  /// texture and the region's central differences leave unresolved (unit: 1).
  struct FarSea {
    const gl::Texture* slopes = nullptr;
    double length_m = 1.0;
    int n = 1;
    double unresolved_var = 0.0, region_var = 0.0;
  };
  std::optional<FarSea> far_sea;
  /// The solids the rays meet (RenderSettings::solid_optics); null: none.
  const TracedSolids* solids = nullptr;
  /// Paper 000's maps of the solids (solid_optics virtual_eye, bound to unit 8); null: none.
  const VirtualEyeMaps* eye_maps = nullptr;
};

/// The eye is under the water: a perspective eye below the rest level over the visible region (the
/// ground it sees directly is then seen through the water; the surface from below is drawn by
/// surface.frag wherever the eye is below it).
bool eye_under_water(const OrbitCamera& camera, const GridPlacement& g);

/// Makes `p` current and sets the uniforms ground_common.glsl reads.
void set_shading_uniforms(const gl::Program& p, const FrameContext& f, const ShadingScene& scene);

/// Sets the colour uniform `name` of the current program `p` to the sRGB colour `srgb` decoded to
/// linear radiance (srgb.hpp).
void set_colour(const gl::Program& p, const char* name, const glm::vec3& srgb);

/// A lit program: the fragment shader `fs` with shaders/solids_trace.glsl, ground_common.glsl and
/// then the shader files `also` in front of it.
gl::Program load_lit_program(const char* vs, const char* fs, std::initializer_list<const char*> also = {});

}  // namespace huygens
