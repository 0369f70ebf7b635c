// A run's scene: the embedded scene with the run's variants applied (run_config.h).
//
// Rules, in the order they are applied:
// 1. The scene embedded in the mesh file is parsed and validated as it is, so that a fault in it
//    is blamed on the mesh file and not on a variant.
// 2. `--config FILE`: FILE is JSON (comments allowed) holding one object, applied as a JSON merge
//    patch (RFC 7386): a member set to null removes that key, an object is merged key by key, and
//    any other value (arrays included) replaces the target whole.
// 3. Each `--set PATH=VALUE`, in command-line order. The text is split at the first '=':
//    - PATH is keys separated by '.', e.g. solver.time_step or materials.rock.young. In an array
//      a segment must be a decimal index within the array (loads.0.force); in an object a
//      segment is always a key, digits or not. Objects missing along the path are created, so a
//      whole new joint set can be built one --set at a time. Keys containing '.' cannot be named.
//    - VALUE is parsed as JSON. If it is not valid JSON it is taken as a plain string, so a bare
//      word (`normal.model=constant`) needs no shell quoting; but a VALUE starting with '{', '['
//      or '"' was meant as JSON, and a syntax error in it is reported rather than turned into a
//      string. A number too large for a double is reported too.
//    - VALUE null on an object member removes the key, as in a merge patch (null is never a valid
//      scene value, so removing is the only useful meaning); this is how gravity is switched off.
// 4. Geometry (/bodies, /joints, /mesh) must be exactly as embedded: the covers and elements in
//    the mesh file were cut from it. JSON equality compares numbers by value, so a variant that
//    restates the geometry unchanged (1 for 1.0) is accepted.
// 5. The result is validated as a scene, under a name saying where it came from, so that a value
//    made invalid by a variant (--set solver.time_step=-1) gives the usual one-line error.
//
// Every mistake is an InputError (exit status 2): in the config file (file, line/column or
// "top level"), in a --set ("--set", the PATH=VALUE text, what), or in the resulting scene.
#include "run_config.h"

#include <charconv>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "error.h"

namespace nmm::solve {

namespace {

using nlohmann::json;

/// The geometry members that must survive every variant unchanged.
const char* const kGeometryKeys[] = {"bodies", "joints", "mesh"};

/// Throws if a geometry member of `doc` differs from `base` (present in one and not the other, or
/// a different value). `source` is the file blamed: the config path or "--set".
void check_geometry_unchanged(const json& base, const json& doc, const std::string& source) {
  for (const char* key : kGeometryKeys) {
    const bool in_base = base.is_object() && base.contains(key);
    const bool in_doc = doc.is_object() && doc.contains(key);
    const bool same = in_base == in_doc && (!in_base || base.at(key) == doc.at(key));
    if (!same)
      throw InputError(source, std::string("/") + key,
                       "geometry cannot change in a solver run (bodies, joints, mesh are fixed "
                       "by the mesh file); preprocess the scene again");
  }
}


/// The error for one `--set` whose whole text is `set_text`.
[[noreturn]] void fail_set(const std::string& set_text, const std::string& what) {
  throw InputError("--set", set_text, what);
}

/// The dot-separated keys of a --set path.
std::vector<std::string> split_path(const std::string& path, const std::string& set_text) {
  std::vector<std::string> keys;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    std::string key =
        path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (key.empty())
      fail_set(set_text, "empty key in PATH (two dots in a row, or a dot at the start or end)");
    keys.push_back(std::move(key));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return keys;
}

/// The array index a segment names, or false if it is not a plain decimal number that fits.
bool parse_index(const std::string& key, std::size_t& index) {
  if (key.empty()) return false;
  for (char c : key)
    if (c < '0' || c > '9') return false;
  const auto result = std::from_chars(key.data(), key.data() + key.size(), index);
  return result.ec == std::errc() && result.ptr == key.data() + key.size();
}

/// VALUE of a --set: JSON if it parses, otherwise the text itself as a string (rule 3 above).
json parse_set_value(const std::string& text, const std::string& set_text) {
  try {
    // No comments here: "//" is far more likely part of a string (a URL) than a comment.
    return json::parse(text);
  } catch (const json::out_of_range&) {
    fail_set(set_text, "VALUE " + text + " is a number too large for a double");
  } catch (const json::parse_error& e) {
    const char first = text.empty() ? '\0' : text.front();
    if (first == '{' || first == '[' || first == '"') {
      // Drop nlohmann's "[json.exception.parse_error.101] " prefix: it means nothing to a user.
      std::string why = e.what();
      const std::size_t tag_end = why.find("] ");
      if (why.rfind("[json.exception.", 0) == 0 && tag_end != std::string::npos)
        why.erase(0, tag_end + 2);
      fail_set(set_text, "VALUE is not valid JSON: " + why);
    }
  }
  return json(text);
}

/// "/a/b/0": the JSON pointer of the first `n` keys, to say where on the path a problem is.
std::string pointer_of(const std::vector<std::string>& keys, std::size_t n) {
  json::json_pointer pointer;
  for (std::size_t i = 0; i < n; ++i) pointer /= keys[i];  // to_string() escapes '~' and '/'
  return n == 0 ? std::string("the top level") : pointer.to_string();
}

/// Applies one `--set PATH=VALUE` to `doc`.
void apply_set(json& doc, const std::string& text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) fail_set(text, "expected PATH=VALUE, e.g. solver.time_step=1e-4");
  const std::string path = text.substr(0, eq);
  if (path.empty()) fail_set(text, "empty PATH before '=' (expected PATH=VALUE)");
  const std::vector<std::string> keys = split_path(path, text);
  json value = parse_set_value(text.substr(eq + 1), text);

