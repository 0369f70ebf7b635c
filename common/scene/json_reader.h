// The scene's one JSON reader: a JSON value together with the file and the JSON path (RFC 6901,
// e.g. /joints/3/points/1) that name it, and the ranges its numbers must lie in.
//
// Every check of a field is one call, and each call knows where to point when it fails: a
// problem is InputError(file, JSON path, message), the message saying what is wrong and what
// was expected ("must be > 0 (got -1)", "expected a number, got a string ("10")"). The readers
// of the scene's parts (common/scene/*.h) are written with it and nothing else, so every part
// reports its mistakes the same way. Unknown keys of an object are checked first by each part
// (check_keys), so that a typo is reported as such rather than as the missing key it hides.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/scene/limits.h"
#include "common/vec2.h"

namespace nmm {

/// An interval of accepted values; each bound open, closed or absent (infinite).
struct ValueRange {
  double lo = -std::numeric_limits<double>::infinity();
  bool lo_closed = false;
  double hi = std::numeric_limits<double>::infinity();
  bool hi_closed = false;

  bool contains(double v) const {
    return (lo_closed ? v >= lo : v > lo) && (hi_closed ? v <= hi : v < hi);
  }
  /// "> 0", ">= 0", "in [0, 0.5)".
  std::string text() const;
};

constexpr ValueRange interval(double lo, bool lo_closed, double hi, bool hi_closed) {
  return ValueRange{lo, lo_closed, hi, hi_closed};
}

// The ranges several parts of the scene share.
inline constexpr ValueRange kAnyFinite{};
inline constexpr ValueRange kPositive{0, false};
inline constexpr ValueRange kStiffness = interval(0, false, kMaxSpringStiffness, true);
inline constexpr ValueRange kStrength = interval(0, false, kMaxStrength, true);
inline constexpr ValueRange kStress = interval(-kMaxStrength, true, kMaxStrength, true);  // Pa, either sign
inline constexpr ValueRange kStressGradient = interval(-1e6, true, 1e6, true);  // Pa/m (rock: about 2.7e4)
inline constexpr ValueRange kCoordinate = interval(-kMaxCoordinate, true, kMaxCoordinate, true);

/// "a, b, c": the names a message lists.
std::string join_names(const std::vector<std::string>& items);

/// One JSON value with the file and path that name it. Holds pointers: the document and the
/// file name outlive the reader.
class JsonReader {
 public:
  JsonReader(const nlohmann::json& value, const std::string& file, std::string path)
      : value_(&value), file_(&file), path_(std::move(path)) {}

  const nlohmann::json& value() const { return *value_; }
  const std::string& path() const { return path_; }

  /// Throws the InputError for this value.
  /// The document itself (JSON pointer "") is named "top level" so the line always says where.
  [[noreturn]] void fail(const std::string& message) const;

  // -- structure --

  const JsonReader& expect_object() const;
  const JsonReader& expect_array() const;
  bool has(const std::string& key) const;

  /// The member `key` of this object; "missing required key" if absent.
  JsonReader operator[](const std::string& key) const;
  /// Element `i` of this array.
  JsonReader operator[](std::size_t i) const;
  std::size_t size() const;

  /// Members of this object as (name, reader) pairs, in the object's (sorted) order.
  std::vector<std::pair<std::string, JsonReader>> members() const;

  /// Rejects any member not in `allowed`, so that a misspelt optional key is not silently
  /// ignored. `context` qualifies the list, e.g. ` for model "constant"`.
  void check_keys(std::initializer_list<const char*> allowed, const std::string& context = "") const;

  // -- scalars (this value) --

  /// A finite number within `range` (nlohmann reads an out-of-range literal such as 1e400 as inf).
  double as_number(const ValueRange& range = kAnyFinite) const;
  /// A whole number >= `min`; 10.0 is accepted, 10.5 is not.
  std::int64_t as_integer(std::int64_t min) const;
  bool as_bool() const;
  std::string as_string() const;
  /// A string that must be one of `known`; returns its index. `what` names it in the message.
  std::size_t as_choice(const std::vector<std::string>& known, const std::string& what) const;

  // -- geometry (this value) --

  /// [a, b]: exactly two finite numbers.
  Vec2 as_pair(const char* expected) const;
  /// [a, b] with each component within ±bound.
  Vec2 as_bounded_pair(const char* expected, double bound) const;
  /// A point [x, y] in m, within kMaxCoordinate of the origin in each axis.
  Vec2 as_point() const;
  /// An array of at least `min_count` points with no point equal to the one before it (the
  /// segment between them would have zero length). `closed`: the last point is also checked
  /// against the first, since a ring closes on its own.
  std::vector<Vec2> as_point_list(std::size_t min_count, bool closed, const char* what) const;
  /// A polygon: at least 3 points, not all on one line.
  Ring as_ring() const;

  // -- shortcuts for members of this object --

  double number(const std::string& key, const ValueRange& range = kAnyFinite) const {
    return (*this)[key].as_number(range);
  }
  double optional_number(const std::string& key, double fallback,
                         const ValueRange& range = kAnyFinite) const {
    return has(key) ? number(key, range) : fallback;
  }
  std::int64_t optional_integer(const std::string& key, std::int64_t fallback,
                                std::int64_t min) const {
    return has(key) ? (*this)[key].as_integer(min) : fallback;
  }
  std::optional<JsonReader> optional(const std::string& key) const {
    if (!has(key)) return std::nullopt;
    return (*this)[key];
  }

 private:
  const nlohmann::json* value_;
  const std::string* file_;
  std::string path_;
};

/// Index of the name at `at` among the definitions (sorted by name: materials, joint sets);
/// fails at `at` if it is not there, listing the known names.
template <typename Def>
int find_by_name(const std::vector<Def>& defs, const JsonReader& at, const std::string& what,
                 const std::string& defined_in) {
  const std::string name = at.as_string();
  for (std::size_t i = 0; i < defs.size(); ++i)
    if (defs[i].name == name) return static_cast<int>(i);
  if (defs.empty())
    at.fail("unknown " + what + " \"" + name + "\" (no " + defined_in + " are defined)");
  std::vector<std::string> names;
  for (const Def& d : defs) names.push_back(d.name);
  at.fail("unknown " + what + " \"" + name + "\" (known: " + join_names(names) + ")");
}

}  // namespace nmm
