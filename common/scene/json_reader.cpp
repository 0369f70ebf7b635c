// The scene's JSON reader: see json_reader.h.
//
// Numbers: a document built in memory (a merge patch, --set) can hold inf or NaN, and nlohmann
// reads an out-of-range literal such as 1e400 as inf, so every number is checked for being
// finite when it is read, before its range.
#include "common/scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/number_format.h"
#include "common/scene/json_text.h"

namespace nmm {

using nlohmann::json;

std::string ValueRange::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && !has_hi) return (lo_closed ? ">= " : "> ") + format_number(lo);
  if (has_hi && !has_lo) return (hi_closed ? "<= " : "< ") + format_number(hi);
  return std::string("in ") + (lo_closed ? "[" : "(") + format_number(lo) + ", " +
         format_number(hi) + (hi_closed ? "]" : ")");
}

std::string join_names(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

void JsonReader::fail(const std::string& message) const {
  throw InputError(*file_, path_.empty() ? "top level" : path_, message);
}

// ---- structure ---------------------------------------------------------------------------------

const JsonReader& JsonReader::expect_object() const {
  if (!value_->is_object()) fail("expected an object, got " + describe_json_value(*value_));
  return *this;
}

const JsonReader& JsonReader::expect_array() const {
  if (!value_->is_array()) fail("expected an array, got " + describe_json_value(*value_));
  return *this;
}

bool JsonReader::has(const std::string& key) const { return value_->contains(key); }

JsonReader JsonReader::operator[](const std::string& key) const {
  expect_object();
  const auto it = value_->find(key);
  if (it == value_->end()) fail("missing required key \"" + key + "\"");
  return JsonReader(*it, *file_, path_ + "/" + escape_json_pointer(key));
}

JsonReader JsonReader::operator[](std::size_t i) const {
  return JsonReader((*value_)[i], *file_, path_ + "/" + std::to_string(i));
}

std::size_t JsonReader::size() const { return value_->size(); }

std::vector<std::pair<std::string, JsonReader>> JsonReader::members() const {
  expect_object();
  std::vector<std::pair<std::string, JsonReader>> out;
  for (auto it = value_->begin(); it != value_->end(); ++it)
    out.emplace_back(it.key(),
                     JsonReader(it.value(), *file_, path_ + "/" + escape_json_pointer(it.key())));
  return out;
}

void JsonReader::check_keys(std::initializer_list<const char*> allowed,
                            const std::string& context) const {
  expect_object();
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    const bool known =
        std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return it.key() == a; });
    if (known) continue;
    std::vector<std::string> names(allowed.begin(), allowed.end());
    std::sort(names.begin(), names.end());
    JsonReader(it.value(), *file_, path_ + "/" + escape_json_pointer(it.key()))
        .fail("unknown key \"" + it.key() + "\" (allowed" + context + ": " + join_names(names) + ")");
  }
}

// ---- scalars -----------------------------------------------------------------------------------

double JsonReader::as_number(const ValueRange& range) const {
  if (!value_->is_number()) fail("expected a number, got " + describe_json_value(*value_));
  const double v = value_->get<double>();
  if (!std::isfinite(v)) fail("must be a finite number (got " + format_number(v) + ")");
  if (!range.contains(v)) fail("must be " + range.text() + " (got " + format_number(v) + ")");
  return v;
}

std::int64_t JsonReader::as_integer(std::int64_t min) const {
  if (!value_->is_number()) fail("expected an integer, got " + describe_json_value(*value_));
  std::int64_t v = 0;
  if (value_->is_number_integer() && !value_->is_number_unsigned()) {
    v = value_->get<std::int64_t>();
  } else if (value_->is_number_unsigned()) {
    const std::uint64_t u = value_->get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      fail("integer too large (got " + std::to_string(u) + ")");
    v = static_cast<std::int64_t>(u);
  } else {
    const double d = value_->get<double>();
    if (!std::isfinite(d)) fail("must be a finite number (got " + format_number(d) + ")");
    if (d != std::floor(d)) fail("must be a whole number (got " + format_number(d) + ")");
    if (std::fabs(d) >= 9.2e18) fail("integer too large (got " + format_number(d) + ")");
    v = static_cast<std::int64_t>(d);
  }
  if (v < min) fail("must be >= " + std::to_string(min) + " (got " + std::to_string(v) + ")");
  return v;
}

