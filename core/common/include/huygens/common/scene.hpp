#pragma once
// Scene files (docs/design.md section 6): JSON parsed into plain parameter structs. Every
// error names the JSON path of the offending value ("$.grid.n", "$.initial[2].x_m")
// and is reported by the programs with exit code 2.
#include <array>
#include <cstddef>
#include <functional>
#include <initializer_list>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace huygens {

/// A scene error: `path` is the JSON path of the offending value, `what()` the full message.
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string path, const std::string& reason)
      : std::runtime_error(path + ": " + reason), path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// Read access to one JSON object or value with its path, for parsing parameter structs.
/// Each getter checks type and range and throws SceneError naming the path.
class JsonIn {
 public:
  JsonIn(const nlohmann::json& j, std::string path);

  const std::string& path() const { return path_; }
  const nlohmann::json& raw() const { return *j_; }
  bool has(const std::string& key) const;
  /// True when the key is present and JSON null.
  bool is_null(const std::string& key) const;
  std::string child_path(const std::string& key) const { return path_ + "." + key; }

  /// Throws for every key of this object that is not in `allowed` ("unknown key").
  void allow_only(std::initializer_list<const char*> allowed) const;
  /// The object under `key` (required).
  JsonIn object(const std::string& key) const;
  /// The object under `key`, or nullopt when absent or null.
  std::optional<JsonIn> optional_object(const std::string& key) const;
  /// Elements of the array under `key`; empty when absent.
  std::vector<JsonIn> array(const std::string& key) const;

  /// A required number in [lo, hi].
  double number(const std::string& key, double lo, double hi) const;
  /// A number in [lo, hi], or `fallback` when absent.
  double number(const std::string& key, double fallback, double lo, double hi) const;
  /// A number in [lo, hi], or nullopt when absent or null.
  std::optional<double> optional_number(const std::string& key, double lo, double hi) const;
  /// An integer in [lo, hi], or `fallback` when absent.
  long long integer(const std::string& key, long long fallback, long long lo, long long hi) const;
  /// A required integer in [lo, hi].
  long long integer(const std::string& key, long long lo, long long hi) const;
  /// A required array of N numbers, each in [lo, hi]; an error names the element
  /// ("$.sph.container_m[1]"). The one vector reader of every solver's scene block.
  template <std::size_t N>
  std::array<double, N> vec(const std::string& key, double lo, double hi) const {
    std::array<double, N> out{};
    read_numbers(key, out.data(), N, lo, hi);
    return out;
  }
  bool boolean(const std::string& key, bool fallback) const;
  /// Throws for a key of an older scene format ({old, new} pairs), naming its new name.
  void reject_renamed(std::initializer_list<std::pair<const char*, const char*>> renamed) const;
  /// A string, one of `allowed` when that is not empty; `fallback` when absent.
  std::string string(const std::string& key, const std::string& fallback,
                     std::initializer_list<const char*> allowed = {}) const;

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;
  /// Reads the array under `key` into out[0..count) (see vec()).
  void read_numbers(const std::string& key, double* out, std::size_t count, double lo, double hi) const;
  [[noreturn]] void fail_here(const std::string& reason) const;

 private:
  const nlohmann::json* j_;
  std::string path_;
};

/// A loaded scene document: the file it came from and its parsed JSON.
struct Scene {
  std::string file;
  std::string solver;  ///< a registered solver's name ("huygens", "sph", "lbm"; solvers/registry.hpp)
  std::shared_ptr<const nlohmann::json> doc;
  /// The folder a file the scene names (an OBJ mesh) is relative to: the scene file's own
  /// folder, made absolute by load_scene (so it does not depend on the working directory);
  /// empty for scene text (parse_scene_text): the working directory.
  std::string dir;
  /// A built-in scene's files by their path relative to the scene ("meshes/wedge.obj"; an empty
  /// view: not there). When set, read_scene_file reads only from here (the program carries
  /// the shipped scenes and their meshes, nothing is read from a folder).
  std::function<std::string_view(std::string_view)> embedded;
  JsonIn root() const;
};

/// Reads and parses a scene file; syntax errors name the line and column.
Scene load_scene(const std::string& file);
/// Parses scene text (for tests); `name` stands for the file in messages.
Scene parse_scene_text(const std::string& text, const std::string& name = "<scene>");

/// The bytes of a file the scene names (`relative`: relative to the scene, Scene::dir, or
/// absolute; a built-in scene's from Scene::embedded). Throws std::runtime_error naming the path
/// it tried when the file cannot be read; a parser turns it into a SceneError at its JSON path.
std::string read_scene_file(const Scene& scene, const std::string& relative);

}  // namespace huygens
