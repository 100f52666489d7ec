#include "huygens/pipeline/render_info.hpp"

namespace huygens {

double mean_level(std::span<const float> height) {
  double sum = 0.0;
  for (float v : height) sum += v;
  return height.empty() ? 0.0 : sum / static_cast<double>(height.size());
}

}  // namespace huygens
