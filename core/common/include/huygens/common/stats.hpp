#pragma once
// Per-stage counters of a solver pipeline: how often each stage ran, how long it took,
// how many bytes it touched and how many N x N transforms it made. Stages are
// registered at construction; counting inside a step never allocates.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace huygens {

struct StageStat {
  std::string name;
  /// Number of times the stage ran.
  std::uint64_t calls = 0;
  /// Total wall time (unit: ns).
  std::uint64_t ns = 0;
  /// Bytes of buffers the stage owns (allocated at construction; unit: bytes).
  std::uint64_t bytes = 0;
  /// Full-grid (N x N) FFTs the stage performed, summed over calls.
  std::uint64_t transforms = 0;
  /// Bytes the stage sent to other MPI ranks, summed over calls (unit: bytes; 0 in one process).
  std::uint64_t sent = 0;
};

class StageStats {
 public:
  /// Registers a stage (construction time only) and returns its index.
  int add(std::string name, std::uint64_t bytes = 0);
  StageStat& operator[](int i) { return stages_[static_cast<std::size_t>(i)]; }
  const StageStat& operator[](int i) const { return stages_[static_cast<std::size_t>(i)]; }
  std::span<const StageStat> all() const { return stages_; }
  /// Index of the named stage, or -1.
  int find(const std::string& name) const;
  void reset_counts();

 private:
  std::vector<StageStat> stages_;
};

/// Times one run of a stage: counts a call and adds the elapsed time on destruction.
class StageTimer {
 public:
  explicit StageTimer(StageStat& s) : s_(s), t0_(std::chrono::steady_clock::now()) {}
  ~StageTimer() {
    ++s_.calls;
    s_.ns += static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0_).count());
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  StageStat& s_;
  std::chrono::steady_clock::time_point t0_;
};

/// Runs fn `reps` times (reps >= 1) after one warm-up call and returns the median wall time
/// (unit: s). Shared by huygens-bench and huygens-caustics-bench.
template <class Fn>
double median_seconds(int reps, Fn&& fn) {
  fn();
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace huygens
