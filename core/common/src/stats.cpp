#include "huygens/common/stats.hpp"

namespace huygens {

int StageStats::add(std::string name, std::uint64_t bytes) {
  stages_.push_back(StageStat{std::move(name), 0, 0, bytes, 0});
  return static_cast<int>(stages_.size()) - 1;
}

int StageStats::find(const std::string& name) const {
  for (std::size_t i = 0; i < stages_.size(); ++i)
    if (stages_[i].name == name) return static_cast<int>(i);
  return -1;
}

void StageStats::reset_counts() {
  for (auto& s : stages_) {
    s.calls = 0;
    s.ns = 0;
    s.transforms = 0;
  }
}

}  // namespace huygens