  json* at = &doc;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string& key = keys[i];
    const bool last = i + 1 == keys.size();
    if (at->is_object()) {
      if (last) {
        if (value.is_null())
          at->erase(key);
        else
          (*at)[key] = std::move(value);
        return;
      }
      // operator[] creates the missing member as null; make it an object to go on into.
      json& next = (*at)[key];
      if (next.is_null()) next = json::object();
      at = &next;
    } else if (at->is_array()) {
      std::size_t index = 0;
      if (!parse_index(key, index))
        fail_set(text,
                 pointer_of(keys, i) + " is an array; \"" + key + "\" is not an index into it");
      if (index >= at->size())
        fail_set(text, "index " + key + " is out of range: " + pointer_of(keys, i) + " has " +
                           std::to_string(at->size()) +
                           (at->size() == 1 ? " element" : " elements"));
      if (last) {
        (*at)[index] = std::move(value);
        return;
      }
      at = &(*at)[index];
    } else {
      fail_set(text, pointer_of(keys, i) + " is " + describe_json_value(*at) + ", which has no member \"" +
                         key + "\"");
    }
  }
}

}  // namespace

RunScene make_run_scene(const Mesh& mesh, const std::string& mesh_path,
                        const std::string& config_path, const std::vector<std::string>& sets) {
  const std::string embedded_name = mesh_path + " (embedded scene)";
  const json base = parse_json_text(mesh.scene_text, embedded_name);
  // Rule 1: a fault already in the embedded scene is not the variants' doing.
  SceneDef embedded = scene_from_json(base, embedded_name);
  if (config_path.empty() && sets.empty()) return RunScene{std::move(embedded), base};

  json doc = base;
  if (!config_path.empty()) {
    const json patch = parse_json_text(read_text_file(config_path), config_path);
    if (!patch.is_object())
      throw InputError(
          config_path, "top level",
          "expected an object (a JSON merge patch, RFC 7386, on the scene), got " + describe_json_value(patch));
    doc.merge_patch(patch);
    check_geometry_unchanged(base, doc, config_path);
  }
  for (const std::string& set : sets) apply_set(doc, set);
  if (!sets.empty()) check_geometry_unchanged(base, doc, "--set");

  std::string name = "scene in " + mesh_path + " with";
  if (!config_path.empty()) name += " --config " + config_path;
  if (!config_path.empty() && !sets.empty()) name += " and";
  if (!sets.empty()) name += " --set";
  RunScene run;
  try {
    run.scene = scene_from_json(doc, name);
  } catch (const InputError& e) {
    // A --set into a joint set or material the scene does not have creates it (a new set may be
    // built one --set at a time); when that new object is incomplete, the likely cause is a
    // misspelt name, so say so and list the names the scene has.
    for (const char* group : {"joint_sets", "materials"}) {
      if (!doc.contains(group) || !doc[group].is_object()) continue;
      for (auto it = doc[group].begin(); it != doc[group].end(); ++it) {
        if (base.contains(group) && base[group].contains(it.key())) continue;
        std::string names;
        if (base.contains(group) && base[group].is_object())
          for (auto b = base[group].begin(); b != base[group].end(); ++b)
            names += (names.empty() ? "" : ", ") + b.key();
        const std::string kind = std::string(group) == "joint_sets" ? "joint set" : "material";
        throw InputError("--set", std::string("/") + group + "/" + it.key(),
                         "no " + kind + " '" + it.key() + "'; " + kind + "s are: " + names +
                             " (a new " + kind + " needs every key: " + e.message() + ")");
      }
    }
    throw;
  }
  run.effective = std::move(doc);
  return run;
}

}  // namespace nmm::solve
