// huygens.Simulation (simulation.hpp): the steps, the fields as arrays, the viewer's commands.
#include "simulation.hpp"

#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "convert.hpp"
#include "huygens/common/finite.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/report.hpp"
#include "huygens/solvers/registry.hpp"
#include "huygens/solvers/sizing.hpp"

namespace huygens::python {

namespace {

// The scene's estimate on one process (what make_solver checked), for a refusal's figures.
MemoryEstimate one_process_memory(const Scene& scene) {
  const MemoryCheckOff sizing_only;
  return scene_rank_memory(scene)(1);
}

}  // namespace

Simulation::Busy::Busy(const Simulation& s, bool reading) : s_(s) {
  if (s_.busy_.exchange(true)) {
    if (reading && s_.owner_.load() == std::this_thread::get_id()) return;  // between two steps of its own call
    throw std::runtime_error(
        "this huygens.Simulation is in use by another thread (or by the call a signal handler interrupted): "
        "one call at a time");
  }
  s_.owner_.store(std::this_thread::get_id());
  owns_ = true;
}
Simulation::Busy::~Busy() {
  if (!owns_) return;
  s_.owner_.store(std::thread::id());
  s_.busy_.store(false);
}

Simulation::Simulation(const py::object& scene, bool fast_plans) : scene_(scene_from(scene, &label_)) {
  options_.measure_plans = !fast_plans;
  reset();
}

void Simulation::reset() {
  Busy busy(*this);
  solver_.reset();  // the old solver goes now unless an array still holds it
  stop_.reset();
  try {
    py::gil_scoped_release release;  // FFTW planning may take seconds
    solver_ = make_solver(scene_, options_);
  } catch (const ResourceError& e) {
    throw MemoryRefusedError(e.what(), one_process_memory(scene_), available_memory());
  } catch (const RunStopped& e) {
    throw RunStoppedError(std::string("run stopped: ") + e.what(), e.stage(), e.step(), 0.0);
  }
}

Solver& Simulation::solver() const {
  if (!solver_) throw std::runtime_error("no solver: the last reset() failed; call reset() again");
  return *solver_;
}

void Simulation::stopped(std::exception_ptr e) {
  try {
    std::rethrow_exception(e);  // anything but the two stops leaves as it is
  } catch (const RunStopped& x) {
    stop_.emplace(std::string("run stopped: ") + x.what(), x.stage(), x.step(), solver().time());
  }
  throw *stop_;
}

void Simulation::step_once() {
  Solver& s = solver();
  std::exception_ptr error;
  {
    py::gil_scoped_release release;
    try {
      s.step();
    } catch (...) {
      error = std::current_exception();
    }
  }
  if (error) stopped(error);
}

std::int64_t Simulation::advance(std::int64_t max_steps, double until_s) {
  Busy busy(*this);
  if (stop_) throw *stop_;
  const Solver& s = solver();
  const double tol = std::isfinite(until_s) ? 1e-9 * std::max(1.0, std::abs(until_s)) : 0.0;
  std::int64_t taken = 0;
  while (taken < max_steps && s.time() < until_s - tol) {
    step_once();
    ++taken;
    // Ctrl-C: Python's handler ran here, at a step boundary; KeyboardInterrupt goes up as it is
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  return taken;
}

std::int64_t Simulation::step(std::int64_t n) {
  if (n < 0) throw py::value_error("step(n): n must be >= 0, got " + std::to_string(n));
  return advance(n, std::numeric_limits<double>::infinity());
}

std::int64_t Simulation::run(double until_s) {
  if (std::isnan(until_s)) throw py::value_error("run(until_s): until_s is NaN");
  return advance(std::numeric_limits<std::int64_t>::max(), until_s);
}

std::vector<OutputField> Simulation::outputs() {
  Solver& s = solver();
  std::vector<OutputField> out;
  std::exception_ptr error;
  {
    py::gil_scoped_release release;  // an SPH surface extraction is a pass over the particles
    try {
      out = s.outputs();
    } catch (...) {
      error = std::current_exception();
    }
  }
  if (error) stopped(error);
  return out;
}

std::vector<std::string> Simulation::field_names() {
  Busy busy(*this);
  if (names_.empty())  // a solver's fields are fixed: asked once (outputs() refreshes the buffers)
    for (const OutputField& f : outputs()) names_.push_back(f.name);
  return names_;
}

namespace {

const OutputField& find_field(const std::vector<OutputField>& out, const std::string& name) {
  std::string names;
  for (const OutputField& f : out) {
    if (f.name == name) return f;
    names += (names.empty() ? "" : ", ") + f.name;
  }
  throw py::key_error("no field '" + name + "' in this scene's solver (its fields: " + names + ")");
}

}  // namespace

py::array Simulation::field(const std::string& name, bool copy) {
  Busy busy(*this);
  const std::vector<OutputField> out = outputs();
  const OutputField& f = find_field(out, name);
  const std::vector<py::ssize_t> shape(f.shape.begin(), f.shape.end());
  std::size_t count = 1;
  for (std::size_t d : f.shape) count *= d;
  if (count != f.data.size())
    throw std::logic_error("field '" + name + "': shape and data differ in size (a solver bug)");
  if (copy) {
    py::array_t<float> a(shape);
    if (count) std::memcpy(a.mutable_data(), f.data.data(), count * sizeof(float));
    return a;
  }
  // a view of the solver's buffer (C order, float32); the capsule holds the solver while it lives
  auto* keep = new std::shared_ptr<Solver>(solver_);
  const py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<Solver>*>(p); });
  py::array_t<float> a(shape, f.data.data(), base);
  a.attr("flags").attr("writeable") = false;
  return a;
}

