#pragma once
// Frames from the simulation thread to the render thread (docs/design.md 2), and the lock-free
// ring of preallocated frame buffers that carries them.
//
// A frame is the visible heightfield eta (m), its time derivative eta_dot (m/s), the simulated
// time, the step index, the ship poses and a snapshot of the per-stage counters. The producer
// fills a free slot (one memcpy per field) and publishes it; the consumer always gets the newest
// frame and the one before it, to interpolate between them (cubic Hermite, paper 004 section
// 3.5). Neither side waits or allocates: one 64-bit atomic word holds the published pair and
// the slots the consumer holds, so five slots always leave one free to write (the protocol is
// spelled out in docs/pipeline.md).
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "huygens/common/fft.hpp"
#include "huygens/common/stats.hpp"
#include "huygens/pipeline/spsc_queue.hpp"

namespace huygens {

/// A snapshot of one stage's counters (the name stays with the solver's StageStats, same index).
struct StageCounter {
  /// Number of times the stage ran.
  std::uint64_t calls = 0;
  /// Total wall time (unit: ns).
  std::uint64_t ns = 0;
  /// Bytes of buffers the stage owns (unit: bytes).
  std::uint64_t bytes = 0;
  /// Full-grid (N x N) transforms, summed over calls.
  std::uint64_t transforms = 0;
};

/// Where one ship is at a frame's time, as the solver has it (Solver::ship_poses): a ship
/// steered by cmd::ShipTarget is drawn here, not where its scene path would put it.
struct ShipState {
  /// Hull centre in the full grid's frame (unit: m).
  double x_m = 0, y_m = 0;
  /// Heading from +x towards +y (unit: rad).
  double heading_rad = 0;
  /// Speed over the last step (unit: m/s).
  double speed_mps = 0;
};

/// Most ships a frame carries (unit: ships); a solver with more reports the first ones.
inline constexpr std::size_t kMaxFrameShips = 8;

/// Everything of a frame except its fields (the producer fills this in).
struct FrameInfo {
  /// Full steps taken when the frame was made.
  std::int64_t step = 0;
  /// Simulated time of the fields (unit: s).
  double time_s = 0;
  /// Commands the runner had applied before this frame (to find the first frame that shows one).
  std::uint64_t commands_applied = 0;
  /// Ships in `ships` (unit: ships; at most kMaxFrameShips).
  std::uint32_t ship_count = 0;
  /// Poses of the solver's ships at time_s (fixed capacity: copied with the frame, no allocation).
  std::array<ShipState, kMaxFrameShips> ships{};
};

struct Frame {
  /// Publication number: 1 for the first frame published, +1 per frame.
  std::uint64_t seq = 0;
  FrameInfo info;
  std::size_t rows = 0;
  std::size_t cols = 0;
  /// True when eta_dot holds the solver's time derivative (false: the solver has none).
  bool has_rate = false;
  /// Visible heightfield, rows x cols, C order (unit: m).
  AlignedBuffer<float> eta;
  /// Its time derivative, rows x cols (unit: m/s); meaningful only when has_rate.
  AlignedBuffer<float> eta_dot;
  /// True when `velocity` holds the solver's depth-averaged velocity (an LBM's "u" output).
  bool has_velocity = false;
  /// Horizontal velocity (u, v) per point, rows x cols x 2, C order (unit: m/s); for flow
  /// visualisation (dye, speed maps); meaningful only when has_velocity.
  AlignedBuffer<float> velocity;
  /// True when `particles` holds the solver's particles (Solver::particles()).
  bool has_particles = false;
  /// x, y, z (unit: m) and speed (unit: m/s) per particle, 4 floats each; meaningful only when
  /// has_particles.
  AlignedBuffer<float> particles;
  /// Per-stage counters, one per stage of the solver's StageStats, same order.
  std::vector<StageCounter> stages;
};

/// The consumer's view: the newest frame and the one published just before it.
/// `prev` is null until two frames were published. Valid until the next acquire().
struct FramePair {
  const Frame* prev = nullptr;
  const Frame* newest = nullptr;
  explicit operator bool() const { return newest != nullptr; }

