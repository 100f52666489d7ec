#include "huygens/pipeline/runner.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace huygens {

namespace {

std::unique_ptr<Solver> checked(std::unique_ptr<Solver> s) {
  if (!s) throw std::invalid_argument("Runner: no solver");
  return s;
}

void sleep_s(double s) {
  std::this_thread::sleep_for(std::chrono::nanoseconds(static_cast<std::int64_t>(std::max(s, 0.0) * 1e9)));
}

}  // namespace

std::int64_t runner_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

Runner::Runner(std::unique_ptr<Solver> solver, RunnerParams params, Factory reset)
    : solver_(checked(std::move(solver))),
      params_(params),
      reset_(std::move(reset)),
      commands_(params.command_capacity),
      refused_(params.command_capacity),
      ring_(solver_->height_rows(), solver_->height_cols(), solver_->stats().all().size(), params.frame_slots,
            !solver_->height_rate().empty(), !solver_->velocity().empty(), solver_->particles().size()) {
  if (!(params.time_scale > 0) || !std::isfinite(params.time_scale))
    throw std::invalid_argument("Runner: time_scale must be a positive number");
  if (!(params.poll_s > 0)) throw std::invalid_argument("Runner: poll_s must be positive");
  for (const auto& s : solver_->stats().all()) stage_names_.push_back(s.name);
  realtime_ = params.realtime;
  time_scale_ = params.time_scale;
  paused_ = params.start_paused;
  paused_flag_.store(paused_, std::memory_order_release);
}

Runner::~Runner() { stop(); }

void Runner::start() {
  if (thread_.joinable() || status_.load() != kRunning) throw std::logic_error("Runner::start: already started");
  thread_ = std::thread([this] { run(); });
}

void Runner::stop() {
  stop_.store(true, std::memory_order_release);
  wake();
  if (thread_.joinable())
    thread_.join();
  else if (status_.load() == kRunning)
    status_.store(kFinished);  // never started
}

Solver& Runner::solver() {
  if (thread_.joinable() && !finished()) throw std::logic_error("Runner::solver: the simulation thread owns it");
  return *solver_;
}

void Runner::rethrow_if_failed() const {
  if (failed() && exception_) std::rethrow_exception(exception_);
}

// ---- display clock (seqlock of atomics; one writer: the simulation thread) ----

void Runner::set_clock(std::int64_t wall_ns, double sim_time, double rate) {
  const std::uint64_t s = clock_seq_.load(std::memory_order_relaxed);
  clock_seq_.store(s + 1, std::memory_order_relaxed);
  // release stores: a reader that sees any new field also sees the odd sequence number
  clock_wall_ns_.store(wall_ns, std::memory_order_release);
  clock_sim_.store(sim_time, std::memory_order_release);
  clock_rate_.store(rate, std::memory_order_release);
  clock_seq_.store(s + 2, std::memory_order_release);
}

double Runner::clock_at(std::int64_t now_ns) const {
  for (;;) {
    const std::uint64_t s1 = clock_seq_.load(std::memory_order_acquire);
    const std::int64_t w = clock_wall_ns_.load(std::memory_order_acquire);
    const double t = clock_sim_.load(std::memory_order_acquire);
    const double r = clock_rate_.load(std::memory_order_acquire);
    const std::uint64_t s2 = clock_seq_.load(std::memory_order_relaxed);
    // retried only while the writer is inside set_clock (three stores, on pause/resume/scale changes)
    if (s1 == s2 && (s1 & 1) == 0) {
      if (r < 0) return std::numeric_limits<double>::infinity();
      return t + r * static_cast<double>(now_ns - w) * 1e-9;
    }
  }
}

double Runner::display_time() const {
  return params_.manual_clock ? shown_t_.load(std::memory_order_acquire) : clock_at(runner_now_ns());
}

// ---- manual clock ----

void Runner::show(double t_s) {
  shown_t_.store(t_s, std::memory_order_release);
  shown_req_.fetch_add(1, std::memory_order_acq_rel);
  wake();
}

void Runner::wake() {
  // taking the mutex orders the change made before it with a waiter's test of its predicate
  { const std::lock_guard<std::mutex> lock(wake_mutex_); }
  wake_cv_.notify_all();
}

