// `--set PATH=VALUE` on a JSON document (json_set.h); moved from common/run_config.cpp.
#include "common/json_set.h"

#include <charconv>
#include <string>
#include <system_error>
#include <vector>

#include "common/error.h"
#include "common/scene.h"

namespace nmm {

namespace {

using nlohmann::json;

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

}  // namespace

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


void throw_if_misspelt_name(const json& base, const json& doc, const InputError& error) {
  for (const char* group : {"joint_sets", "materials"}) {
    if (!doc.contains(group) || !doc[group].is_object()) continue;
    for (auto it = doc[group].begin(); it != doc[group].end(); ++it) {
      if (base.contains(group) && base[group].is_object() && base[group].contains(it.key())) continue;
      std::string names;
      if (base.contains(group) && base[group].is_object())
        for (auto b = base[group].begin(); b != base[group].end(); ++b)
          names += (names.empty() ? "" : ", ") + b.key();
      const std::string kind = std::string(group) == "joint_sets" ? "joint set" : "material";
      throw InputError("--set", std::string("/") + group + "/" + it.key(),
                       "no " + kind + " '" + it.key() + "'; " + kind + "s are: " + names +
                           " (a new " + kind + " needs every key: " + error.message() + ")");
    }
  }
}

}  // namespace nmm
