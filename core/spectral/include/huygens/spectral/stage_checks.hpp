#pragma once
// Non-finite results of the stages of one Huygens step (docs/huygens.md "Non-finite values",
// docs/scale.md "Huygens on slabs"). On one process a stage that fails throws NonFiniteError at
// once. On a slab the failure is recorded; settle() sums the records of every rank, with the
// still-sea energy, in the step's one reduction and throws on every rank for the first failing
// stage in step order, so all ranks name the same stage or enter the still state together.
#include <array>
#include <cstdint>
#include <functional>
#include <span>

#include "huygens/common/stats.hpp"

namespace huygens {

class StageChecks {
 public:
  /// Stages a step can record (indices into the step's StageStats).
  static constexpr int kMaxStages = 16;
  /// deferred: record failures until settle() (a slab); else throw at once (one process).
  explicit StageChecks(bool deferred = false) : deferred_(deferred) {}
  /// Stage `stage` of `stats` produced a non-finite value in step `step` (1-based).
  void fail(const StageStats& stats, int stage, std::int64_t step);
  /// Before a step: nothing failed, no energy.
  void clear() { flags_.fill(0.0); }
  /// This process's share of the value reduced with the flags (the still-sea energy sum); after
  /// settle(), the sum over the ranks.
  double& energy() { return flags_[kMaxStages]; }
  /// Sums flags and energy over the ranks with `sum` (one reduction) and throws NonFiniteError
  /// for the first stage in `order` that failed on any rank (indices < 0 are skipped).
  void settle(const std::function<void(std::span<double>)>& sum, const StageStats& stats, std::span<const int> order,
              std::int64_t step);

 private:
  bool deferred_;
  std::array<double, kMaxStages + 1> flags_{};  // per stage: failures this step; last: energy
};

}  // namespace huygens
