#include "huygens/pipeline/frame.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>

#include "huygens/common/time_interp.hpp"

namespace huygens {

FrameRing::FrameRing(std::size_t rows, std::size_t cols, std::size_t stage_count, std::size_t slots, bool with_rate,
                     bool with_velocity, std::size_t particle_floats)
    : rows_(rows), cols_(cols), state_(pack(kNone, kNone, 0)) {
  if (slots < kMinSlots || slots > kMaxSlots)
    throw std::invalid_argument("FrameRing: slots must be in [5, 32], got " + std::to_string(slots));
  frames_.resize(slots);
  for (auto& f : frames_) {
    f.rows = rows;
    f.cols = cols;
    f.eta = AlignedBuffer<float>(rows * cols);
    if (with_rate) f.eta_dot = AlignedBuffer<float>(rows * cols);
    if (with_velocity) f.velocity = AlignedBuffer<float>(2 * rows * cols);
    if (particle_floats > 0) f.particles = AlignedBuffer<float>(particle_floats);
    f.stages.resize(stage_count);
  }
}

Frame& FrameRing::begin_write() {
  if (writing_ == kNone) {
    // acquire: the consumer's reads of any slot it has since let go of happen before we write it
    const std::uint64_t s = state_.load(std::memory_order_acquire);
    const std::uint32_t busy = mask_of(s) | bit(pub_newest_) | bit(pub_prev_);
    // at most 4 bits are set and there are >= 5 slots, so a free one exists
    writing_ = static_cast<unsigned>(std::countr_one(busy));
  }
  return frames_[writing_];
}

void FrameRing::publish() {
  if (writing_ == kNone) begin_write();
  const std::uint64_t seq = published_.load(std::memory_order_relaxed) + 1;
  frames_[writing_].seq = seq;
  std::uint64_t s = state_.load(std::memory_order_relaxed);
  // fails only when the consumer has just taken a pair (and changed the mask): retry with it
  while (!state_.compare_exchange_weak(s, pack(writing_, pub_newest_, mask_of(s)), std::memory_order_release,
                                       std::memory_order_relaxed)) {
  }
  pub_prev_ = pub_newest_;
  pub_newest_ = writing_;
  writing_ = kNone;
  published_.store(seq, std::memory_order_release);
}

void FrameRing::publish(const FrameInfo& info, std::span<const float> eta, std::span<const float> eta_dot,
                        std::span<const StageStat> stages, std::span<const float> velocity,
                        std::span<const float> particles) {
  const std::size_t n = rows_ * cols_;
  if (eta.size() != n || (!eta_dot.empty() && eta_dot.size() != n) || (!velocity.empty() && velocity.size() != 2 * n))
    throw std::invalid_argument("FrameRing::publish: field size " + std::to_string(eta.size()) + "/" +
                                std::to_string(eta_dot.size()) + "/" + std::to_string(velocity.size()) +
                                " != " + std::to_string(rows_) + " x " + std::to_string(cols_));
  Frame& f = begin_write();
  if (!eta_dot.empty() && f.eta_dot.size() != n)
    throw std::invalid_argument("FrameRing::publish: ring was built without eta_dot buffers");
  if (!velocity.empty() && f.velocity.size() != 2 * n)
    throw std::invalid_argument("FrameRing::publish: ring was built without velocity buffers");
  if (!particles.empty() && f.particles.size() != particles.size())
    throw std::invalid_argument("FrameRing::publish: " + std::to_string(particles.size()) +
                                " particle floats for buffers of " + std::to_string(f.particles.size()));
  f.has_particles = !particles.empty();
  if (f.has_particles) std::memcpy(f.particles.data(), particles.data(), particles.size() * sizeof(float));
  f.has_velocity = !velocity.empty();
  if (f.has_velocity) std::memcpy(f.velocity.data(), velocity.data(), 2 * n * sizeof(float));
  f.info = info;
  std::memcpy(f.eta.data(), eta.data(), n * sizeof(float));
  f.has_rate = !eta_dot.empty();
  if (f.has_rate) std::memcpy(f.eta_dot.data(), eta_dot.data(), n * sizeof(float));
  const std::size_t k = std::min(stages.size(), f.stages.size());
  for (std::size_t i = 0; i < k; ++i)
    f.stages[i] = StageCounter{stages[i].calls, stages[i].ns, stages[i].bytes, stages[i].transforms};
  publish();
}

bool FramePair::velocity(std::span<float> out) const {
  if (!newest || !newest->has_velocity || out.size() != newest->velocity.size()) return false;
  std::memcpy(out.data(), newest->velocity.data(), out.size() * sizeof(float));
  return true;
}

FramePair FrameRing::acquire() {
  std::uint64_t s = state_.load(std::memory_order_acquire);
  for (;;) {
    const unsigned nw = newest_of(s), pv = prev_of(s);
    if (nw == kNone) return {};
    // nothing new: the producer cannot republish a slot we hold, so same newest = same pair
    if (nw == held_newest_) break;
    // take the published pair and let go of what we held (acq_rel: see the header)
    if (state_.compare_exchange_weak(s, pack(nw, pv, bit(nw) | bit(pv)), std::memory_order_acq_rel,
                                     std::memory_order_acquire)) {
      held_newest_ = nw;
      held_prev_ = pv;
      const std::uint64_t seq = frames_[nw].seq;
      dropped_ += seq - last_seq_ - 1;
      last_seq_ = seq;
      break;
    }
  }
  return {held_prev_ == kNone ? nullptr : &frames_[held_prev_], &frames_[held_newest_]};
}

double FramePair::phase(double t) const {
  if (!newest || !prev) return 1.0;
  const double h = newest->info.time_s - prev->info.time_s;
  if (!(h > 0)) return 1.0;
  return std::clamp((t - prev->info.time_s) / h, 0.0, 1.0);
}

void FramePair::sample(double t, std::span<float> out) const {
  if (!newest) throw std::logic_error("FramePair::sample: no frame yet");
  const std::size_t n = newest->rows * newest->cols;
  if (out.size() != n) throw std::invalid_argument("FramePair::sample: output size mismatch");
  const double s = phase(t);
  if (!prev || s >= 1.0 || s <= 0.0) {
    // at an end (or clamped to it) the frame itself, bit for bit
    std::memcpy(out.data(), (prev && s <= 0.0 ? prev : newest)->eta.data(), n * sizeof(float));
    return;
  }
  const double h = newest->info.time_s - prev->info.time_s;
  if (prev->has_rate && newest->has_rate) {
    hermite_interpolate(prev->eta.data(), prev->eta_dot.data(), newest->eta.data(), newest->eta_dot.data(), n,
                        hermite_weights(s), h, out.data());
    return;
  }
  // no time derivative: linear in time
  const float w1 = static_cast<float>(s), w0 = 1.0f - w1;
  const float *a = prev->eta.data(), *b = newest->eta.data();
  float* o = out.data();
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) o[i] = w0 * a[i] + w1 * b[i];
}

bool FramePair::ship(std::size_t i, double t, ShipState& out) const {
  if (!newest || i >= newest->info.ship_count) return false;
  const ShipState& b = newest->info.ships[i];
  if (!prev || i >= prev->info.ship_count) {
    out = b;
    return true;
  }
  const ShipState& a = prev->info.ships[i];
  const double s = phase(t);
  if (s >= 1.0 || s <= 0.0) {  // at an end: that frame's pose exactly
    out = s >= 1.0 ? b : a;
    return true;
  }
  out.x_m = a.x_m + s * (b.x_m - a.x_m);
  out.y_m = a.y_m + s * (b.y_m - a.y_m);
  out.speed_mps = a.speed_mps + s * (b.speed_mps - a.speed_mps);
  // heading along the shorter arc
  const double two_pi = 2.0 * std::numbers::pi;
  double dh = std::fmod(b.heading_rad - a.heading_rad, two_pi);
  if (dh > std::numbers::pi) dh -= two_pi;
  if (dh < -std::numbers::pi) dh += two_pi;
  out.heading_rad = a.heading_rad + s * dh;
  return true;
}

}  // namespace huygens
