// SpscQueue: FIFO semantics, capacity, and a two-thread stress test that pushes many
// items (10 million per capacity by default; HUYGENS_STRESS_ITEMS overrides, the
// ThreadSanitizer run uses fewer) through rings of capacity 2, 3 and 8 with a
// consumer that is alternately fast and deliberately slow, checking order and content (every item carries a checksum of
// its payload).
#include "huygens/pipeline/spsc_queue.hpp"

#include <gtest/gtest.h>
#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <thread>

#include "huygens/pipeline/command.hpp"

using namespace huygens;

namespace {

std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// A small frame: sequence number, payload derived from it, checksum of the payload.
struct Item {
  std::uint64_t seq = 0;
  std::array<std::uint32_t, 6> payload{};
  std::uint64_t checksum = 0;
};

std::uint64_t checksum_of(const Item& it) {
  std::uint64_t h = splitmix(it.seq);
  for (std::uint32_t p : it.payload) h = splitmix(h ^ p);
  return h;
}

Item make_item(std::uint64_t seq) {
  Item it;
  it.seq = seq;
  std::uint64_t x = seq * 0x2545F4914F6CDD1Dull;
  for (auto& p : it.payload) p = static_cast<std::uint32_t>(x = splitmix(x));
  it.checksum = checksum_of(it);
  return it;
}

std::uint64_t stress_items() {
  if (const char* e = std::getenv("HUYGENS_STRESS_ITEMS")) return std::strtoull(e, nullptr, 10);
  return 10'000'000;
}

// How a stress thread waits for the other side: spin a few times (cheap when both threads have
// a core), then sleep on a futex until the other side rings. A sleeping thread leaves the run
// queue, so on a machine whose cores are busy with other work the scheduler runs the peer in its
// place and wakes this thread as soon as the peer has made progress. A yield would hand the core
// to the other work for a whole time slice per item, and so would std::atomic::wait, which
// libstdc++ 12 precedes with four sched_yield calls; hence the raw futex. The doorbell is the
// test's own: the queue is polled in the product and stays as it is.
class Doorbell {
 public:
  /// The count to wait on: read it before the attempt that may fail.
  std::uint32_t seen() const noexcept { return rings_.load(std::memory_order_seq_cst); }
  /// After a push (or pop): counts it and wakes the peer if it sleeps (no system call otherwise).
  void ring() noexcept {
    rings_.fetch_add(1, std::memory_order_seq_cst);
    if (sleepers_.load(std::memory_order_seq_cst) != 0) futex(FUTEX_WAKE_PRIVATE, 1);
  }
  /// After a failed attempt: spin 64 times, then sleep until ring() moves the count past `seen`
  /// (the kernel compares the count with `seen` atomically, so a ring in between is not lost).
  void wait(std::uint32_t seen, int& spins) noexcept {
    if (++spins <= 64) return;
    spins = 0;
    sleepers_.fetch_add(1, std::memory_order_seq_cst);
    futex(FUTEX_WAIT_PRIVATE, seen);
    sleepers_.fetch_sub(1, std::memory_order_seq_cst);
  }

 private:
  void futex(int op, std::uint32_t value) noexcept {
    static_assert(sizeof(rings_) == sizeof(std::uint32_t), "the futex word is 32 bits");
    syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&rings_), op, value, nullptr, nullptr, 0);
  }
  std::atomic<std::uint32_t> rings_{0};
  std::atomic<int> sleepers_{0};
};

}  // namespace

TEST(SpscQueue, FifoAndCapacity) {
  SpscQueue<int> q(3);
  EXPECT_EQ(q.capacity(), 3u);
  int v = -1;
  EXPECT_FALSE(q.try_pop(v));
  EXPECT_TRUE(q.try_push(1));
  EXPECT_TRUE(q.try_push(2));
  EXPECT_TRUE(q.try_push(3));
  EXPECT_FALSE(q.try_push(4)) << "a full ring refuses, it never overwrites";
  EXPECT_EQ(q.size(), 3u);
  ASSERT_TRUE(q.try_pop(v));
  EXPECT_EQ(v, 1);
  EXPECT_TRUE(q.try_push(4));
  for (int want : {2, 3, 4}) {
    ASSERT_TRUE(q.try_pop(v));
    EXPECT_EQ(v, want);
  }
  EXPECT_FALSE(q.try_pop(v));
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.pushed(), 4u);
  EXPECT_EQ(q.popped(), 4u);
}

TEST(SpscQueue, WrapsManyTimesAtCapacityOne) {
  SpscQueue<std::uint64_t> q(1);
  std::uint64_t v = 0;
  for (std::uint64_t i = 0; i < 1000; ++i) {
    ASSERT_TRUE(q.try_push(i));
    ASSERT_FALSE(q.try_push(i));
    ASSERT_TRUE(q.try_pop(v));
    ASSERT_EQ(v, i);
  }
}

TEST(SpscQueue, FrontAndPopPeekInPlace) {
  SpscQueue<int> q(2);
  EXPECT_EQ(q.front(), nullptr);
  q.try_push(7);
  q.try_push(8);
  ASSERT_NE(q.front(), nullptr);
  EXPECT_EQ(*q.front(), 7);
  q.pop();
  EXPECT_EQ(*q.front(), 8);
  q.pop();
  EXPECT_EQ(q.front(), nullptr);
}