std::uintptr_t Simulation::field_address(const std::string& name) {
  Busy busy(*this);
  const std::vector<OutputField> out = outputs();
  return reinterpret_cast<std::uintptr_t>(find_field(out, name).data.data());
}

void Simulation::apply(const Command& c, const std::string& what) {
  Busy busy(*this);
  if (stop_) throw *stop_;
  bool ok = false;
  try {
    ok = solver().apply(c);
  } catch (...) {
    stopped(std::current_exception());
  }
  if (!ok)
    throw CommandRefusedError("the " + scene_.solver + " solver of " + label_ + " refused " + what, command_kind(c));
}

void Simulation::drop(double x_m, double y_m, double radius_m, double depth_m) {
  apply(cmd::Drop{static_cast<float>(x_m), static_cast<float>(y_m), static_cast<float>(radius_m),
                  static_cast<float>(depth_m)},
        fmt("drop(x_m=%g, y_m=%g, radius_m=%g, depth_m=%g)", x_m, y_m, radius_m, depth_m));
}

void Simulation::steer_ship(int ship, double x_m, double y_m, double vx_mps, double vy_mps) {
  apply(cmd::ShipTarget{ship, static_cast<float>(x_m), static_cast<float>(y_m), static_cast<float>(vx_mps),
                        static_cast<float>(vy_mps)},
        fmt("steer_ship(%d, x_m=%g, y_m=%g, vx_mps=%g, vy_mps=%g)", ship, x_m, y_m, vx_mps, vy_mps));
}

void Simulation::toggle(const std::string& feature, bool on) {
  apply(cmd::Toggle{CommandName(feature), on}, "toggle('" + feature + "', " + (on ? "True" : "False") + ")");
}

void Simulation::set_param(const std::string& name, double value) {
  apply(cmd::SetParam{CommandName(name), value}, fmt("set_param('%s', %g)", name.c_str(), value));
}

double Simulation::time_s() const {
  Busy busy(*this, true);
  return solver().time();
}
std::int64_t Simulation::step_count() const {
  Busy busy(*this, true);
  return solver().steps();
}

py::object Simulation::meta() const {
  Busy busy(*this, true);
  return to_python(solver().meta());
}

py::list Simulation::stats() const {
  Busy busy(*this, true);
  py::list out;
  for (const StageStat& s : solver().stats().all())
    out.append(py::dict(py::arg("stage") = s.name, py::arg("calls") = s.calls, py::arg("total_ms") = s.ns * 1e-6,
                        py::arg("ms_per_call") = s.calls ? s.ns * 1e-6 / static_cast<double>(s.calls) : 0.0,
                        py::arg("transforms") = s.transforms, py::arg("bytes") = s.bytes));
  return out;
}

py::dict Simulation::memory() const {
  Busy busy(*this, true);
  py::dict d = estimate_dict(solver().memory());
  d["available_bytes"] = available_memory();
  return d;
}

py::list Simulation::ship_poses() const {
  Busy busy(*this, true);
  std::vector<ShipState> poses(256);
  poses.resize(solver().ship_poses(poses));
  py::list out;
  for (const ShipState& p : poses)
    out.append(py::dict(py::arg("x_m") = p.x_m, py::arg("y_m") = p.y_m, py::arg("heading_rad") = p.heading_rad,
                        py::arg("speed_mps") = p.speed_mps));
  return out;
}

std::string Simulation::repr() const {
  if (busy_.load() && owner_.load() != std::this_thread::get_id())
    return "<huygens.Simulation " + label_ + " (" + scene_.solver + "), in use by another thread>";
  if (!solver_) return "<huygens.Simulation " + label_ + " (" + scene_.solver + "), no solver>";
  return fmt("<huygens.Simulation %s (%s): step %lld, t = %.6g s%s>", label_.c_str(), scene_.solver.c_str(),
             static_cast<long long>(solver_->steps()), solver_->time(), stop_ ? ", stopped" : "");
}

}  // namespace huygens::python
