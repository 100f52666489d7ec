#include "huygens/common/scene.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace huygens {

using nlohmann::json;

JsonIn::JsonIn(const json& j, std::string path) : j_(&j), path_(std::move(path)) {}

void JsonIn::fail(const std::string& key, const std::string& reason) const {
  throw SceneError(child_path(key), reason);
}
void JsonIn::fail_here(const std::string& reason) const { throw SceneError(path_, reason); }

bool JsonIn::has(const std::string& key) const { return j_->is_object() && j_->contains(key); }
bool JsonIn::is_null(const std::string& key) const { return has(key) && (*j_)[key].is_null(); }

void JsonIn::allow_only(std::initializer_list<const char*> allowed) const {
  if (!j_->is_object()) fail_here("expected an object");
  for (const auto& [key, value] : j_->items()) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || key == a;
    if (!ok) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail(key, "unknown key (allowed here: " + list + ")");
    }
  }
}

JsonIn JsonIn::object(const std::string& key) const {
  if (!has(key)) fail(key, "missing required object");
  const json& v = (*j_)[key];
  if (!v.is_object()) fail(key, "expected an object");
  return JsonIn(v, child_path(key));
}

std::optional<JsonIn> JsonIn::optional_object(const std::string& key) const {
  if (!has(key) || (*j_)[key].is_null()) return std::nullopt;
  return object(key);
}

std::vector<JsonIn> JsonIn::array(const std::string& key) const {
  std::vector<JsonIn> out;
  if (!has(key) || (*j_)[key].is_null()) return out;
  const json& v = (*j_)[key];
  if (!v.is_array()) fail(key, "expected an array");
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string p = child_path(key) + "[" + std::to_string(i) + "]";
    if (!v[i].is_object()) throw SceneError(p, "expected an object");
    out.emplace_back(v[i], p);
  }
  return out;
}

namespace {
std::string range_text(double lo, double hi) {
  std::ostringstream s;
  s << "[" << lo << ", " << hi << "]";
  return s.str();
}
}  // namespace

std::optional<double> JsonIn::optional_number(const std::string& key, double lo, double hi) const {
  if (!has(key) || (*j_)[key].is_null()) return std::nullopt;
  const json& v = (*j_)[key];
  if (!v.is_number()) fail(key, std::string("expected a number, got ") + v.type_name());
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi) {
    std::ostringstream s;
    s << "value " << x << " is out of range " << range_text(lo, hi);
    fail(key, s.str());
  }
  return x;
}

double JsonIn::number(const std::string& key, double lo, double hi) const {
  if (!has(key)) fail(key, "missing required number");
  auto v = optional_number(key, lo, hi);
  if (!v) fail(key, "expected a number, got null");
  return *v;
}

double JsonIn::number(const std::string& key, double fallback, double lo, double hi) const {
  if (!has(key)) return fallback;
  return number(key, lo, hi);
}

long long JsonIn::integer(const std::string& key, long long lo, long long hi) const {
  if (!has(key)) fail(key, "missing required integer");
  const json& v = (*j_)[key];
  if (!v.is_number_integer()) {
    if (v.is_number_float() && std::floor(v.get<double>()) == v.get<double>()) {
      // 512.0 is accepted as 512.
    } else {
      fail(key, std::string("expected an integer, got ") + (v.is_number() ? "a fraction" : v.type_name()));
    }
  }
  const long long x = v.is_number_integer() ? v.get<long long>() : static_cast<long long>(v.get<double>());
  if (x < lo || x > hi)
    fail(key,
         "value " + std::to_string(x) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return x;
}

long long JsonIn::integer(const std::string& key, long long fallback, long long lo, long long hi) const {
  if (!has(key)) return fallback;
  return integer(key, lo, hi);
}

bool JsonIn::boolean(const std::string& key, bool fallback) const {
  if (!has(key)) return fallback;
  const json& v = (*j_)[key];
  if (!v.is_boolean()) fail(key, std::string("expected true or false, got ") + v.type_name());
  return v.get<bool>();
}

std::string JsonIn::string(const std::string& key, const std::string& fallback,
                           std::initializer_list<const char*> allowed) const {
  if (!has(key)) return fallback;
  const json& v = (*j_)[key];
  if (!v.is_string()) fail(key, std::string("expected a string, got ") + v.type_name());
  std::string s = v.get<std::string>();
  if (allowed.size() == 0) return s;
  std::string list;
  for (const char* a : allowed) {
    if (s == a) return s;
    list += (list.empty() ? "\"" : ", \"") + std::string(a) + "\"";
  }
  fail(key, "\"" + s + "\" is not one of " + list);
}

void JsonIn::read_numbers(const std::string& key, double* out, std::size_t count, double lo, double hi) const {
  const std::string want = "an array of " + std::to_string(count) + " numbers";
  if (!has(key)) fail(key, "required (" + want + ")");
  const json& v = (*j_)[key];
  if (!v.is_array() || v.size() != count) fail(key, "expected " + want);
  for (std::size_t k = 0; k < count; ++k) {
    const std::string p = child_path(key) + "[" + std::to_string(k) + "]";
    if (!v[k].is_number()) throw SceneError(p, std::string("expected a number, got ") + v[k].type_name());
    const double x = v[k].get<double>();
    if (!std::isfinite(x) || x < lo || x > hi)
      throw SceneError(p, "value " + std::to_string(x) + " is out of range [" + std::to_string(lo) + ", " +
                              std::to_string(hi) + "]");
    out[k] = x;
  }
}

void JsonIn::reject_renamed(std::initializer_list<std::pair<const char*, const char*>> renamed) const {
  for (const auto& [old_key, new_key] : renamed)
    if (has(old_key))
      fail(old_key, std::string("this key is now \"") + new_key +
                        "\" (every dimensional key carries its SI unit suffix, docs/design.md section 6)");
}

JsonIn Scene::root() const { return JsonIn(*doc, "$"); }

Scene parse_scene_text(const std::string& text, const std::string& name) {
  auto doc = std::make_shared<json>();
  try {
    *doc = json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte is the 1-based offset of the error; translate it into line and column.
    std::size_t line = 1, col = 1;
    for (std::size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    std::string what = e.what();
    const auto p = what.find("error:");
    throw SceneError("$", "JSON syntax error in " + name + " at line " + std::to_string(line) + ", column " +
                              std::to_string(col) + ": " + (p == std::string::npos ? what : what.substr(p + 7)));
  }
  if (!doc->is_object()) throw SceneError("$", "a scene must be a JSON object");
  Scene s;
  s.file = name;
  s.doc = doc;
  s.solver = s.root().string("solver", "huygens", {"huygens", "sph", "lbm"});
  return s;
}

Scene load_scene(const std::string& file) {
  std::ifstream f(file, std::ios::binary);
  if (!f) throw SceneError("$", "cannot open scene file " + file);
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_scene_text(ss.str(), file);
}

}  // namespace huygens
