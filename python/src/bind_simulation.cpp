// The Python class huygens.Simulation and its docstrings (help(huygens.Simulation)).
#include <pybind11/stl.h>

#include "simulation.hpp"

namespace huygens::python {

namespace {

constexpr const char* kClassDoc = R"(A scene's solver, stepped from Python.

Simulation(scene, *, fast_plans=False)

scene: a scene file's path (str or os.PathLike), a shipped scene's name
(huygens.scenes(): "ring", "ocean", ...; a file of that name comes first, as
for `huygens run`), or a dict with a scene's JSON (files it names, such as an
OBJ mesh, are relative to the working folder). huygens.scene(name) gives a
shipped scene as a dict to change before passing it here.

fast_plans: FFT plans without timing them (FFTW_ESTIMATE), as `huygens run
--fast-plans`: a faster start and the same bits on every run; the default times
them (FFTW_MEASURE), which may differ from run to run in the last bits.

Raises SceneError (a ValueError; .path is the JSON path, as `huygens run`
exits 2), MemoryRefused (a MemoryError with the figures, exit 4) before
anything is allocated, RunStopped for a non-finite initial state.

Steps release the GIL; Ctrl-C (KeyboardInterrupt) stops step() and run() at
the next step boundary, with the state whole. One thread at a time: a call
while another thread's call has not returned raises RuntimeError.)";

constexpr const char* kStepDoc = R"(Takes n full steps (default 1); returns the steps taken.

Ctrl-C raises KeyboardInterrupt after the step in progress: step_count and
time_s then say where it stopped, and stepping may go on. A non-finite value
(or a negative LBM depth) raises RunStopped with its stage and step.)";

constexpr const char* kRunDoc = R"(Steps until time_s >= until_s; returns the steps taken.

The last step ends at until_s (to 1e-9 relative) or passes it by less than one
step (SPH's step is adaptive). Nothing happens when time_s is already there.
until_s=math.inf runs until Ctrl-C. Stops as step() does (KeyboardInterrupt,
RunStopped).)";

constexpr const char* kFieldDoc = R"(A field of the current state as a NumPy float32 array (C order, SI units).

The names (Simulation.fields): Huygens "eta" (m, rows = y, cols = x, the
visible region); SPH "pos" (particles x 3, m, by particle id), "vel" (particles
x 3, m/s), "density" (kg/m^3), "pressure" (the density pass's) and "eta" (the surface height
above the floor, m); LBM "h" (depth, m), "u" (rows x cols x 2,
m/s) and "eta" (h + bed, m). An unknown name raises KeyError.

copy=False (default): a read-only view of the solver's own output buffer, no
copy, for every field of every solver. The array keeps that buffer's memory
alive (past reset() and the Simulation itself), but its values are this
state's only until the next step(), run(), field(), command or reset(): the
solver writes the next state into the same buffer (Huygens at every step, SPH
and LBM when a field is asked for again). Keep a state with copy=True or
numpy.array(a).

copy=True: a new writable array that nothing changes.)";

constexpr const char* kDropDoc = R"(Drops a stone at (x_m, y_m) as the viewer does (metres in the full grid's frame).

Huygens: a Gaussian depression of sigma radius_m and depth depth_m (the grid
only: 0 <= x, y <= length_m); SPH: a downward velocity splash of speed
depth_m sqrt(g / radius_m). The LBM refuses it. A refused command raises
CommandRefused (a ValueError).)";

constexpr const char* kSteerDoc = R"(Steers ship `ship` (its index in the scene's "ships") as the viewer's drag does.

The ship leaves its scene path now and heads for (x_m, y_m), arriving with
velocity (vx_mps, vy_mps). Huygens scenes with ships only; CommandRefused
otherwise (no ships, an index out of range).)";

constexpr const char* kToggleDoc = R"(Switches a feature on or off as the viewer's check boxes do.

Huygens: 'stokes' (the second-order Stokes height) and 'wind' (a scene with a
wind sea). CommandRefused for anything else.)";

constexpr const char* kParamDoc = R"(Sets a solver parameter as the viewer does.

SPH: 'gravity_x', 'gravity_y', 'gravity_z' (m/s^2, |g| <= 1000: tilts or
shakes the container). CommandRefused for anything else.)";

void bind_stepping(py::class_<Simulation>& c) {
  c.def(py::init<const py::object&, bool>(), py::arg("scene"), py::kw_only(), py::arg("fast_plans") = false)
      .def("step", &Simulation::step, py::arg("n") = 1, kStepDoc)
      .def("run", &Simulation::run, py::arg("until_s"), kRunDoc)
      .def("reset", &Simulation::reset,
           "Starts the scene again from its initial state (a new solver; arrays of the old one stay readable).")
      .def_property_readonly("time_s", &Simulation::time_s, "Simulated time (unit: s).")
      .def_property_readonly("step_count", &Simulation::step_count, "Full steps taken since the start or reset().")
      .def_property_readonly("solver", &Simulation::solver_name, "The scene's solver: 'huygens', 'sph' or 'lbm'.")
      .def_property_readonly("scene", &Simulation::label,
                             "What the scene is called: its file, 'built-in NAME.json' or '<dict>'.")
      .def("__repr__", &Simulation::repr);
}

void bind_fields(py::class_<Simulation>& c) {
  c.def("field", &Simulation::field, py::arg("name"), py::kw_only(), py::arg("copy") = false, kFieldDoc)
      .def_property_readonly("fields", &Simulation::field_names, "The names field() accepts, in dump order.")
      .def("_field_address", &Simulation::field_address, py::arg("name"),
           "The address of the solver's buffer of field `name` (tests of the zero-copy view).")
      .def_property_readonly("meta", &Simulation::meta,
                             "Grid, spacing, time step, visible region, ... as `huygens run` writes them to meta.json.")
      .def("stats", &Simulation::stats,
           "The stage table of `huygens run`: dicts with stage, calls, total_ms, ms_per_call, transforms, bytes.")
      .def_property_readonly("memory", &Simulation::memory,
                             "The solver's memory estimate: total_bytes, parts [{name, bytes, key}], summary, "
                             "largest_part, available_bytes.");
}

void bind_commands(py::class_<Simulation>& c) {
  c.def("drop", &Simulation::drop, py::arg("x_m"), py::arg("y_m"), py::arg("radius_m") = 0.05,
        py::arg("depth_m") = 0.01, kDropDoc)
      .def("steer_ship", &Simulation::steer_ship, py::arg("ship"), py::arg("x_m"), py::arg("y_m"),
           py::arg("vx_mps") = 0.0, py::arg("vy_mps") = 0.0, kSteerDoc)
      .def("toggle", &Simulation::toggle, py::arg("feature"), py::arg("on") = true, kToggleDoc)
      .def("set_param", &Simulation::set_param, py::arg("name"), py::arg("value"), kParamDoc)
      .def("ship_poses", &Simulation::ship_poses,
           "Where the ships are now (steered or on their path): dicts with x_m, y_m, heading_rad, speed_mps.");
}

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<Simulation> c(m, "Simulation", kClassDoc);
  bind_stepping(c);
  bind_fields(c);
  bind_commands(c);
}

}  // namespace huygens::python
