#include "huygens/common/scene.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <vector>

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
// A double in messages: up to 10 significant digits ("1e+300", not 300 digits).
std::string number_text(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}
std::string range_text(double lo, double hi) { return "[" + number_text(lo) + ", " + number_text(hi) + "]"; }
}  // namespace

std::optional<double> JsonIn::optional_number(const std::string& key, double lo, double hi) const {
  if (!has(key) || (*j_)[key].is_null()) return std::nullopt;
  const json& v = (*j_)[key];
  if (!v.is_number()) fail(key, std::string("expected a number, got ") + v.type_name());
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < lo || x > hi)
    fail(key, "value " + number_text(x) + " is out of range " + range_text(lo, hi));
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
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (v.is_number_unsigned() || v.is_number_integer()) {
    // an unsigned above the largest long long is compared as unsigned, never wrapped
    const bool above =
        v.is_number_unsigned() && (hi < 0 || v.get<unsigned long long>() > static_cast<unsigned long long>(hi));
    const long long x = above ? hi : v.get<long long>();
    if (above || x < lo || x > hi) fail(key, "value " + v.dump() + " is out of range " + range);
    return x;
  }
  if (!v.is_number_float()) fail(key, std::string("expected an integer in ") + range + ", got " + v.type_name());
  // 512.0 is accepted as 512; the range is checked on the double, before any conversion
  const double d = v.get<double>();
  if (std::floor(d) != d) fail(key, "expected an integer in " + range + ", got a fraction " + number_text(d));
  if (!(d >= static_cast<double>(lo) && d <= static_cast<double>(hi) && std::abs(d) < 0x1p63))
    fail(key, "value " + number_text(d) + " is out of range " + range);
  const long long x = static_cast<long long>(d);
  if (x < lo || x > hi) fail(key, "value " + number_text(d) + " is out of range " + range);
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
      throw SceneError(p, "value " + number_text(x) + " is out of range " + range_text(lo, hi));
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