bool JsonReader::as_bool() const {
  if (!value_->is_boolean()) fail("expected true or false, got " + describe_json_value(*value_));
  return value_->get<bool>();
}

std::string JsonReader::as_string() const {
  if (!value_->is_string()) fail("expected a string, got " + describe_json_value(*value_));
  return value_->get<std::string>();
}

std::size_t JsonReader::as_choice(const std::vector<std::string>& known,
                                  const std::string& what) const {
  const std::string s = as_string();
  const auto it = std::find(known.begin(), known.end(), s);
  if (it == known.end()) fail("unknown " + what + " \"" + s + "\" (known: " + join_names(known) + ")");
  return static_cast<std::size_t>(it - known.begin());
}

// ---- geometry ----------------------------------------------------------------------------------

Vec2 JsonReader::as_pair(const char* expected) const {
  if (!value_->is_array() || value_->size() != 2) {
    const std::size_t n = value_->size();
    const std::string got =
        value_->is_array() ? "an array of " + std::to_string(n) + (n == 1 ? " value" : " values")
                           : describe_json_value(*value_);
    fail(std::string("expected ") + expected + ", got " + got);
  }
  return Vec2{(*this)[0].as_number(), (*this)[1].as_number()};
}

Vec2 JsonReader::as_bounded_pair(const char* expected, double bound) const {
  const Vec2 v = as_pair(expected);
  const ValueRange within = interval(-bound, true, bound, true);
  (*this)[0].as_number(within);
  (*this)[1].as_number(within);
  return v;
}

Vec2 JsonReader::as_point() const { return as_bounded_pair("a point [x, y]", kMaxCoordinate); }

std::vector<Vec2> JsonReader::as_point_list(std::size_t min_count, bool closed,
                                            const char* what) const {
  expect_array();
  if (size() < min_count)
    fail(std::string(what) + " needs at least " + std::to_string(min_count) + " points, got " +
         std::to_string(size()));
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < size(); ++i) points.push_back((*this)[i].as_point());
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i] == points[i - 1])
      (*this)[i].fail("zero-length segment: point " + std::to_string(i) + " repeats point " +
                      std::to_string(i - 1));
  if (closed && points.back() == points.front())
    (*this)[points.size() - 1].fail(
        "zero-length segment: the last point repeats the first; leave the closing point out "
        "(polygons close on their own)");
  return points;
}

namespace {

/// True when every point of the ring lies on one line, up to round-off relative to the ring's
/// size: such a "polygon" has no inside. (An exact test is in scene_geometry; this one catches
/// the common case early with a clear message.)
bool all_collinear(const Ring& ring) {
  const Vec2 a = ring.front();
  Vec2 b = a;
  double far2 = 0;
  for (const Vec2& p : ring) {
    const double d2 = (p.x - a.x) * (p.x - a.x) + (p.y - a.y) * (p.y - a.y);
    if (d2 > far2) {
      far2 = d2;
      b = p;
    }
  }
  if (far2 == 0) return true;
  // Distance of c from line ab is |cross| / |ab|; compare it with 1e-12 |ab|.
  for (const Vec2& c : ring) {
    const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (std::fabs(cross) > 1e-12 * far2) return false;
  }
  return true;
}

}  // namespace

Ring JsonReader::as_ring() const {
  Ring ring = as_point_list(3, /*closed=*/true, "a polygon");
  if (all_collinear(ring)) fail("zero-area polygon: all its points lie on one line");
  // A ring with zero signed area whose points are not on one line crosses itself (a symmetric
  // bow tie): check_scene_geometry() reports it as self-intersecting, with the edges.
  return ring;
}

}  // namespace nmm