bool Runner::wait_shown(double timeout_s) const {
  const std::uint64_t req = shown_req_.load(std::memory_order_acquire);
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::nanoseconds(static_cast<std::int64_t>(timeout_s * 1e9));
  std::unique_lock<std::mutex> lock(wake_mutex_);
  wake_cv_.wait_until(lock, deadline, [&] { return shown_done_.load(std::memory_order_acquire) >= req || finished(); });
  return shown_done_.load(std::memory_order_acquire) >= req;
}

void Runner::mark_shown(std::uint64_t req) {
  if (shown_done_.exchange(req, std::memory_order_acq_rel) != req) wake();
}

void Runner::wait_for_show() {
  std::unique_lock<std::mutex> lock(wake_mutex_);
  wake_cv_.wait_for(lock, std::chrono::nanoseconds(static_cast<std::int64_t>(params_.poll_s * 1e9)), [&] {
    return shown_req_.load(std::memory_order_acquire) != seen_req_ || stop_.load(std::memory_order_acquire);
  });
}

bool Runner::due(double t_s, double h_s) {
  if (!params_.manual_clock) return !realtime_;  // as fast as possible: always; real time: see run_once
  // the request is read before the time (show() stores them the other way round), so a frame
  // found not due is not due at the time of that request either
  const std::uint64_t req = shown_req_.load(std::memory_order_acquire);
  const double t = shown_t_.load(std::memory_order_acquire);
  seen_req_ = req;
  // the same tolerance as a caller stepping while t_n + h <= T (1e-9 of a step)
  if (t_s <= t + 1e-9 * h_s) return true;
  mark_shown(req);
  return false;
}

bool Runner::unreachable(std::int64_t steps_origin) const {
  if (!params_.manual_clock || paused_ || step_once_ > 0) return false;
  // frame n is drawn as the newest (t_n <= T < t_{n+1}) or the one before it (t_{n+1} <= T <
  // t_{n+2}, the interpolation's other end); neither when step n+2 is taken and t_{n+2} <= T
  if (params_.max_steps > 0 && solver_->steps() - steps_origin + 2 > params_.max_steps) return false;
  return solver_->time_bound(2) <= shown_t_.load(std::memory_order_acquire);
}

// ---- simulation thread ----

void Runner::publish() {
  FrameInfo info{solver_->steps(), solver_->time(), applied_.load(std::memory_order_relaxed)};
  // where the solver has its ships (a steered ship is not where its scene path says)
  info.ship_count = static_cast<std::uint32_t>(std::min(solver_->ship_poses(info.ships), info.ships.size()));
  // (a solver with a velocity output: the frames' buffers exist, Runner's constructor)
  const std::span<const float> velocity = ring_.with_velocity() ? solver_->velocity() : std::span<const float>{};
  // (a particle solver: the frames' buffers have its size, unless a reset changed the count)
  std::span<const float> particles = ring_.particle_floats() > 0 ? solver_->particles() : std::span<const float>{};
  if (particles.size() != ring_.particle_floats()) particles = {};
  ring_.publish(info, solver_->height(), solver_->height_rate(), solver_->stats().all(), velocity, particles);
}

void Runner::apply_commands() {
  // in queue order; a StepOnce or Reset ends the batch so that it happens before the
  // commands sent after it are applied
  Command c;
  while (commands_.try_pop(c)) {
    apply(c);
    if (step_once_ > 0 || reset_requested_) break;
  }
}

void Runner::apply(const Command& c) {
  bool ok = true;
  const std::int64_t now = runner_now_ns();
  const double rate = realtime_ ? time_scale_ : -1.0;
  if (std::holds_alternative<cmd::Pause>(c)) {
    if (!paused_) set_clock(now, std::min(clock_at(now), solver_->time()), 0.0);
    paused_ = true;
  } else if (std::holds_alternative<cmd::Resume>(c)) {
    if (paused_) set_clock(now, clock_at(now), rate);
    paused_ = false;
  } else if (std::holds_alternative<cmd::StepOnce>(c)) {
    if (paused_) ++step_once_;
  } else if (std::holds_alternative<cmd::Reset>(c)) {
    // with a factory the loop rebuilds the solver; otherwise the solver resets itself (or refuses)
    ok = reset_ ? true : solver_->apply(c);
    reset_requested_ = reset_requested_ || ok;
  } else if (const auto* p = std::get_if<cmd::SetParam>(&c); p && p->name == "time_scale") {
    ok = p->value > 0 && std::isfinite(p->value);
    if (ok) {
      time_scale_ = p->value;
      if (realtime_ && !paused_) set_clock(now, clock_at(now), time_scale_);
    }
  } else if (const auto* t = std::get_if<cmd::Toggle>(&c); t && t->feature == "realtime") {
    if (t->on != realtime_) {
      realtime_ = t->on;
      // into real time: continue the display from the newest frame; out of it: show the newest
      const double from = realtime_ ? solver_->time() : clock_at(now);
      set_clock(now, from, paused_ ? 0.0 : (realtime_ ? time_scale_ : -1.0));
    }
  } else {
    ok = solver_->apply(c);
  }
  paused_flag_.store(paused_, std::memory_order_release);
  (ok ? applied_ : rejected_).fetch_add(1, std::memory_order_acq_rel);
  if (!ok) refused_.try_push(c);  // back to the UI (a full queue keeps only the count)
}

