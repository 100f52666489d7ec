#pragma once
// The scenes shipped in scenes/ compiled into the library, so that a program run from any folder
// (or installed) can open them by name: `huygens run ocean`, `huygens-viz sph_wedge`. The OBJ meshes
// they name are compiled in too, by their path relative to the scenes folder ("meshes/wedge.obj").
#include <string>
#include <string_view>

#include "huygens/common/scene.hpp"

namespace huygens {

/// The shipped scenes' file names, separated by spaces ("channel.json dam_break.json ...").
const char* shipped_scene_names();

/// A shipped file's text by its path relative to the scenes folder ("ocean.json",
/// "meshes/wedge.obj"), or an empty view.
std::string_view shipped_scene_text(std::string_view name);

/// A scene named by a program's SCENE argument: the JSON file `arg` when it exists or names a
/// folder ('/'); otherwise the shipped scene `arg` ("ocean" or "ocean.json"); "" is the shipped
/// default.json. `label` (optional) receives what to call it ("scenes/ocean.json", "built-in
/// ocean.json"). Throws SceneError like load_scene (a missing file names itself).
Scene open_scene(const std::string& arg, std::string* label = nullptr);

}  // namespace huygens
