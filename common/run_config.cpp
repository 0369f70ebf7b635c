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
#include "common/run_config.h"

#include <charconv>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "common/error.h"
#include "common/json_set.h"
#include "common/whole_file.h"

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


/// Generated joint sets are geometry too: their `generate` (or, in an embedded scene,
/// `generated_from`) block made the joints the mesh was cut with. Changing it here would be
/// accepted and ignored, so it is refused, naming the way that works (docs/joint-networks.md).
void check_generation_unchanged(const json& base, const json& doc, const std::string& source) {
  const json empty = json::object();
  const json& a = base.is_object() && base.contains("joint_sets") ? base["joint_sets"] : empty;
  const json& b = doc.is_object() && doc.contains("joint_sets") ? doc["joint_sets"] : empty;
  if (!b.is_object()) return;  // scene_from_json reports the type error
  for (auto it = b.begin(); it != b.end(); ++it) {
    if (!it.value().is_object()) continue;
    for (const char* key : {"generate", "generated_from"}) {
      const bool in_doc = it.value().contains(key);
      const bool in_base = a.is_object() && a.contains(it.key()) && a[it.key()].is_object() &&
                           a[it.key()].contains(key);
      if (in_doc == in_base && (!in_doc || a[it.key()][key] == it.value()[key])) continue;
      throw InputError(source, "/joint_sets/" + it.key() + "/" + key,
                       "generated joints are geometry fixed by the mesh file: re-preprocess "
                       "with nmm-preprocess --set joint_sets." + it.key() +
                           ".generate.KEY=VALUE for another network");
    }
  }
}

}  // namespace

RunScene make_run_scene(const Mesh& mesh, const std::string& mesh_path,
                        const std::string& config_path, const std::vector<std::string>& sets) {
  return make_run_scene(mesh, mesh_path, config_path.empty() ? "" : read_text_file(config_path),
                        config_path, sets);
}

RunScene make_run_scene(const Mesh& mesh, const std::string& mesh_path,
                        const std::string& config_text, const std::string& config_path,
                        const std::vector<std::string>& sets) {
  const std::string embedded_name = mesh_path + " (embedded scene)";
  const json base = parse_json_text(mesh.scene_text, embedded_name);
  // Rule 1: a fault already in the embedded scene is not the variants' doing.
  SceneDef embedded = scene_from_json(base, embedded_name);
  if (config_path.empty() && sets.empty()) return RunScene{std::move(embedded), base, embedded_name};

  json doc = base;
  if (!config_path.empty()) {
    const json patch = parse_json_text(config_text, config_path);
    if (!patch.is_object())
      throw InputError(
          config_path, "top level",
          "expected an object (a JSON merge patch, RFC 7386, on the scene), got " + describe_json_value(patch));
    doc.merge_patch(patch);
    check_geometry_unchanged(base, doc, config_path);
    check_generation_unchanged(base, doc, config_path);
  }
  for (const std::string& set : sets) {
    json before = doc;
    apply_set(doc, set);
    check_generation_unchanged(before, doc, "--set");
  }
  if (!sets.empty()) check_geometry_unchanged(base, doc, "--set");

  std::string name = "scene in " + mesh_path + " with";
  if (!config_path.empty()) name += " --config " + config_path;
  if (!config_path.empty() && !sets.empty()) name += " and";
  if (!sets.empty()) name += " --set";
  RunScene run;
  try {
    run.scene = scene_from_json(doc, name);
  } catch (const InputError& e) {
    throw_if_misspelt_name(base, doc, e);  // "no joint set 'beding'; joint sets are: ..."
    throw;
  }
  run.effective = std::move(doc);
  run.name = name;
  return run;
}

}  // namespace nmm::solve
