// Conversions between the core's values and Python objects, and the translation of the core's
// errors into the package's exception classes (huygens/_errors.py).
#include "convert.hpp"

#include <nlohmann/json.hpp>

#include "errors.hpp"
#include "huygens/common/program.hpp"
#include "huygens/common/shipped_scenes.hpp"

namespace huygens::python {

py::object to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

Scene scene_from(const py::object& scene, std::string* label) {
  if (py::isinstance<py::dict>(scene)) {
    const std::string text = py::str(py::module_::import("json").attr("dumps")(scene));
    if (label) *label = "<dict>";
    return parse_scene_text(text, "<dict>");
  }
  const py::object os = py::module_::import("os");
  if (!py::isinstance<py::str>(scene) && !py::isinstance(scene, os.attr("PathLike")))
    throw py::type_error("scene: a path, a shipped scene's name (huygens.scenes()) or a dict, not " +
                         std::string(py::str(scene.get_type().attr("__name__"))));
  const std::string arg = py::str(os.attr("fspath")(scene));
  return open_scene(arg, label);
}

py::dict estimate_dict(const MemoryEstimate& m) {
  py::list parts;
  for (const auto& p : m.parts)
    parts.append(py::dict(py::arg("name") = p.name, py::arg("bytes") = p.bytes,
                          py::arg("key") = p.key.empty() ? m.size_key : p.key));
  return py::dict(py::arg("total_bytes") = m.total(), py::arg("parts") = parts, py::arg("summary") = m.summary(),
                  py::arg("largest_part") = m.largest_part());
}

namespace {

// An instance of the class `name` of huygens._errors, raised as the current Python error.
void raise(const char* name, const char* message, const py::dict& fields) {
  const py::object cls = py::module_::import("huygens._errors").attr(name);
  const py::object e = cls(message, **fields);
  PyErr_SetObject(cls.ptr(), e.ptr());
}

}  // namespace

void translate_exception(std::exception_ptr p) {
  try {
    std::rethrow_exception(p);
  } catch (const SceneError& e) {
    raise("SceneError", e.what(), py::dict(py::arg("path") = e.path()));
  } catch (const RunStoppedError& e) {
    raise("RunStopped", e.what(),
          py::dict(py::arg("stage") = e.stage, py::arg("step") = e.step, py::arg("time_s") = e.time_s));
  } catch (const MemoryRefusedError& e) {
    std::string key;  // the largest part's, as MemoryEstimate::largest_part() names it
    std::uint64_t largest = 0;
    for (const auto& part : e.need.parts)
      if (key.empty() || part.bytes > largest)
        largest = part.bytes, key = part.key.empty() ? e.need.size_key : part.key;
    raise("MemoryRefused", e.what(),
          py::dict(py::arg("needed_bytes") = e.need.total(), py::arg("available_bytes") = e.available_bytes,
                   py::arg("parts") = estimate_dict(e.need)["parts"], py::arg("key") = key));
  } catch (const CommandRefusedError& e) {
    raise("CommandRefused", e.what(), py::dict(py::arg("command") = e.command));
  } catch (const ResourceError& e) {  // a refusal outside a Simulation's construction: the message alone
    raise("MemoryRefused", e.what(), py::dict());
  } catch (const UsageError& e) {  // a bad HUYGENS_MAX_MEMORY_GIB
    PyErr_SetString(PyExc_ValueError, e.what());
  }
}

}  // namespace huygens::python
