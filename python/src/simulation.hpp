#pragma once
// huygens.Simulation: one solver (make_solver) stepped from Python. Steps run with the GIL released
// and a check for Ctrl-C (PyErr_CheckSignals) at every step boundary; fields are NumPy arrays that
// view the solver's own output buffers (no copy) and keep the solver alive.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "errors.hpp"
#include "huygens/common/scene.hpp"
#include "huygens/pipeline/solver.hpp"

namespace huygens::python {

namespace py = pybind11;

class Simulation {
 public:
  Simulation(const py::object& scene, bool fast_plans);

  /// Takes n steps; returns how many were taken (n, or fewer on Ctrl-C, which re-raises).
  std::int64_t step(std::int64_t n);
  /// Steps until time() >= until_s (within 1e-9 relative); returns the steps taken.
  std::int64_t run(double until_s);
  /// The field `name` as a read-only view of the solver's buffer, or an owned copy.
  py::array field(const std::string& name, bool copy);
  /// The address of field `name`'s data in the solver (for the zero-copy test).
  std::uintptr_t field_address(const std::string& name);
  std::vector<std::string> field_names();

  void drop(double x_m, double y_m, double radius_m, double depth_m);
  void steer_ship(int ship, double x_m, double y_m, double vx_mps, double vy_mps);
  void toggle(const std::string& feature, bool on);
  void set_param(const std::string& name, double value);
  /// A new solver from the same scene (arrays of the old one stay valid: they keep it alive).
  void reset();

  double time_s() const;
  std::int64_t step_count() const;
  const std::string& solver_name() const { return scene_.solver; }
  const std::string& label() const { return label_; }
  py::object meta() const;
  py::list stats() const;
  py::dict memory() const;
  py::list ship_poses() const;
  std::string repr() const;

 private:
  /// Marks the simulation busy for one call (a second thread gets RuntimeError, not a data race).
  /// `reading`: a read of the state may also come from the thread whose call is under way (a
  /// signal handler Python runs between two steps, when the state is whole).
  class Busy {
   public:
    explicit Busy(const Simulation& s, bool reading = false);
    ~Busy();
    Busy(const Busy&) = delete;
    Busy& operator=(const Busy&) = delete;

   private:
    const Simulation& s_;
    bool owns_ = false;
  };
  std::int64_t advance(std::int64_t max_steps, double until_s);
  /// One step with the GIL released; a non-finite value or a dry LBM cell becomes RunStoppedError.
  void step_once();
  /// Turns a RunStopped (a non-finite value, an LBM depth below 0) in flight into RunStoppedError (and remembers it).
  [[noreturn]] void stopped(std::exception_ptr e);
  void apply(const Command& c, const std::string& what);
  Solver& solver() const;
  std::vector<OutputField> outputs();

  std::string label_;  // before scene_: the constructor's scene_from() writes it
  Scene scene_;
  RunOptions options_;
  std::shared_ptr<Solver> solver_;
  std::optional<RunStoppedError> stop_;
  std::vector<std::string> names_;  ///< field_names(), once
  mutable std::atomic<bool> busy_{false};
  mutable std::atomic<std::thread::id> owner_{};
};

void bind_simulation(py::module_& m);

}  // namespace huygens::python
