#pragma once
// A lock-free single-producer / single-consumer FIFO ring (docs/design.md 2): commands travel
// UI -> simulation over it, and it is the building block the stress tests hammer.
//
// Lamport's ring with monotonic 64-bit counters: the producer owns `tail_`, the consumer
// owns `head_`; an element i lives in slot i mod capacity. The producer writes the slot,
// then stores tail = i + 1 with release; the consumer loads tail with acquire before it
// reads the slot, and stores head with release after it has copied the element out, so
// the producer (acquire load of head) never overwrites a slot that is still being read.
// Each side caches the other's counter and re-reads it only when the ring looks full
// (producer) or empty (consumer). Producer and consumer fields sit on separate 64-byte
// cache lines (no false sharing). Capacity is any value >= 1 fixed at construction; the
// slots are allocated there and nothing is allocated afterwards.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <type_traits>

namespace huygens {

/// Size of a destructive-interference unit (unit: bytes); 64 on the x86-64 and ARMv8 we target.
inline constexpr std::size_t kCacheLine = 64;

template <class T>
class SpscQueue {
  static_assert(std::is_nothrow_copy_assignable_v<T> && std::is_default_constructible_v<T>,
                "SpscQueue elements are default-constructed once and then copy-assigned");

 public:
  /// A ring holding at most `capacity` elements (>= 1).
  explicit SpscQueue(std::size_t capacity) : cap_(capacity) {
    if (capacity == 0) throw std::invalid_argument("SpscQueue: capacity must be >= 1");
    slots_ = std::make_unique<T[]>(capacity);
  }
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  std::size_t capacity() const { return cap_; }

  /// Producer: appends a copy of `v`; false (nothing written) when the ring is full.
  bool try_push(const T& v) noexcept {
    const std::uint64_t t = tail_.load(std::memory_order_relaxed);
    if (t - head_cache_ == cap_) {
      head_cache_ = head_.load(std::memory_order_acquire);
      if (t - head_cache_ == cap_) return false;
    }
    slots_[slot(t)] = v;
    tail_.store(t + 1, std::memory_order_release);
    return true;
  }

  /// Consumer: copies the oldest element into `out` and removes it; false when empty.
  bool try_pop(T& out) noexcept {
    const std::uint64_t h = head_.load(std::memory_order_relaxed);
    if (h == tail_cache_) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (h == tail_cache_) return false;
    }
    out = slots_[slot(h)];
    head_.store(h + 1, std::memory_order_release);
    return true;
  }

  /// Consumer: the oldest element in place (nullptr when empty); valid until pop().
  const T* front() noexcept {
    const std::uint64_t h = head_.load(std::memory_order_relaxed);
    if (h == tail_cache_) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (h == tail_cache_) return nullptr;
    }
    return &slots_[slot(h)];
  }
  /// Consumer: removes the element front() returned (precondition: front() != nullptr).
  void pop() noexcept { head_.store(head_.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

  /// Elements in the ring; exact from either side when the other is idle, otherwise a snapshot.
  std::size_t size() const noexcept {
    const std::uint64_t h = head_.load(std::memory_order_acquire);
    const std::uint64_t t = tail_.load(std::memory_order_acquire);
    return static_cast<std::size_t>(t - h);
  }
  bool empty() const noexcept { return size() == 0; }

  /// Elements pushed so far (producer counter; read from any thread).
  std::uint64_t pushed() const noexcept { return tail_.load(std::memory_order_acquire); }
  /// Elements popped so far (consumer counter; read from any thread).
  std::uint64_t popped() const noexcept { return head_.load(std::memory_order_acquire); }

 private:
  std::size_t slot(std::uint64_t i) const noexcept { return static_cast<std::size_t>(i % cap_); }

  // shared, read-only after construction
  const std::size_t cap_;
  std::unique_ptr<T[]> slots_;
  // consumer line: its index and its cached copy of the producer's
  alignas(kCacheLine) std::atomic<std::uint64_t> head_{0};
  std::uint64_t tail_cache_ = 0;
  // producer line: its index and its cached copy of the consumer's
  alignas(kCacheLine) std::atomic<std::uint64_t> tail_{0};
  std::uint64_t head_cache_ = 0;
  // (the class is 64-byte aligned, so its size rounds up and nothing else shares this line)
};

}  // namespace huygens