namespace {

// The JSON path of the value the parser is reading, kept by a SAX pass over the text, so that an
// error the parser raises without a position (a number that overflows a double) names "$.grid.n",
// and a key repeated in its object is refused with its path. A SAX pass and then a plain parse:
// nlohmann's parser with a callback scans the parent container at every object's end, quadratic in
// an array of objects (10^5 LBM regions took minutes); both passes here are linear.
class PathTracker : public nlohmann::json_sax<json> {
 public:
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& k) override {
    Frame& f = frames_.back();
    f.key = k;
    f.has_key = true;
    // RFC 8259 leaves repeated names to the parser; nlohmann keeps the last, silently
    if (!f.keys.insert(f.key).second)
      throw SceneError(path(),
                       "the key appears twice in its object (the later value would silently replace the "
                       "earlier one)");
    return true;
  }
  // the parser's own error, thrown as its type so that parse_json names its position or path
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    if (const auto* pe = dynamic_cast<const json::parse_error*>(&e)) throw *pe;
    if (const auto* oor = dynamic_cast<const json::out_of_range*>(&e)) throw *oor;
    throw std::runtime_error(e.what());
  }
  std::string path() const {
    std::string p = "$";
    for (const auto& f : frames_) {
      if (f.array)
        p += "[" + std::to_string(f.index) + "]";
      else if (f.has_key)
        p += "." + f.key;
    }
    return p;
  }

 private:
  struct Frame {
    bool array;
    bool has_key;
    std::string key;
    std::size_t index;
    std::set<std::string> keys;  // the object's keys so far
  };
  bool open(bool array) {
    frames_.push_back({array, false, {}, 0, {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return value();
  }
  bool value() {  // a value ends: the array it is in moves on
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  std::vector<Frame> frames_;
};

// Line and column (1-based) of the 1-based byte offset `byte` of `text`.
std::string line_column(const std::string& text, std::size_t byte) {
  std::size_t line = 1, col = 1;
  for (std::size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(col);
}

// The reason of a nlohmann message: after "[json.exception.<kind>.<id>] " and, for a parse error,
// after its own "parse error at line L, column C: " (the caller gives the position).
std::string json_reason(const json::exception& e) {
  std::string what = e.what();
  auto p = what.find("] ");
  if (p != std::string::npos) what = what.substr(p + 2);
  if (what.rfind("parse error", 0) == 0 && (p = what.find(": ")) != std::string::npos) what = what.substr(p + 2);
  return what;
}

json parse_json(const std::string& text, const std::string& name) {
  PathTracker tracker;
  try {
    json::sax_parse(text, &tracker);  // errors with their path, repeated keys
    return json::parse(text);
  } catch (const json::parse_error& e) {
    throw SceneError("$", "JSON syntax error in " + name + " at " + line_column(text, e.byte) + ": " + json_reason(e));
  } catch (const json::out_of_range& e) {
    // 406: a number literal beyond the range of a double (1e400)
    throw SceneError(tracker.path(),
                     "in " + name + ": " + json_reason(e) + " (numbers must be finite doubles, at most about 1.8e308)");
  } catch (const json::exception& e) {
    throw SceneError(tracker.path(), "cannot parse " + name + ": " + json_reason(e));
  }
}

}  // namespace

Scene parse_scene_text(const std::string& text, const std::string& name) {
  auto doc = std::make_shared<json>(parse_json(text, name));
  if (!doc->is_object()) throw SceneError("$", "a scene must be a JSON object");
  Scene s;
  s.file = name;
  s.doc = doc;
  s.solver = s.root().string("solver", "huygens");  // a registered name (solvers/registry.hpp)
  return s;
}

namespace {

// scenes are a few KB and their meshes a few MB; an input above this is not one
constexpr std::size_t kMaxSceneBytes = std::size_t{64} << 20;

// The bytes of `in`, read in blocks up to kMaxSceneBytes: a larger input, also one with no size
// (/dev/zero, a pipe), is refused after that much instead of being read until memory runs out.
// Returns "" with `why` set on a failure.
std::string read_bounded(std::istream& in, std::string& why) {
  std::string out;
  std::vector<char> block(std::size_t{1} << 16);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    out.append(block.data(), static_cast<std::size_t>(in.gcount()));
    if (out.size() > kMaxSceneBytes) {
      why = "larger than 64 MiB";
      return {};
    }
  }
  if (in.bad()) why = "read error";
  return out;
}

}  // namespace

Scene load_scene(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw SceneError("$", "cannot read scene file " + file + ": a directory");
  // a regular file above the limit is refused before it is read
  if (std::filesystem::is_regular_file(file, ec) && std::filesystem::file_size(file, ec) > kMaxSceneBytes)
    throw SceneError("$", "scene file " + file + " is larger than 64 MiB");
  std::ifstream f(file, std::ios::binary);
  if (!f) throw SceneError("$", "cannot open scene file " + file);
  std::string why;
  const std::string text = read_bounded(f, why);
  if (!why.empty()) throw SceneError("$", "cannot read scene file " + file + ": " + why);
  Scene s = parse_scene_text(text, file);
  s.dir = std::filesystem::absolute(std::filesystem::path(file), ec).parent_path().string();
  return s;
}

std::string read_scene_file(const Scene& scene, const std::string& relative) {
  if (scene.embedded) {
    const std::string_view bytes = scene.embedded(relative);
    if (bytes.empty())
      throw std::runtime_error(relative + ": not a file of the built-in scene " + scene.file +
                               " (its files are compiled into the program)");
    return std::string(bytes);
  }
  const std::filesystem::path path = std::filesystem::path(scene.dir) / relative;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw std::runtime_error(path.string() + ": a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read");
  std::string why;
  std::string bytes = read_bounded(in, why);
  if (!why.empty()) throw std::runtime_error(path.string() + ": " + why);
  return bytes;
}

}  // namespace huygens
