#pragma once
// The scene's "render" block read into the RenderRequest of render_info.hpp (each solver's scene
// parser calls it; the viewer parses no JSON).
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/render_info.hpp"

namespace huygens {

/// Reads the scene's optional "render" block below `root`: {"caustics": bool, "blur":
/// "accumulation" | "float" | "none", "caustics_mode": ..., "look": ..., "view": "perspective" |
/// "plan", "camera": {"target_m", "distance_m", "yaw_deg", "pitch_deg", "follow_ship"}, "sun":
/// {"elevation_deg", "azimuth_deg"}}; throws SceneError naming the path of a bad or unknown key.
RenderRequest parse_render_request(const JsonIn& root);

}  // namespace huygens
