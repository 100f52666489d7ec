#include "huygens/spectral/stage_checks.hpp"

#include <stdexcept>

#include "huygens/common/finite.hpp"

namespace huygens {

void StageChecks::fail(const StageStats& stats, int stage, std::int64_t step) {
  if (!deferred_) throw NonFiniteError(stats[stage].name, step);
  if (stage < 0 || stage >= kMaxStages) throw std::logic_error("StageChecks: stage index beyond kMaxStages");
  flags_[static_cast<std::size_t>(stage)] += 1.0;
}

void StageChecks::settle(const std::function<void(std::span<double>)>& sum, const StageStats& stats,
                         std::span<const int> order, std::int64_t step) {
  sum(flags_);
  for (const int st : order)
    if (st >= 0 && flags_[static_cast<std::size_t>(st)] > 0) throw NonFiniteError(stats[st].name, step);
}

}  // namespace huygens