void Runner::run() {
  if (params_.omp_threads > 0) omp_set_num_threads(params_.omp_threads);
  try {
    bool pending = false;  // a step computed and not yet published (real time holds it until due)
    double last_time = solver_->time();
    publish();
    set_clock(runner_now_ns(), last_time, paused_ ? 0.0 : (realtime_ ? time_scale_ : -1.0));
    std::int64_t steps_origin = solver_->steps();

    while (!stop_.load(std::memory_order_acquire)) {
      if (hold_commands_ == 0) apply_commands();
      if (reset_requested_) {
        reset_requested_ = false;
        if (reset_) {
          std::unique_ptr<Solver> fresh = reset_();
          if (!fresh || fresh->height_rows() != ring_.rows() || fresh->height_cols() != ring_.cols() ||
              fresh->stats().all().size() != stage_names_.size())
            throw std::runtime_error("Runner: the reset solver's frame shape or stages differ from the original");
          solver_ = std::move(fresh);
        }
        pending = false;
        steps_origin = solver_->steps();
        last_time = solver_->time();
        publish();
        set_clock(runner_now_ns(), last_time, paused_ ? 0.0 : (realtime_ ? time_scale_ : -1.0));
        continue;
      }

      if (!run_once(pending, last_time, steps_origin)) break;
    }
    status_.store(kFinished, std::memory_order_release);
  } catch (const RunStopped& e) {
    error_ = RunnerError{e.stage(), e.step(), e.what(), true};
    exception_ = std::current_exception();
    status_.store(kFailed, std::memory_order_release);
  } catch (const std::exception& e) {
    error_ = RunnerError{"", solver_ ? solver_->steps() : -1, e.what(), false};
    exception_ = std::current_exception();
    status_.store(kFailed, std::memory_order_release);
  }
  wake();  // wait_shown() returns once the thread has ended
}

bool Runner::run_once(bool& pending, double& last_time, std::int64_t steps_origin) {
  if (!pending) {
    if (paused_ && step_once_ == 0) {
      // paused: everything it will publish is published
      if (params_.manual_clock) mark_shown(shown_req_.load(std::memory_order_acquire));
      sleep_s(params_.poll_s);
      return true;
    }
    if (params_.max_steps > 0 && solver_->steps() - steps_origin >= params_.max_steps) return false;
    step_from_ = solver_->time();
    solver_->step();
    if (hold_commands_ > 0) --hold_commands_;
    pending = true;
  }

  // publish now: as fast as possible, a single step while paused, or a due frame of the manual clock
  if (step_once_ > 0 || due(solver_->time(), solver_->time() - step_from_)) {
    if (unreachable(steps_origin)) {  // the manual clock's display passes it: not published
      hold_commands_ = 2;
      pending = false;
      return true;
    }
    publish();
    last_time = solver_->time();
    pending = false;
    if (step_once_ > 0) {
      --step_once_;
      if (paused_) set_clock(runner_now_ns(), last_time, 0.0);
    }
    return true;
  }
  if (params_.manual_clock && !paused_) {
    wait_for_show();
    return true;
  }
  if (paused_ || params_.manual_clock) {
    sleep_s(params_.poll_s);
    return true;
  }
  // real time: publish frame n+1 when the display clock reaches t_n
  const std::int64_t now = runner_now_ns();
  const double d = clock_at(now);
  if (d >= last_time) {
    // more than a step behind: rebase the clock instead of racing to catch up
    if (d > solver_->time()) set_clock(now, last_time, time_scale_);
    publish();
    last_time = solver_->time();
    pending = false;
    return true;
  }
  sleep_s(std::min(params_.poll_s, (last_time - d) / time_scale_));
  return true;
}

}  // namespace huygens
