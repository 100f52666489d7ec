// The scene's "render" block (huygens/pipeline/render_request.hpp).
#include "huygens/pipeline/render_request.hpp"

namespace huygens {

RenderRequest parse_render_request(const JsonIn& root) {
  RenderRequest r;
  const std::optional<JsonIn> block = root.optional_object("render");
  if (!block) return r;
  block->allow_only({"caustics", "blur", "caustics_mode", "look", "view", "camera", "sun", "foam"});
  if (block->has("caustics")) r.caustics = block->boolean("caustics", true);
  if (block->has("blur")) {
    const std::string b = block->string("blur", "accumulation", {"accumulation", "float", "none"});
    r.blur = b == "float" ? BlurMode::float_target : b == "none" ? BlurMode::none : BlurMode::accumulation;
  }
  if (block->has("caustics_mode")) {
    const std::string m =
        block->string("caustics_mode", "conserving", {"conserving", "mip_paper", "mip_float", "explicit_u8", "simple"});
    r.caustics_mode = m == "mip_paper"     ? CausticsModeRequest::mip_paper
                      : m == "mip_float"   ? CausticsModeRequest::mip_float
                      : m == "explicit_u8" ? CausticsModeRequest::explicit_u8
                      : m == "simple"      ? CausticsModeRequest::simple
                                           : CausticsModeRequest::conserving;
  }
  if (block->has("look")) {
    const std::string l = block->string("look", "pool", {"pool", "ocean", "shallow", "sph"});
    r.look = l == "ocean"     ? LookRequest::ocean
             : l == "shallow" ? LookRequest::shallow
             : l == "sph"     ? LookRequest::sph
                              : LookRequest::pool;
  }
  if (block->has("foam")) r.foam = block->boolean("foam", true);
  if (block->has("view")) r.plan_view = block->string("view", "perspective", {"perspective", "plan"}) == "plan";
  if (const std::optional<JsonIn> cam = block->optional_object("camera")) {
    cam->allow_only({"target_m", "distance_m", "yaw_deg", "pitch_deg", "follow_ship"});
    if (cam->has("target_m")) r.camera.target_m = cam->vec<3>("target_m", -1e6, 1e6);
    r.camera.distance_m = cam->optional_number("distance_m", 1e-3, 1e6);
    r.camera.yaw_deg = cam->optional_number("yaw_deg", -360.0, 360.0);
    r.camera.pitch_deg = cam->optional_number("pitch_deg", -90.0, 90.0);  // below 0: the eye below the target
    if (cam->has("follow_ship")) r.camera.follow_ship = cam->boolean("follow_ship", true);
  }
  if (const std::optional<JsonIn> sun = block->optional_object("sun")) {
    sun->allow_only({"elevation_deg", "azimuth_deg"});
    r.sun_elevation_deg = sun->optional_number("elevation_deg", 3.0, 90.0);
    r.sun_azimuth_deg = sun->optional_number("azimuth_deg", -360.0, 360.0);
  }
  return r;
}

}  // namespace huygens
