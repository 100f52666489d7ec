#pragma once
// The simulation runner (docs/design.md 2, docs/pipeline.md; paper 004 Figure 2): a Solver on
// its own thread, UI commands applied at step boundaries (refused ones handed back), a frame
// published after every step (manual clock: every step the display can reach) into a FrameRing
// the render thread reads without waiting; an exception from step() stops the thread and is
// kept (failed(), error(), rethrow_if_failed()).
// Clocks: as fast as possible; real time, D(now) = t0 + time_scale (now - wall0), frame n+1
// published when D reaches t_n (so D lies between the two newest frames; rebased when more
// than a step behind); manual (deterministic: headless, tests), frame n published once
// t_n <= T of show(T), the newest frame the last step at or before T, the one before it the step
// before that; a frame the display cannot reach, t_{n+2} <= T by Solver::time_bound(2), is
// computed but not published (nor are commands applied until step n+2: they could move it).
// Threads: the constructor, start(), stop() and solver() belong to the owning thread;
// send(), show() and next_refused() to one UI thread (single producer of commands); frames(),
// display_time(), wait_shown(), failed(), error() to one render thread (single consumer).
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "huygens/pipeline/command.hpp"
#include "huygens/pipeline/frame.hpp"
#include "huygens/pipeline/solver.hpp"
#include "huygens/pipeline/spsc_queue.hpp"

namespace huygens {

struct RunnerParams {
  /// Pace to the wall clock (true) or step as fast as possible (false).
  bool realtime = true;
  /// Manual display clock set by show() (deterministic; `realtime` and "realtime" are then ignored).
  bool manual_clock = false;
  /// Simulated seconds per wall-clock second when pacing to real time (unit: s/s).
  double time_scale = 1.0;
  /// Commands the UI may queue before send() refuses one (unit: commands).
  std::size_t command_capacity = 256;
  /// Frame buffers in the ring, >= FrameRing::kMinSlots (unit: frames).
  std::size_t frame_slots = FrameRing::kMinSlots;
  /// Stop after this many steps of the current solver, 0 = run until stop() (unit: steps).
  std::int64_t max_steps = 0;
  /// Start paused (the initial frame is published; StepOnce / Resume continue).
  bool start_paused = false;
  /// Longest an idle simulation thread sleeps before it looks at its commands again (unit: s).
  double poll_s = 0.0005;
  /// OpenMP threads of the simulation thread, 0 = OpenMP's default (OMP_NUM_THREADS). A new
  /// std::thread does not inherit omp_set_num_threads() from the thread that made it.
  int omp_threads = 0;
};

/// Why the simulation thread stopped on an exception.
struct RunnerError {
  /// Stage that produced the first non-finite value ("" when the error was not a NonFiniteError).
  std::string stage;
  /// Step at which it happened (-1 when unknown).
  std::int64_t step = -1;
  /// The exception's what().
  std::string message;
  bool non_finite = false;
};

class Runner {
 public:
  using Factory = std::function<std::unique_ptr<Solver>()>;

  /// Runs `solver`; `reset` (optional) builds a fresh solver for the Reset command
  /// (without it, Reset is offered to the solver's apply()).
  explicit Runner(std::unique_ptr<Solver> solver, RunnerParams params = {}, Factory reset = {});
  /// Stops and joins the thread.
  ~Runner();
  Runner(const Runner&) = delete;
  Runner& operator=(const Runner&) = delete;

  // ---- owning thread ----
  /// Starts the simulation thread; it publishes the initial state as the first frame.
  void start();
  /// Asks the thread to stop at the next step boundary and joins it (idempotent).
  void stop();
  /// The solver, for the owning thread only while the simulation thread is not running.
  Solver& solver();
  /// Stage names, same order as Frame::stages (fixed at construction).
  const std::vector<std::string>& stage_names() const { return stage_names_; }

  // ---- UI thread (single producer) ----
  /// Queues a command for the next step boundary; false when the queue is full (nothing queued).
  bool send(const Command& c) { return commands_.try_push(c); }
  /// The oldest command the solver or the runner refused that was not taken yet (false: none).
  /// At most command_capacity are kept; later refusals are only counted (commands_rejected()).
  bool next_refused(Command& out) { return refused_.try_pop(out); }
  /// Manual clock: the display time (unit: s); the simulation publishes the last step at or before
  /// it and the one before that (every step while it cannot bound the next steps' times). Display
  /// times given in increasing order (a smaller one shows the newest frame: none is computed back).
  void show(double t_s);

