// The extension module huygens._huygens: Simulation (bind_simulation.cpp), the package's functions
// (scenes, scene, validate, validation_cases, memory_estimate) and the submodule reference
// (reference.cpp). The pure-Python huygens/__init__.py re-exports them with the exception classes.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "convert.hpp"
#include "huygens/common/isa.hpp"
#include "huygens/common/shipped_scenes.hpp"
#include "huygens/solvers/sizing.hpp"
#include "huygens/validation/validation.hpp"
#include "simulation.hpp"

namespace huygens::python {

void bind_reference(py::module_& m);

namespace {

std::vector<std::string> shipped_names() {
  std::vector<std::string> out;
  std::string all = shipped_scene_names(), word;
  all += ' ';
  for (char ch : all) {
    if (ch != ' ') {
      word += ch;
    } else if (!word.empty()) {
      if (word.size() > 5 && word.compare(word.size() - 5, 5, ".json") == 0) word.resize(word.size() - 5);
      out.push_back(word);
      word.clear();
    }
  }
  return out;
}

py::object scene_dict(const py::object& scene) {
  std::string label;
  const Scene s = scene_from(scene, &label);
  return to_python(*s.doc);
}

py::dict row_dict(const ValidationRow& r) {
  return py::dict(py::arg("case") = r.case_name, py::arg("quantity") = r.quantity, py::arg("measured") = r.measured,
                  py::arg("expected") = r.expected, py::arg("error") = r.error,
                  py::arg("tolerance") = r.judged ? py::object(py::float_(r.tolerance)) : py::object(py::none()),
                  py::arg("passed") = r.judged ? py::object(py::bool_(r.pass)) : py::object(py::none()),
                  py::arg("judged") = r.judged);
}

// The case names a user asked for (None: all; one str: that case), each checked.
std::vector<std::string> case_names(const py::object& cases, const std::vector<ValidationCase>& all) {
  std::vector<std::string> names;
  if (cases.is_none()) return names;
  if (py::isinstance<py::str>(cases))
    names.push_back(cases.cast<std::string>());
  else
    for (const py::handle h : cases) names.push_back(py::cast<std::string>(h));
  for (const std::string& n : names) {
    bool found = false;
    for (const ValidationCase& c : all) found = found || c.name == n;
    if (!found) throw py::value_error("unknown validation case '" + n + "' (huygens.validation_cases())");
  }
  return names;
}

py::list validate(const py::object& cases, bool progress) {
  const std::vector<ValidationCase> all = all_validation_cases();
  const std::vector<std::string> names = case_names(cases, all);
  py::list rows;
  for (const ValidationCase& c : all) {
    if (!names.empty() && std::find(names.begin(), names.end(), c.name) == names.end()) continue;
    if (progress)
      py::print("validating " + c.name + " ...", py::arg("file") = py::module_::import("sys").attr("stderr"));
    std::vector<ValidationRow> out;
    {
      py::gil_scoped_release release;
      try {
        out = c.run();
      } catch (const std::exception& e) {  // as `huygens validate` prints it: a failed row
        out.push_back(ValidationRow{c.name, std::string("exception: ") + e.what(), 0, 0, 0, 0, false});
      }
    }
    for (const ValidationRow& r : out) rows.append(row_dict(r));
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C between two cases
  }
  return rows;
}

py::list validation_cases() {
  py::list out;
  for (const ValidationCase& c : all_validation_cases())
    out.append(
        py::dict(py::arg("name") = c.name, py::arg("solver") = c.solver, py::arg("description") = c.description));
  return out;
}

py::dict memory_estimate(const py::object& scene, int ranks) {
  if (ranks < 1) throw py::value_error("memory_estimate: ranks must be >= 1, got " + std::to_string(ranks));
  std::string label;
  const Scene s = scene_from(scene, &label);
  const SceneSizing z = scene_sizing(s);
  if (z.distributed && ranks > z.max_ranks)
    throw py::value_error(label + " runs on at most " + std::to_string(z.max_ranks) + " ranks (" + z.split_rule +
                          "), not " + std::to_string(ranks));
  const int p = z.distributed ? ranks : 1;
  py::dict d = estimate_dict(scene_rank_memory(s)(p));
  const std::uint64_t available = available_memory();
  d["solver"] = z.solver;
  d["grid"] = z.grid;
  d["ranks"] = p;
  d["distributed"] = z.distributed;
  d["max_ranks"] = z.distributed ? z.max_ranks : 1;
  d["available_bytes"] = available;
  d["fits"] = d["total_bytes"].cast<std::uint64_t>() <= available;
  return d;
}

constexpr const char* kModuleDoc =
    R"(Huygens water waves from Python: the extension module behind the package huygens.)";

void bind_functions(py::module_& m) {
  m.def("scenes", &shipped_names, "The shipped scenes' names (Simulation and scene() take them).");
  m.def("scene", &scene_dict, py::arg("scene"),
        "A scene (a shipped scene's name or a file) as a dict, to change and pass to Simulation.");
  m.def("validate", &validate, py::arg("cases") = py::none(), py::kw_only(), py::arg("progress") = false,
        R"(Runs validation cases as `huygens validate [CASE...]` does; returns its table as a list of rows.

cases: None (every case: 7 to 12 minutes on 2 cores), a case name or a list of
names (validation_cases() lists them; an unknown name raises ValueError).
Each row is a dict: case, quantity (with its unit), measured, expected, error,
tolerance and passed (None for a row reported without a target), judged.
A case that raises gives one failed row "exception: ...". The GIL is released
while a case runs; Ctrl-C raises KeyboardInterrupt after the case in progress.
progress=True prints "validating CASE ..." to stderr before each case.)");
  m.def("validation_cases", &validation_cases,
        "The validation cases as `huygens validate --list` prints them: dicts with name, solver, description.");
  m.def(
      "memory_estimate", &memory_estimate, py::arg("scene"), py::arg("ranks") = 1,
      R"(The memory a scene needs per rank on `ranks` MPI ranks, as `huygens run SCENE --dry-run --ranks P`; allocates nothing.

Returns a dict: total_bytes (the largest rank's), parts [{name, bytes, key}]
(key: the JSON path that sets the part's size), summary, largest_part, solver,
grid, ranks (1 for SPH, which is not distributed), distributed, max_ranks,
available_bytes (on this machine: MemAvailable, cgroup, ulimit -v,
HUYGENS_MAX_MEMORY_GIB) and fits. Raises SceneError for a bad scene, ValueError
for more ranks than the grid has rows for.)");
  m.def("build_isa", &build_isa, "The instruction set the package was compiled for, e.g. 'x86-64-v3 (AVX2 FMA)'.");
  m.def("cpu_isa", &cpu_isa, "This CPU's model name and vector extensions, as huygens-bench prints them.");
}

}  // namespace

PYBIND11_MODULE(_huygens, m) {
  m.doc() = kModuleDoc;
  py::register_exception_translator(&translate_exception);
  bind_simulation(m);
  bind_functions(m);
  py::module_ ref =
      m.def_submodule("reference", "Analytic solutions and measured data the validation compares against.");
  bind_reference(ref);
}

}  // namespace huygens::python
