#include "huygens/pipeline/render_info.hpp"

namespace huygens {

double mean_level(std::span<const float> height) {
  double sum = 0.0;
  for (float v : height) sum += v;
  return height.empty() ? 0.0 : sum / static_cast<double>(height.size());
}

RenderRequest parse_render_request(const JsonIn& root) {
  RenderRequest r;
  const std::optional<JsonIn> block = root.optional_object("render");
  if (!block) return r;
  block->allow_only({"caustics", "blur"});
  if (block->has("caustics")) r.caustics = block->boolean("caustics", true);
  if (block->has("blur")) {
    const std::string b = block->string("blur", "accumulation", {"accumulation", "float", "none"});
    r.blur = b == "float" ? BlurMode::float_target : b == "none" ? BlurMode::none : BlurMode::accumulation;
  }
  return r;
}

}  // namespace huygens
