#pragma once
// Conversions between the core's values and Python objects, shared by the binding's sources.
#include <pybind11/pybind11.h>

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "huygens/common/memory.hpp"
#include "huygens/common/scene.hpp"

namespace huygens::python {

namespace py = pybind11;

/// A JSON value as Python objects (dict, list, str, float, int, bool, None).
py::object to_python(const nlohmann::json& j);

/// A scene from what a user passes: a path (str or os.PathLike) or a shipped scene's name
/// (open_scene()), or a dict (its JSON text, parse_scene_text(); files it names are relative to
/// the working folder). `label` receives what to call it. Throws SceneError.
Scene scene_from(const py::object& scene, std::string* label);

/// An estimate as a dict: total_bytes, parts [{name, bytes, key}], summary, largest_part.
py::dict estimate_dict(const MemoryEstimate& m);

/// Turns the exception in flight into the Python error the package documents: SceneError,
/// RunStopped, MemoryRefused, CommandRefused (module.cpp registers it).
void translate_exception(std::exception_ptr p);

}  // namespace huygens::python