  /// Interpolation parameter s in [0, 1] of display time t (unit: s) between prev and
  /// newest; times outside are clamped (the consumer never extrapolates).
  double phase(double t) const;
  /// The heightfield at display time t (unit: s) into `out` (rows x cols; unit: m): the cubic
  /// Hermite interpolant of eta and eta_dot between prev and newest (paper 004 section 3.5,
  /// weights 20/27, 7/27, 4/27 dt, -2/27 dt at s = 1/3; time_interp.hpp); linear when a frame
  /// has no rate, the newest frame alone when there is no prev; at s = 0 or 1 (or clamped there)
  /// that frame's heights bit for bit.
  void sample(double t, std::span<float> out) const;
  /// Pose of ship i at display time t (clamped like sample()): linear in position and speed
  /// between prev and newest, heading along the shorter arc; the newest frame's pose when prev
  /// has no such ship. False when the newest frame has no ship i.
  bool ship(std::size_t i, double t, ShipState& out) const;
  /// The newest frame's velocity into `out` (rows x cols x 2; unit: m/s; not interpolated).
  /// False, leaving `out` alone, when it has none.
  bool velocity(std::span<float> out) const;
};

class FrameRing {
 public:
  /// The fewest slots the protocol needs (2 held by the consumer, 2 published, 1 being written).
  static constexpr std::size_t kMinSlots = 5;
  /// The most slots the state word can describe.
  static constexpr std::size_t kMaxSlots = 32;

  /// Allocates `slots` frames of rows x cols (with an eta_dot buffer when `with_rate`, a
  /// velocity buffer of rows x cols x 2 when `with_velocity`, a particle buffer of
  /// `particle_floats` floats) and `stage_count` counters each. Throws std::invalid_argument for
  /// slots outside [5, 32].
  FrameRing(std::size_t rows, std::size_t cols, std::size_t stage_count, std::size_t slots = kMinSlots,
            bool with_rate = true, bool with_velocity = false, std::size_t particle_floats = 0);
  FrameRing(const FrameRing&) = delete;
  FrameRing& operator=(const FrameRing&) = delete;

  std::size_t rows() const { return rows_; }
  std::size_t cols() const { return cols_; }
  std::size_t slots() const { return frames_.size(); }
  /// The frames have velocity buffers.
  bool with_velocity() const { return !frames_.empty() && frames_[0].velocity.size() > 0; }
  /// Floats of each frame's particle buffer (0: none).
  std::size_t particle_floats() const { return frames_.empty() ? 0 : frames_[0].particles.size(); }

  // ---- producer (one thread) ----
  /// A free slot to fill (never blocks; the same slot until publish()).
  Frame& begin_write();
  /// Publishes the slot begin_write() returned as the newest frame (sets its seq).
  void publish();
  /// begin_write + one memcpy per field + publish. `eta_dot` may be empty (has_rate = false),
  /// `velocity` and `particles` too (has_velocity / has_particles = false); stage counters beyond the ring's
  /// stage_count are not copied. Throws std::invalid_argument, before touching the ring, when a field has the wrong
  /// size or the ring has no buffer for it.
  void publish(const FrameInfo& info, std::span<const float> eta, std::span<const float> eta_dot,
               std::span<const StageStat> stages = {}, std::span<const float> velocity = {},
               std::span<const float> particles = {});
  /// Frames published so far (producer's count; readable from any thread).
  std::uint64_t published() const { return published_.load(std::memory_order_acquire); }

  // ---- consumer (one thread) ----
  /// The newest frame and the one before it. Never blocks; returns the same pair when
  /// nothing new was published; an empty pair before the first publish.
  FramePair acquire();
  /// Frames the consumer never saw as newest because a newer one replaced them first.
  std::uint64_t dropped() const { return dropped_; }

 private:
  static constexpr unsigned kNone = 0xFF;
  static unsigned newest_of(std::uint64_t s) { return static_cast<unsigned>(s & 0xFF); }
  static unsigned prev_of(std::uint64_t s) { return static_cast<unsigned>((s >> 8) & 0xFF); }
  static std::uint32_t mask_of(std::uint64_t s) { return static_cast<std::uint32_t>(s >> 16); }
  static std::uint64_t pack(unsigned newest, unsigned prev, std::uint32_t mask) {
    return std::uint64_t{newest} | (std::uint64_t{prev} << 8) | (std::uint64_t{mask} << 16);
  }
  static std::uint32_t bit(unsigned slot) { return slot == kNone ? 0u : (1u << slot); }

  std::size_t rows_, cols_;
  std::vector<Frame> frames_;
  // shared word: published pair + consumer mask
  alignas(kCacheLine) std::atomic<std::uint64_t> state_;
  // producer line
  alignas(kCacheLine) std::atomic<std::uint64_t> published_{0};
  unsigned writing_ = kNone, pub_newest_ = kNone, pub_prev_ = kNone;
  // consumer line
  alignas(kCacheLine) unsigned held_newest_ = kNone;
  unsigned held_prev_ = kNone;
  std::uint64_t last_seq_ = 0;
  std::uint64_t dropped_ = 0;
};

}  // namespace huygens