  // ---- render thread (single consumer) ----
  /// The newest frame and the one before it; never waits.
  FramePair frames() { return ring_.acquire(); }
  /// The simulated time to display now (unit: s): the real-time clock, frozen while paused;
  /// +infinity when running as fast as possible (FramePair::sample then shows the newest frame);
  /// the time given to show() with the manual clock.
  double display_time() const;
  /// Manual clock: waits (on a condition variable, woken by the simulation thread) until every step
  /// at or before the time last given to show() is computed and the last two of them published (or
  /// the simulation is paused). False when the thread ended first or after timeout_s.
  bool wait_shown(double timeout_s = 600.0) const;
  /// True once the simulation thread stopped on an exception; error() is then valid.
  bool failed() const { return status_.load(std::memory_order_acquire) == kFailed; }
  const RunnerError& error() const { return error_; }
  /// Rethrows the exception that stopped the simulation thread (original type), if any.
  void rethrow_if_failed() const;
  /// True once the thread has ended (stop(), max_steps reached, or an exception).
  bool finished() const { return status_.load(std::memory_order_acquire) != kRunning; }

  // ---- any thread ----
  bool paused() const { return paused_flag_.load(std::memory_order_acquire); }
  /// Commands applied so far (by the runner or the solver).
  std::uint64_t commands_applied() const { return applied_.load(std::memory_order_acquire); }
  /// Commands the solver refused (Solver::apply returned false) or that named an unknown runner parameter.
  std::uint64_t commands_rejected() const { return rejected_.load(std::memory_order_acquire); }
  /// Frames published so far.
  std::uint64_t frames_published() const { return ring_.published(); }

 private:
  enum Status : int { kRunning = 0, kFinished = 1, kFailed = 2 };

  void run();
  /// One pass of the loop after the commands: step, publish when due, or wait; false when
  /// max_steps is reached.
  bool run_once(bool& pending, double& last_time, std::int64_t steps_origin);
  /// True when the frame just computed (time t_s, h_s after the last published one) is published
  /// now rather than held: always when running as fast as possible, t_s <= show() time when manual.
  bool due(double t_s, double h_s);
  /// Manual clock: true when the frame just computed will be neither the newest nor the one before
  /// it when the display time is reached, t_{n+2} <= T (Solver::time_bound(2)), so it is not published.
  bool unreachable(std::int64_t steps_origin) const;
  /// Manual clock: stores the request every due frame is published for; wakes wait_shown().
  void mark_shown(std::uint64_t req);
  /// Manual clock, nothing due: waits until show() is called again, at most poll_s.
  void wait_for_show();
  /// Wakes the threads waiting in wait_shown() or wait_for_show().
  void wake();
  void apply_commands();
  void apply(const Command& c);
  void publish();
  double clock_at(std::int64_t wall_ns) const;
  void set_clock(std::int64_t wall_ns, double sim_time, double rate);

  std::unique_ptr<Solver> solver_;
  RunnerParams params_;
  Factory reset_;
  std::vector<std::string> stage_names_;
  SpscQueue<Command> commands_;
  SpscQueue<Command> refused_;
  FrameRing ring_;
  std::thread thread_;

  // simulation-thread state
  bool paused_ = false;
  bool realtime_ = true;
  double time_scale_ = 1.0;
  int step_once_ = 0;
  bool reset_requested_ = false;
  std::int64_t steps_at_reset_ = 0;
  /// Simulated time before the step in hand (unit: s): the due tolerance's step length.
  double step_from_ = 0.0;
  /// Manual clock: steps to take before commands are applied again (a frame was not published on
  /// the promise that the next two steps are due: a command could change them).
  int hold_commands_ = 0;
  /// Manual clock: the show() request the last due() answered.
  std::uint64_t seen_req_ = 0;

  // display clock, written by the simulation thread, read by the render thread (a seqlock
  // of atomics: the writer bumps seq to odd, stores, bumps to even; readers retry on change)
  alignas(kCacheLine) std::atomic<std::uint64_t> clock_seq_{0};
  std::atomic<std::int64_t> clock_wall_ns_{0};
  std::atomic<double> clock_sim_{0};
  /// simulated s per wall s; 0 = paused; < 0 = as fast as possible
  std::atomic<double> clock_rate_{0};

  alignas(kCacheLine) std::atomic<bool> stop_{false};
  std::atomic<int> status_{kRunning};
  std::atomic<bool> paused_flag_{false};
  std::atomic<std::uint64_t> applied_{0};
  std::atomic<std::uint64_t> rejected_{0};
  // manual clock: show() stores the time, then bumps shown_req_; the simulation thread copies
  // shown_req_ into shown_done_ once every due frame is published
  alignas(kCacheLine) std::atomic<double> shown_t_{0.0};
  std::atomic<std::uint64_t> shown_req_{0};
  std::atomic<std::uint64_t> shown_done_{0};
  // manual clock: wakes wait_shown() when shown_done_ or the status changes, the simulation
  // thread when show() is called (the changes are made before the mutex is taken to notify)
  mutable std::mutex wake_mutex_;
  mutable std::condition_variable wake_cv_;
  RunnerError error_;
  std::exception_ptr exception_;
};

/// Wall clock used by the runner's display clock (steady_clock; unit: ns).
std::int64_t runner_now_ns();

}  // namespace huygens
