#include "shading.hpp"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "srgb.hpp"

namespace huygens {

gl::Program load_lit_program(const char* vs, const char* fs, std::initializer_list<const char*> also) {
  const std::string vsrc(gl::shader_source(vs));
  std::string fsrc = "#version 330 core\n" + std::string(gl::shader_source("solids_trace.glsl")) + "\n" +
                     std::string(gl::shader_source("ground_common.glsl")) + "\n";
  for (const char* a : also) fsrc += std::string(gl::shader_source(a)) + "\n";
  fsrc += gl::shader_source(fs);
  return gl::program_from_strings(vsrc, fsrc, std::string(vs) + " + " + fs);
}

bool eye_under_water(const OrbitCamera& camera, const GridPlacement& g) {
  const glm::dvec3 e = camera.eye();
  return !camera.ortho && e.z < 0.0 && e.x >= g.x(0) && e.x <= g.x(g.cols - 1) && e.y >= g.y(0) &&
         e.y <= g.y(g.rows - 1);
}

namespace {

// The eye, the sky, the sun, the water's colour and the Fresnel and glint models.
void set_view_and_light(const gl::Program& p, const FrameContext& f) {
  const RenderSettings& s = f.s;
  const ViewRays v = f.camera.rays();
  glUniform3f(p.loc("u_eye"), static_cast<float>(v.eye.x), static_cast<float>(v.eye.y), static_cast<float>(v.eye.z));
  glUniform1i(p.loc("u_ortho"), v.ortho ? 1 : 0);
  glUniform3f(p.loc("u_view_dir"), static_cast<float>(v.dir.x), static_cast<float>(v.dir.y),
              static_cast<float>(v.dir.z));
  glUniform1f(p.loc("u_index"), s.index);
  set_colour(p, "u_water_colour", s.water_colour);
  set_colour(p, "u_sky", s.sky_colour);
  glUniform1i(p.loc("u_sky_gradient"), s.sky_gradient ? 1 : 0);
  set_colour(p, "u_sky_zenith", s.sky_zenith);
  glUniform3fv(p.loc("u_sun_dir"), 1, glm::value_ptr(s.sun_dir));
  glUniform1i(p.loc("u_deep"), s.deep_water ? 1 : 0);
  glUniform1i(p.loc("u_absorption"), s.absorption ? 1 : 0);
  glUniform3fv(p.loc("u_absorb"), 1, glm::value_ptr(s.absorb_rgb));
  glUniform1f(p.loc("u_ambient"), s.ambient);
  glUniform1f(p.loc("u_sun_light"), s.sun_light);
  glUniform1i(p.loc("u_deck"), s.pool_deck ? 1 : 0);
  glUniform1i(p.loc("u_fresnel"), static_cast<int>(s.fresnel));
  glUniform1i(p.loc("u_glint"), !s.sun_glint ? 0 : s.paper_glint ? 1 : 2);
  glUniform1f(p.loc("u_sun_radius"), s.sun_radius_rad);
  glUniform1f(p.loc("u_sun_irradiance"), s.sun_irradiance);
  set_colour(p, "u_sun_colour", s.sun_colour);
}

// The ground's pattern, the floor under the region and the caustics' light on it.
void set_ground(const gl::Program& p, const FrameContext& f, const ShadingScene& scene) {
  const GridPlacement& g = scene.grid;
  glUniform1i(p.loc("u_ground"), 0);
  glUniform1i(p.loc("u_caustics"), 1);
  if (f.s.ground == GroundPattern::tiles) {  // square tiles of tile_m from the frame's origin
    const float e = static_cast<float>(std::max(1, f.s.ground_squares) * scene.tile_m);
    glUniform2f(p.loc("u_ground_origin"), 0.0f, 0.0f);
    glUniform2f(p.loc("u_ground_extent"), e, e);
  } else {  // the pattern spans the visible region
    glUniform2f(p.loc("u_ground_origin"), static_cast<float>(g.x0), static_cast<float>(g.y0));
    glUniform2f(p.loc("u_ground_extent"), static_cast<float>(g.cols * g.dx), static_cast<float>(g.rows * g.dx));
  }
  glUniform1i(p.loc("u_use_caustics"), scene.caustics ? 1 : 0);
  if (scene.caustics) {
    glUniform2f(p.loc("u_caustics_origin"), scene.caustics->origin.x, scene.caustics->origin.y);
    glUniform2f(p.loc("u_caustics_extent"), scene.caustics->extent.x, scene.caustics->extent.y);
    glUniform1f(p.loc("u_caustics_scale"), scene.caustics->scale);
  }
  glUniform1f(p.loc("u_ground_z"), static_cast<float>(scene.ground_z));
  // the floor under the visible region (walls beyond it when there is a deck)
  glUniform4f(p.loc("u_floor_rect"), static_cast<float>(g.x(0)), static_cast<float>(g.y(0)),
              static_cast<float>(g.x(g.cols - 1)), static_cast<float>(g.y(g.rows - 1)));
  glUniform1i(p.loc("u_eye_under"), eye_under_water(f.camera, g) ? 1 : 0);
}

// The wind's short waves (beyond the region those its texture does not resolve, in it u_region_var
// more: those its central differences do not) and the sea beyond the region.
void set_far_sea(const gl::Program& p, const FrameContext& f, const ShadingScene& scene) {
  const std::optional<ShadingScene::FarSea>& sea = scene.far_sea;
  glUniform1f(p.loc("u_slope_var"), static_cast<float>(f.s.slope_var + (sea ? sea->unresolved_var : 0.0)));
  glUniform1f(p.loc("u_region_var"), static_cast<float>(sea ? sea->region_var - sea->unresolved_var : 0.0));
  glUniform1i(p.loc("u_far"), sea ? 1 : 0);
  glUniform1i(p.loc("u_far_slopes"), 7);
  if (!sea) return;
  sea->slopes->bind(7);
  // texel centres at the grid points
  const float L = static_cast<float>(sea->length_m), h = 0.5f * L / static_cast<float>(sea->n);
  glUniform2f(p.loc("u_far_origin"), -h, -h);
  glUniform1f(p.loc("u_far_length"), L);
}

// The solids the rays are traced against (solids_trace.glsl): the surface's refracted and
// reflected rays, the sun's rays to the ground.
void set_traced_solids(const gl::Program& p, const FrameContext& f, const ShadingScene& scene) {
  const int n = scene.solids ? scene.solids->count() : 0;
  const bool on = f.s.solid_optics != SolidOptics::off && n > 0;
  glUniform1i(p.loc("u_trace_solids"), on ? static_cast<int>(f.s.solid_optics) : 0);
  glUniform1i(p.loc("u_traced_count"), on ? n : 0);
  if (on) glUniform4fv(p.loc("u_traced"), 3 * n, glm::value_ptr(scene.solids->packed()[0]));
  if (on) glUniform3fv(p.loc("u_traced_lo"), 1, glm::value_ptr(scene.solids->lo()));
  if (on) glUniform3fv(p.loc("u_traced_hi"), 1, glm::value_ptr(scene.solids->hi()));
  glUniform1i(p.loc("u_env_count"), 0);
  if (f.s.solid_optics == SolidOptics::virtual_eye && scene.eye_maps) scene.eye_maps->set_uniforms(p, 8);
}

}  // namespace

void set_colour(const gl::Program& p, const char* name, const glm::vec3& srgb) {
  const glm::vec3 linear = srgb_to_linear(srgb);
  glUniform3fv(p.loc(name), 1, glm::value_ptr(linear));
}

void set_shading_uniforms(const gl::Program& p, const FrameContext& f, const ShadingScene& scene) {
  p.use();
  set_view_and_light(p, f);
  set_ground(p, f, scene);
  set_far_sea(p, f, scene);
  set_traced_solids(p, f, scene);
}

}  // namespace huygens