TEST(SpscQueue, RejectsZeroCapacity) { EXPECT_THROW(SpscQueue<int>(0), std::invalid_argument); }

TEST(SpscQueue, IndicesOnSeparateCacheLines) {
  // the consumer's and the producer's counters must not share a line (no false sharing)
  EXPECT_EQ(alignof(SpscQueue<int>), kCacheLine);
  EXPECT_GE(sizeof(SpscQueue<int>), 3 * kCacheLine);
}

TEST(SpscQueue, CarriesCommandsByValue) {
  SpscQueue<Command> q(4);
  ASSERT_TRUE(q.try_push(cmd::Drop{1.5f, 2.5f, 0.1f, 0.02f}));
  ASSERT_TRUE(q.try_push(cmd::SetParam{"time_scale", 0.5}));
  ASSERT_TRUE(q.try_push(cmd::Toggle{"stokes", false}));
  Command c;
  ASSERT_TRUE(q.try_pop(c));
  ASSERT_TRUE(std::holds_alternative<cmd::Drop>(c));
  EXPECT_EQ(std::get<cmd::Drop>(c).y_m, 2.5f);
  ASSERT_TRUE(q.try_pop(c));
  EXPECT_STREQ(command_kind(c), "set_param");
  EXPECT_TRUE(std::get<cmd::SetParam>(c).name == "time_scale");
  EXPECT_EQ(std::get<cmd::SetParam>(c).value, 0.5);
  ASSERT_TRUE(q.try_pop(c));
  EXPECT_TRUE(std::get<cmd::Toggle>(c).feature == "stokes");
  EXPECT_FALSE(std::get<cmd::Toggle>(c).on);
  EXPECT_THROW(CommandName(std::string(32, 'x')), std::invalid_argument);
}

// ---- stress: two threads, order and content ----
//
// Per capacity, n items (10 million by default) go through the ring. The consumer
// alternates between two behaviours in blocks of n/10 items: fast (pops as quickly as it
// can, so the ring runs near empty and the consumer meets "empty") and deliberately slow
// (extra work per item and a yield every 4096 items, so the ring runs full and the
// producer meets "full"). Every item is checked for order and content. A side that finds the
// ring empty or full sleeps on the other side's doorbell, so the test needs no free core.

class SpscStress : public ::testing::TestWithParam<std::size_t> {};

TEST_P(SpscStress, OrderAndContentSurviveMillionsOfItems) {
  const std::size_t capacity = GetParam();
  const std::uint64_t n = stress_items();
  const std::uint64_t block = std::max<std::uint64_t>(n / 10, 1);
  SpscQueue<Item> q(capacity);
  std::atomic<std::uint64_t> producer_full{0};
  Doorbell pushed_bell, popped_bell;  // rung after every push / pop

  std::thread producer([&] {
    std::uint64_t full = 0;
    int spins = 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      const Item it = make_item(i);
      for (std::uint32_t seen = popped_bell.seen(); !q.try_push(it); seen = popped_bell.seen()) {
        ++full;
        popped_bell.wait(seen, spins);
      }
      pushed_bell.ring();
    }
    producer_full.store(full);
  });

  std::uint64_t next = 0, bad_order = 0, bad_content = 0, empty_fast = 0, empty_slow = 0, sink = 0;
  std::uint64_t fast_items = 0, slow_items = 0;
  int spins = 0;
  Item it;
  while (next < n) {
    const bool slow = (next / block) % 2 == 1;
    const std::uint32_t seen = pushed_bell.seen();
    if (!q.try_pop(it)) {
      ++(slow ? empty_slow : empty_fast);
      pushed_bell.wait(seen, spins);
      continue;
    }
    popped_bell.ring();
    if (it.seq != next) ++bad_order;
    // the checksum must match the payload, and the payload the one made for this sequence number
    if (checksum_of(it) != it.checksum || make_item(next).payload != it.payload) ++bad_content;
    ++next;
    if (slow) {
      ++slow_items;
      for (int k = 0; k < 16; ++k) sink = splitmix(sink ^ it.payload[k % 6]);
      if ((next & 4095) == 0) std::this_thread::yield();
    } else {
      ++fast_items;
    }
  }
  producer.join();
  EXPECT_EQ(bad_order, 0u);
  EXPECT_EQ(bad_content, 0u);
  EXPECT_EQ(q.pushed(), n);
  EXPECT_EQ(q.popped(), n);
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(fast_items + slow_items, n);
  // the slow phases must have made the producer meet a full ring (the back-pressure path ran)
  if (n >= 100000) {
    EXPECT_GT(producer_full.load(), 0u);
  }
  RecordProperty("items", std::to_string(n));
  RecordProperty("producer_full", std::to_string(producer_full.load()));
  RecordProperty("consumer_empty_fast", std::to_string(empty_fast));
  RecordProperty("consumer_empty_slow", std::to_string(empty_slow));
  RecordProperty("sink", std::to_string(sink & 1));
}

INSTANTIATE_TEST_SUITE_P(Capacities, SpscStress, ::testing::Values(2u, 3u, 8u),
                         [](const auto& info) { return "cap" + std::to_string(info.param); });
