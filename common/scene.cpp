// Scene files: JSON with comments -> SceneDef, validated once.
//
// Every problem is reported as InputError(file, JSON pointer, message) for the first problem
// found, where the pointer (RFC 6901, e.g. /joints/3/points/1) names the value at fault and the
// message says what is wrong and what was expected. The checks run in a fixed order (unknown
// keys of an object first, so that a typo is reported as such rather than as the missing key it
// hides), so the same bad file always gives the same message.
//
// Numbers: nlohmann refuses a literal that overflows a double (1e400) while parsing, with no
// position; parse_json_text() finds it again with a SAX pass and reports its path, line and
// column. Documents built in memory (merge patches) can still hold inf or NaN, so every number is
// also checked for being finite when it is read.
//
// The reading is done through `Reader`, a JSON value together with its file and path: each check
// of a field is one call, and each call knows where to point when it fails.
#include "common/scene.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>

#include "common/error.h"
#include "common/lattice.h"
#include "common/number_format.h"
#include "common/ring_geometry.h"
#include "common/whole_file.h"

namespace nmm {

using nlohmann::json;

namespace {

// ---- formatting --------------------------------------------------------------------------------

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

}  // namespace

std::string describe_json_value(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::object:
      return "an object";
    case json::value_t::array:
      return "an array";
    case json::value_t::string: {
      const std::string& s = v.get_ref<const std::string&>();
      // Quote short strings: `got a string ("10")` shows at once that the quotes are the mistake.
      return s.size() <= 40 ? "a string (\"" + s + "\")" : "a string";
    }
    case json::value_t::boolean:
      return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number";
    default:
      return "an unsupported value";
  }
}

namespace {

/// RFC 6901 escaping of one path component: '~' -> "~0", '/' -> "~1".
std::string escape_pointer(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// ---- value ranges ------------------------------------------------------------------------------

/// An interval of accepted values; each bound open, closed or absent (infinite).
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  bool lo_closed = false;
  double hi = std::numeric_limits<double>::infinity();
  bool hi_closed = false;

  bool contains(double v) const {
    return (lo_closed ? v >= lo : v > lo) && (hi_closed ? v <= hi : v < hi);
  }
  /// "> 0", ">= 0", "in [0, 0.5)".
  std::string text() const {
    const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
    if (has_lo && !has_hi) return (lo_closed ? ">= " : "> ") + format_number(lo);
    if (has_hi && !has_lo) return (hi_closed ? "<= " : "< ") + format_number(hi);
    return std::string("in ") + (lo_closed ? "[" : "(") + format_number(lo) + ", " +
           format_number(hi) + (hi_closed ? "]" : ")");
  }
};

const Range kAnyFinite{};
const Range kPositive{0, false};
Range interval(double lo, bool lo_closed, double hi, bool hi_closed) {
  return Range{lo, lo_closed, hi, hi_closed};
}
const Range kStiffness = interval(0, false, kMaxSpringStiffness, true);
const Range kStrength = interval(0, false, kMaxStrength, true);
const Range kStress = interval(-kMaxStrength, true, kMaxStrength, true);  // Pa, either sign
const Range kStressGradient = interval(-1e6, true, 1e6, true);  // Pa/m (rock: about 2.7e4)
const Range kCoordinate = interval(-kMaxCoordinate, true, kMaxCoordinate, true);

// ---- Reader: one JSON value with the file and path that name it --------------------------------

class Reader {
 public:
  Reader(const json& value, const std::string& file, std::string path)
      : value_(&value), file_(&file), path_(std::move(path)) {}

  const json& value() const { return *value_; }
  const std::string& path() const { return path_; }

  /// Throws the InputError for this value.
  /// The document itself (JSON pointer "") is named "top level" so the line always says where.
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(*file_, path_.empty() ? "top level" : path_, message);
  }

  // -- structure --

  const Reader& expect_object() const {
    if (!value_->is_object()) fail("expected an object, got " + describe_json_value(*value_));
    return *this;
  }
  const Reader& expect_array() const {
    if (!value_->is_array()) fail("expected an array, got " + describe_json_value(*value_));
    return *this;
  }

  bool has(const std::string& key) const { return value_->contains(key); }

  /// The member `key` of this object; "missing required key" if absent.
  Reader operator[](const std::string& key) const {
    expect_object();
    const auto it = value_->find(key);
    if (it == value_->end()) fail("missing required key \"" + key + "\"");
    return Reader(*it, *file_, path_ + "/" + escape_pointer(key));
  }

  /// Element `i` of this array.
  Reader operator[](std::size_t i) const {
    return Reader((*value_)[i], *file_, path_ + "/" + std::to_string(i));
  }

  std::size_t size() const { return value_->size(); }

  /// Members of this object as (name, reader) pairs, in the object's (sorted) order.
  std::vector<std::pair<std::string, Reader>> members() const {
    expect_object();
    std::vector<std::pair<std::string, Reader>> out;
    for (auto it = value_->begin(); it != value_->end(); ++it)
      out.emplace_back(it.key(),
                       Reader(it.value(), *file_, path_ + "/" + escape_pointer(it.key())));
    return out;
  }

  /// Rejects any member not in `allowed`, so that a misspelt optional key is not silently
  /// ignored. `context` qualifies the list, e.g. ` for model "constant"`.
  void check_keys(std::initializer_list<const char*> allowed,
                  const std::string& context = "") const {
    expect_object();
    for (auto it = value_->begin(); it != value_->end(); ++it) {
      const bool known =
          std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return it.key() == a; });
      if (known) continue;
      std::vector<std::string> names(allowed.begin(), allowed.end());
      std::sort(names.begin(), names.end());
      Reader(it.value(), *file_, path_ + "/" + escape_pointer(it.key()))
          .fail("unknown key \"" + it.key() + "\" (allowed" + context + ": " + join(names) + ")");
    }
  }

  // -- scalars (this value) --

  double as_number(const Range& range = kAnyFinite) const {
    if (!value_->is_number()) fail("expected a number, got " + describe_json_value(*value_));
    const double v = value_->get<double>();
    // nlohmann reads an out-of-range literal such as 1e400 as inf.
    if (!std::isfinite(v)) fail("must be a finite number (got " + format_number(v) + ")");
    if (!range.contains(v)) fail("must be " + range.text() + " (got " + format_number(v) + ")");
    return v;
  }

  /// A whole number >= `min`; 10.0 is accepted, 10.5 is not.
  std::int64_t as_integer(std::int64_t min) const {
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

  bool as_bool() const {
    if (!value_->is_boolean()) fail("expected true or false, got " + describe_json_value(*value_));
    return value_->get<bool>();
  }

  std::string as_string() const {
    if (!value_->is_string()) fail("expected a string, got " + describe_json_value(*value_));
    return value_->get<std::string>();
  }

  /// A string that must be one of `known`; returns its index. `what` names it in the message.
  std::size_t as_choice(const std::vector<std::string>& known, const std::string& what) const {
    const std::string s = as_string();
    const auto it = std::find(known.begin(), known.end(), s);
    if (it == known.end()) fail("unknown " + what + " \"" + s + "\" (known: " + join(known) + ")");
    return static_cast<std::size_t>(it - known.begin());
  }

  // -- geometry (this value) --

  /// [a, b]: exactly two finite numbers.
  Vec2 as_pair(const char* expected) const {
    if (!value_->is_array() || value_->size() != 2) {
      const std::size_t n = value_->size();
      const std::string got =
          value_->is_array() ? "an array of " + std::to_string(n) + (n == 1 ? " value" : " values")
                             : describe_json_value(*value_);
      fail(std::string("expected ") + expected + ", got " + got);
    }
    return Vec2{(*this)[0].as_number(), (*this)[1].as_number()};
  }

  /// [a, b] with each component within ±bound.
  Vec2 as_bounded_pair(const char* expected, double bound) const {
    const Vec2 v = as_pair(expected);
    const Range within = interval(-bound, true, bound, true);
    (*this)[0].as_number(within);
    (*this)[1].as_number(within);
    return v;
  }

  /// A point [x, y] in m, within kMaxCoordinate of the origin in each axis.
  Vec2 as_point() const {
    return as_bounded_pair("a point [x, y]", kMaxCoordinate);
  }

  /// An array of at least `min_count` points with no point equal to the one before it (the
  /// segment between them would have zero length). `closed`: the last point is also checked
  /// against the first, since a ring closes on its own.
  std::vector<Vec2> as_point_list(std::size_t min_count, bool closed, const char* what) const {
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

  Ring as_ring() const;

  // -- shortcuts for members of this object --

  double number(const std::string& key, const Range& range = kAnyFinite) const {
    return (*this)[key].as_number(range);
  }
  double optional_number(const std::string& key, double fallback,
                         const Range& range = kAnyFinite) const {
    return has(key) ? number(key, range) : fallback;
  }
  std::int64_t optional_integer(const std::string& key, std::int64_t fallback,
                                std::int64_t min) const {
    return has(key) ? (*this)[key].as_integer(min) : fallback;
  }
  std::optional<Reader> optional(const std::string& key) const {
    if (!has(key)) return std::nullopt;
    return (*this)[key];
  }

 private:
  const json* value_;
  const std::string* file_;
  std::string path_;
};

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

Ring Reader::as_ring() const {
  Ring ring = as_point_list(3, /*closed=*/true, "a polygon");
  if (all_collinear(ring)) fail("zero-area polygon: all its points lie on one line");
  // A ring with zero signed area whose points are not on one line crosses itself (a symmetric
  // bow tie): check_scene_geometry() reports it as self-intersecting, with the edges.
  return ring;
}

// ---- the scene's parts -------------------------------------------------------------------------

/// Index of `name` among the definitions (sorted by name); fails at `at` if it is not there.
template <typename Def>
int find_by_name(const std::vector<Def>& defs, const Reader& at, const std::string& what,
                 const std::string& defined_in) {
  const std::string name = at.as_string();
  for (std::size_t i = 0; i < defs.size(); ++i)
    if (defs[i].name == name) return static_cast<int>(i);
  if (defs.empty())
    at.fail("unknown " + what + " \"" + name + "\" (no " + defined_in + " are defined)");
  std::vector<std::string> names;
  for (const Def& d : defs) names.push_back(d.name);
  at.fail("unknown " + what + " \"" + name + "\" (known: " + join(names) + ")");
}

MaterialDef read_material(const std::string& name, const Reader& r) {
  r.check_keys({"density", "young", "poisson", "strength"});
  MaterialDef m;
  m.name = name;
  m.density = r.number("density", interval(0, false, kMaxDensity, true));
  m.young = r.number("young", interval(0, false, kMaxModulus, true));
  // 0.5 is incompressible: the plane-strain elasticity matrix blows up.
  m.poisson = r.number("poisson", interval(0, true, 0.5, false));
  if (const auto st = r.optional("strength")) {
    st->check_keys({"tensile", "cohesion", "friction_deg", "fracture_energy"});
    StrengthDef& s = m.strength;
    s.present = true;
    s.tensile = st->number("tensile", kStrength);
    s.cohesion = st->number("cohesion", interval(0, true, kMaxStrength, true));
    s.friction_deg = st->number("friction_deg", interval(0, true, 90, false));  // tan 90° is infinite
    // J/m²: rock's is 10–500; the bound only refuses typing accidents. Cohesive softening of new
    // cracks is not built yet (docs/fracture.md "Not yet"): a scene asking for it is refused
    // rather than run without it.
    s.fracture_energy = st->optional_number("fracture_energy", 0, interval(0, true, 1e9, true));
    if (s.fracture_energy > 0)
      (*st)["fracture_energy"].fail("cohesive softening of new cracks is not built yet: a crack's faces start "
                                    "closed without tensile strength (docs/fracture.md); leave fracture_energy out");
  }
  return m;
}

NormalLawDef read_normal_law(const Reader& r) {
  r.expect_object();
  NormalLawDef law;
  // constant: kn in Pa/m (per unit joint length); penalty: DDA's kn in N/m per contact point.
  const std::size_t model = r["model"].as_choice({"constant", "bandis_barton", "penalty"}, "normal model");
  // A joint set may hold the parameters of both models, so that a run can switch models with
  // --set joint_sets.NAME.normal.model=... on the same mesh; the model picks which are needed.
  r.check_keys({"model", "kn", "kni", "vm", "jrc", "jcs", "ucs", "hysteresis", "reload"}, "");
  // Used by the bandis_barton closure only (kept, like kni and vm, when a run switches models).
  if (r.has("hysteresis")) law.hysteresis = r["hysteresis"].as_bool();
  if (const auto reload = r.optional("reload")) {
    // Bandis' later load cycles: a hyperbola of their own (joint_law.cpp), which needs the
    // largest closure the hysteresis remembers.
    reload->expect_object();
    reload->check_keys({"kni", "vm"}, "");
    law.reload_kni = reload->number("kni", kStiffness);
    law.reload_vm = reload->number("vm", interval(0, false, kMaxClosure, true));
    if (r.has("hysteresis") && !law.hysteresis)
      r["hysteresis"].fail("the reloading cycle (reload) needs the hysteresis: true or leave it out");
    law.hysteresis = true;
  }
  if (r.has("kn")) law.kn = r.number("kn", kStiffness);
  if (model == 0 || model == 2) {
    law.model = model == 0 ? NormalModel::constant : NormalModel::penalty;
    law.kn = r.number("kn", kStiffness);
  } else if (r.has("jrc") || r.has("jcs") || r.has("ucs")) {
    // Barton–Bandis empirical relations (Barton, Bandis & Bakhtar 1985; docs/physics.md §4), with
    // JCS and σc in MPa and lengths in mm inside the formulas:
    //   a_j = (JRC/5)(0.2·σc/JCS − 0.1)           initial aperture, mm
    //   Kni = −7.15 + 1.75·JRC + 0.02·JCS/a_j      MPa/mm = GPa/m
    //   Vm  = −0.2960 − 0.0056·JRC + 2.2410·(JCS/a_j)^−0.2450   mm (first load cycle)
    if (r.has("kni") || r.has("vm"))
      r.fail("give either kni and vm, or jrc, jcs and ucs, not both");
    law.model = NormalModel::bandis_barton;
    law.jrc = r.number("jrc", interval(0, false, 20, true));
    law.jcs = r.number("jcs", kStrength);
    law.ucs = r.number("ucs", kStrength);
    const double jcs_mpa = law.jcs / 1e6, ucs_mpa = law.ucs / 1e6;
    const double aj = (law.jrc / 5.0) * (0.2 * ucs_mpa / jcs_mpa - 0.1);  // mm
    if (!(aj > 0))
      r.fail("JRC, JCS and UCS give a non-positive initial aperture (needs UCS > 0.5·JCS)");
    const double kni_gpa = -7.15 + 1.75 * law.jrc + 0.02 * jcs_mpa / aj;
    const double vm_mm = -0.2960 - 0.0056 * law.jrc + 2.2410 * std::pow(jcs_mpa / aj, -0.2450);
    if (!(kni_gpa > 0) || !(vm_mm > 0))
      r.fail("JRC, JCS and UCS lie outside the range of the Barton–Bandis relations (Kni = " +
             std::to_string(kni_gpa) + " GPa/m, Vm = " + std::to_string(vm_mm) + " mm)");
    law.aperture = aj * 1e-3;
    law.kni = kni_gpa * 1e9;
    law.vm = vm_mm * 1e-3;
  } else {
    law.model = NormalModel::bandis_barton;
    law.kni = r.number("kni", kStiffness);
    law.vm = r.number("vm", interval(0, false, kMaxClosure, true));
  }
  return law;
}

ShearLawDef read_shear_law(const Reader& r) {
  r.expect_object();
  ShearLawDef law;
  // constant: ks in Pa/m (per unit joint length); penalty: DDA's ks in N/m per contact point.
  const std::size_t model =
      r["model"].as_choice({"constant", "hyperbolic", "penalty", "barton_bandis"}, "shear model");
  // Every model's parameters may be given side by side (runs switch models with --set).
  r.check_keys({"model", "ks", "ksi", "rf", "jrc", "jcs", "length", "lab_length", "strength_factor"}, "");
  if (r.has("ks")) law.ks = r.number("ks", kStiffness);
  if (model == 0 || model == 2) {
    law.model = model == 0 ? ShearModel::constant : ShearModel::penalty;
    law.ks = r.number("ks", kStiffness);
  } else if (model == 3) {
    // Barton–Bandis shear (solver/contact/barton_bandis.h): the elastic spring ks (Pa/m), JRC and JCS,
    // the joint length L_n for the peak displacement, and — if JRC and JCS were measured on a
    // sample of length L_0 — Bandis' scale corrections (Barton & Bandis 1982):
    //   JRC_n = JRC_0·(L_n/L_0)^(−0.02·JRC_0),   JCS_n = JCS_0·(L_n/L_0)^(−0.03·JRC_0)
    law.model = ShearModel::barton_bandis;
    law.ks = r.number("ks", kStiffness);
    law.jrc = r.number("jrc", interval(0, true, 20, true));
    law.jcs = r.number("jcs", kStrength);
    law.length = r.number("length", interval(0, false, kMaxCoordinate, true));
    law.lab_length = r.optional_number("lab_length", 0, interval(0, false, kMaxCoordinate, true));
    // Strength reduction (nmm-fos): τ = σn·tan(φr + JRC_mob·log10(JCS/σn)) / F at every σn.
    law.strength_factor = r.optional_number("strength_factor", 1, interval(1e-3, true, 1e3, true));
    if (law.lab_length > 0) {
      const double ratio = law.length / law.lab_length, jrc0 = law.jrc;
      law.jrc = jrc0 * std::pow(ratio, -0.02 * jrc0);
      law.jcs = law.jcs * std::pow(ratio, -0.03 * jrc0);
    }
  } else {
    law.model = ShearModel::hyperbolic;
    law.ksi = r.number("ksi", kStiffness);
    law.rf = r.number("rf", interval(0, false, 1, true));
  }
  return law;
}

/// A length distribution (trace length or spacing), m; a bare number is a constant.
LengthDef read_length_distribution(const Reader& r) {
  const Range length = interval(0, false, kMaxCoordinate, true);
  LengthDef d;
  if (r.value().is_number()) {
    d.mean = r.as_number(length);
    return d;
  }
  r.check_keys({"distribution", "mean", "std_dev", "exponent", "min", "max"});
  const std::size_t kind = r["distribution"].as_choice(
      {"constant", "exponential", "lognormal", "power_law"}, "length distribution");
  d.kind = static_cast<LengthDistribution>(kind);
  if (d.kind == LengthDistribution::power_law) {
    // p(L) ∝ L^-a on [min, max]; a = 1 would need a logarithmic inverse CDF, a > 1 is the field range.
    d.exponent = r.number("exponent", interval(1, false, 10, true));
    d.min = r.number("min", length);
    d.max = r.number("max", length);
    if (!(d.max > d.min)) r["max"].fail("must be > min (" + format_number(d.min) + ")");
    return d;
  }
  d.mean = r.number("mean", length);
  if (d.kind == LengthDistribution::lognormal) d.std_dev = r.number("std_dev", length);
  return d;
}

/// Mean of a length distribution, m (the power law's in closed form).
double mean_of(const LengthDef& d) {
  if (d.kind != LengthDistribution::power_law) return d.mean;
  const double a = d.exponent;
  if (std::fabs(a - 2) < 1e-12) return std::log(d.max / d.min) / (1 / d.min - 1 / d.max);
  return (a - 1) / (2 - a) * (std::pow(d.max, 2 - a) - std::pow(d.min, 2 - a)) /
         (std::pow(d.min, 1 - a) - std::pow(d.max, 1 - a));
}

/// joint_sets.NAME.generate (common/joint_generation.h, docs/joint-networks.md).
JointGenerationDef read_joint_generation(const Reader& r) {
  r.check_keys({"region", "orientation", "p21", "spacing", "length", "position", "termination",
                "seed"});
  JointGenerationDef g;
  if (r.has("region")) g.region = r["region"].as_ring();
  const Reader o = r["orientation"];
  o.check_keys({"mean_deg", "kappa", "spread_deg"});
  g.mean_angle_deg = o.number("mean_deg", interval(-360, true, 360, true));
  if (o.has("kappa") && o.has("spread_deg")) o.fail("give either kappa or spread_deg, not both");
  if (o.has("kappa")) {
    g.dispersion = DispersionKind::von_mises;
    g.kappa = o.number("kappa", interval(0, false, 1e6, true));
  } else if (o.has("spread_deg")) {
    g.dispersion = DispersionKind::uniform;
    g.spread_deg = o.number("spread_deg", interval(0, false, 90, true));
  }
  if (r.has("position"))
    g.position = r["position"].as_choice({"poisson", "spacing"}, "position model") == 0
                     ? PositionModel::poisson
                     : PositionModel::spacing;
  g.length = read_length_distribution(r["length"]);
  const Range p21 = interval(0, false, 1e3, true);
  if (g.position == PositionModel::poisson) {
    if (r.has("p21") == r.has("spacing")) r.fail("give either p21 or spacing (one of them)");
    if (r.has("p21")) g.p21 = r.number("p21", p21);
    if (r.has("spacing")) {
      g.spacing_distribution = read_length_distribution(r["spacing"]);
      g.mean_spacing = mean_of(g.spacing_distribution);
      g.p21 = 1 / g.mean_spacing;
    }
  } else {
    if (g.dispersion != DispersionKind::none)
      o.fail("the spacing position model makes parallel joints: no kappa or spread_deg");
    g.spacing_distribution = read_length_distribution(r["spacing"]);
    g.mean_spacing = mean_of(g.spacing_distribution);
    if (r.has("p21")) {
      g.p21 = r.number("p21", p21);
      // Traces cover the fraction P21·s̄ of each line; more than all of it is impossible.
      if (g.p21 * g.mean_spacing > 1)
        r["p21"].fail("must be <= 1 / mean spacing (" + format_number(1 / g.mean_spacing) +
                      ") for the spacing model");
    }
  }
  g.termination = r.optional_number("termination", 0, interval(0, true, 1, true));
  g.seed = static_cast<std::uint64_t>(r.optional_integer("seed", 1, 0));
  return g;
}

JointSetDef read_joint_set(const std::string& name, const Reader& r) {
  r.check_keys({"friction_deg", "cohesion", "tensile_strength", "residual_cohesion", "normal", "shear",
                "generate", "generated_from"});
  JointSetDef s;
  s.name = name;
  s.friction_deg = r.number("friction_deg", interval(0, true, 90, false));  // tan 90° is infinite
  s.cohesion = r.optional_number("cohesion", 0, interval(0, true, kMaxStrength, true));
  s.tensile_strength = r.optional_number("tensile_strength", 0, interval(0, true, kMaxStrength, true));
  // Residual cohesion (docs/contact.md, "Cohesion after failure"): 0 = brittle (the default),
  // = cohesion: perfectly plastic Mohr–Coulomb, what limit-equilibrium closed forms assume.
  s.residual_cohesion = r.optional_number("residual_cohesion", 0, interval(0, true, s.cohesion, true));
  s.normal = read_normal_law(r["normal"]);
  s.shear = read_shear_law(r["shear"]);
  if (r.has("generate")) {
    s.generated = true;
    s.generate = read_joint_generation(r["generate"]);
  }
  // Written by nmm-preprocess in the embedded (explicit) scene: the generate block the listed
  // joints came from (docs/joint-networks.md). Read with the same rules; never generates.
  if (r.has("generated_from")) {
    if (s.generated)
      r["generated_from"].fail("a joint set has either generate (joints to generate) or "
                               "generated_from (joints already generated), not both");
    s.expanded = true;
    s.generate = read_joint_generation(r["generated_from"]);
  }
  return s;
}

BodyDef read_body(const Reader& r, const std::vector<MaterialDef>& materials) {
  r.check_keys({"material", "outer", "holes"});
  BodyDef b;
  b.material = find_by_name(materials, r["material"], "material", "materials");
  b.outer = r["outer"].as_ring();
  if (const auto holes = r.optional("holes")) {
    holes->expect_array();
    for (std::size_t i = 0; i < holes->size(); ++i) b.holes.push_back((*holes)[i].as_ring());
  }
  return b;
}

JointDef read_joint(const Reader& r, const std::vector<JointSetDef>& sets) {
  r.check_keys({"set", "points"});
  JointDef j;
  j.set = find_by_name(sets, r["set"], "joint set", "joint_sets");
  j.points = r["points"].as_point_list(2, /*closed=*/false, "a joint");
  return j;
}

/// An array of points (fixed_points, measure_points).
std::vector<Vec2> read_points(const Reader& r) {
  r.expect_array();
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < r.size(); ++i) points.push_back(r[i].as_point());
  return points;
}

SolverDef read_solver(const Reader& r) {
  r.check_keys({"time_step", "steps", "dynamic", "dynamic_factor", "newmark_beta",
                "max_displacement_ratio", "output_every", "fixed_point_stiffness",
                "sliver_cover_weight", "checkpoint_every", "support_stiffness", "static_mode",
                "excavation_steps", "cover_order", "history_every", "stop_at_ratio",
                "contact_tolerance"});
  SolverDef s;  // defaults from scene.h
  s.time_step = r.optional_number("time_step", s.time_step, interval(kMinTimeStep, true, kMaxTimeStep, true));
  s.steps = r.optional_integer("steps", s.steps, 0);
  if (r.has("dynamic")) s.dynamic = r["dynamic"].as_bool();
  if (r.has("static_mode"))
    s.static_mode = r["static_mode"].as_choice({"dda", "equilibrium"}, "static_mode") == 0
                        ? StaticMode::dda
                        : StaticMode::equilibrium;
  s.dynamic_factor = r.optional_number("dynamic_factor", s.dynamic_factor, interval(0, true, 1, true));
  s.newmark_beta = r.optional_number("newmark_beta", s.newmark_beta, interval(0.5, true, 1, true));
  s.fixed_point_stiffness =
      r.optional_number("fixed_point_stiffness", s.fixed_point_stiffness, interval(0, true, kMaxSpringStiffness, true));
  s.max_displacement_ratio = r.optional_number("max_displacement_ratio", s.max_displacement_ratio,
                                               interval(0, false, 1, false));
  s.output_every = r.optional_integer("output_every", s.output_every, 1);
  s.history_every = r.optional_integer("history_every", s.history_every, 1);
  s.stop_at_ratio = r.optional_number("stop_at_ratio", s.stop_at_ratio, interval(0, false, 1, false));
  // Below 1/3 every element keeps at least one cover above it (its three weights sum to 1).
  s.sliver_cover_weight = r.optional_number("sliver_cover_weight", s.sliver_cover_weight,
                                            interval(0, true, 0.3, false));
  s.checkpoint_every = r.optional_integer("checkpoint_every", s.checkpoint_every, 0);
  s.support_stiffness = r.optional_number("support_stiffness", s.support_stiffness,
                                          interval(0, true, kMaxSpringStiffness, true));
  s.excavation_steps = r.optional_integer("excavation_steps", s.excavation_steps, 1);
  s.contact_tolerance =
      r.optional_number("contact_tolerance", s.contact_tolerance, interval(1e-12, true, 1e-2, true));
  s.cover_order = static_cast<int>(r.optional_integer("cover_order", s.cover_order, 0));
  if (s.cover_order > 2) r["cover_order"].fail("cover_order must be 0, 1 or 2");
  return s;
}

// ---- rock-engineering set-ups (docs/interface.md "Rock-engineering set-ups and restart") ------

/// A time table: inline rows [[t, value], ...] or the name of a CSV file with rows "t,value"
/// (blank lines, lines starting with '#' and one header line of words are skipped). Times must
/// increase strictly.
TimeTable read_time_table(const Reader& r) {
  TimeTable t;
  if (r.value().is_string()) {
    const std::string path = r.as_string();
    std::string text;
    try {
      text = read_text_file(path);
    } catch (const InputError& e) {
      r.fail("cannot read the time table file \"" + path + "\": " + e.message());
    }
    std::size_t line_no = 0, start = 0;
    while (start <= text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(start, end - start);
      start = end + 1;
      ++line_no;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const std::size_t first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line[first] == '#') continue;
      double tv[2];
      const char* p = line.c_str();
      bool ok = true;
      for (int k = 0; k < 2 && ok; ++k) {
        while (*p == ' ' || *p == '\t' || (k == 1 && *p == ',') || (k == 1 && *p == ';')) ++p;
        char* q = nullptr;
        tv[k] = std::strtod(p, &q);
        ok = q != p && std::isfinite(tv[k]);
        p = q;
      }
      if (!ok) {
        if (t.time.empty() && line_no == 1) continue;  // a header line
        r.fail("time table file \"" + path + "\" line " + std::to_string(line_no) +
               ": expected two numbers \"t,value\"");
      }
      if (!t.time.empty() && !(tv[0] > t.time.back()))
        r.fail("time table file \"" + path + "\" line " + std::to_string(line_no) +
               ": times must increase strictly");
      t.time.push_back(tv[0]);
      t.value.push_back(tv[1]);
    }
    if (t.time.empty()) r.fail("time table file \"" + path + "\" holds no rows");
    return t;
  }
  r.expect_array();
  if (r.size() == 0) r.fail("a time table needs at least one row [t, value]");
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 row = r[i].as_pair("a row [t, value]");
    if (!t.time.empty() && !(row.x > t.time.back())) r[i][0].fail("times must increase strictly");
    t.time.push_back(row.x);
    t.value.push_back(row.y);
  }
  return t;
}

std::vector<SupportDef> read_supports(const Reader& r) {
  r.expect_array();
  std::vector<SupportDef> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Reader s = r[i];
    s.check_keys({"points", "fix", "velocity", "table"});
    SupportDef d;
    d.points = s["points"].as_point_list(2, false, "a support");
    const std::size_t fix = s["fix"].as_choice({"x", "y", "xy"}, "fix direction");
    d.fix_x = fix != 1;
    d.fix_y = fix != 0;
    if (const auto v = s.optional("velocity")) {
      d.velocity = v->as_pair("a velocity [vx, vy] in m/s");
      if ((!d.fix_x && d.velocity.x != 0) || (!d.fix_y && d.velocity.y != 0))
        v->fail("a support moves only in the directions it holds (fix)");
    }
    if (const auto t = s.optional("table")) {
      if (d.velocity.x == 0 && d.velocity.y == 0) t->fail("a velocity table needs the support's velocity");
      d.table = read_time_table(*t);
    }
    out.push_back(std::move(d));
  }
  return out;
}

std::vector<TractionDef> read_tractions(const Reader& r) {
  r.expect_array();
  std::vector<TractionDef> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Reader s = r[i];
    s.check_keys({"points", "normal", "shear", "from_insitu", "table"});
    TractionDef d;
    d.points = s["points"].as_point_list(2, false, "a traction");
    if (s.has("from_insitu")) d.from_insitu = s["from_insitu"].as_bool();
    if (d.from_insitu && (s.has("normal") || s.has("shear")))
      s["from_insitu"].fail("give either normal/shear or from_insitu, not both");
    if (!d.from_insitu && !s.has("normal") && !s.has("shear"))
      s.fail("a traction needs \"normal\" and/or \"shear\" (Pa), or \"from_insitu\": true");
    d.normal = s.optional_number("normal", 0, kStress);
    d.shear = s.optional_number("shear", 0, kStress);
    if (const auto t = s.optional("table")) d.table = read_time_table(*t);
    out.push_back(std::move(d));
  }
  return out;
}

/// bolts: [{points: [a, b], type: anchored | grouted, ...}] (BoltDef; docs/reinforcement.md).
/// The keys of one type are refused on the other, so that a grouted cable given a "stiffness"
/// (an anchored bolt's) is not silently a cable without it.
std::vector<BoltDef> read_bolts(const Reader& r) {
  r.expect_array();
  const Range force = interval(0, false, kMaxForce, true);  // N per bolt
  std::vector<BoltDef> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Reader b = r[i];
    b.expect_object();
    BoltDef d;
    d.type = b["type"].as_choice({"anchored", "grouted"}, "bolt type") == 0 ? BoltType::anchored
                                                                            : BoltType::grouted;
    const bool anchored = d.type == BoltType::anchored;
    if (anchored)
      b.check_keys({"points", "type", "stiffness", "pretension", "strength", "spacing"}, " for type \"anchored\"");
    else
      b.check_keys({"points", "type", "ea", "yield", "bond_stiffness", "bond_strength", "spacing", "segments"},
                   " for type \"grouted\"");
    const Reader pts = b["points"];
    const std::vector<Vec2> p = pts.as_point_list(2, false, "a bolt");
    if (p.size() != 2) pts.fail("a bolt is straight: exactly 2 points [[x0, y0], [x1, y1]], got " + std::to_string(p.size()));
    d.a = p[0];
    d.b = p[1];
    d.spacing = b.optional_number("spacing", 1.0, interval(0, false, 1e3, true));
    constexpr double none = std::numeric_limits<double>::infinity();
    if (anchored) {
      d.stiffness = b.number("stiffness", kStiffness);
      d.pretension = b.optional_number("pretension", 0, interval(0, true, kMaxForce, true));
      d.strength = b.optional_number("strength", none, force);
      if (d.pretension >= d.strength)
        b["pretension"].fail("must be below the bolt's strength (" + format_number(d.strength) + " N), or it breaks as it is installed");
    } else {
      d.ea = b.number("ea", force);
      d.yield = b.optional_number("yield", none, force);
      d.bond_stiffness = b.number("bond_stiffness", kStiffness);
      d.bond_strength = b.optional_number("bond_strength", none, force);
      d.segments = static_cast<int>(b.optional_integer("segments", 0, 1));
      if (d.segments > 1000) b["segments"].fail("must be <= 1000 (got " + std::to_string(d.segments) + ")");
    }
    out.push_back(d);
  }
  return out;
}

/// absorbing: [{points: polyline, input_velocity: {x: TABLE, y: TABLE}}] (AbsorbingDef).
std::vector<AbsorbingDef> read_absorbing(const Reader& r) {
  r.expect_array();
  std::vector<AbsorbingDef> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Reader a = r[i];
    a.check_keys({"points", "input_velocity"});
    AbsorbingDef d;
    d.points = a["points"].as_point_list(2, false, "an absorbing boundary");
    if (const auto v = a.optional("input_velocity")) {
      v->check_keys({"x", "y"});
      if (!v->has("x") && !v->has("y")) v->fail("an input velocity needs \"x\" and/or \"y\" (time tables, m/s)");
      if (const auto t = v->optional("x")) d.input_x = read_time_table(*t);
      if (const auto t = v->optional("y")) d.input_y = read_time_table(*t);
    }
    out.push_back(std::move(d));
  }
  return out;
}

/// water: {density, phreatic: polyline, joints: [{joint, pressure | fill_depth}]} (WaterDef).
/// Hydrostatic pressure needs gravity; the phreatic surface must be a single-valued function
/// of the position across gravity (its points in strictly monotone order across it).
WaterDef read_water(const Reader& r, const SceneDef& scene) {
  r.check_keys({"density", "phreatic", "joints"});
  WaterDef w;
  w.present = true;
  w.density = r.optional_number("density", 1000, interval(0, false, kMaxDensity, true));
  const double g = scene.has_gravity ? std::hypot(scene.gravity.x, scene.gravity.y) : 0.0;
  if (const auto ph = r.optional("phreatic")) {
    if (!(g > 0)) ph->fail("a phreatic surface needs gravity (the pressure is ρw·g·depth)");
    w.phreatic = ph->as_point_list(2, /*closed=*/false, "a phreatic surface");
    // Position across gravity: s = x·(−gy) + y·gx over |g| (gravity pointing down: s = x).
    auto across = [&](const Vec2& p) { return (-p.x * scene.gravity.y + p.y * scene.gravity.x) / g; };
    const double dir = across(w.phreatic[1]) - across(w.phreatic[0]);
    for (std::size_t i = 1; i < w.phreatic.size(); ++i) {
      const double step = across(w.phreatic[i]) - across(w.phreatic[i - 1]);
      if (!(step * dir > 0))
        (*ph)[i].fail("the phreatic surface turns back across gravity here (it must give one water "
                      "level at each position)");
    }
  }
  if (const auto js = r.optional("joints")) {
    js->expect_array();
    std::vector<char> seen(scene.joints.size(), 0);
    for (std::size_t i = 0; i < js->size(); ++i) {
      const Reader e = (*js)[i];
      e.check_keys({"joint", "pressure", "fill_depth"});
      JointWaterDef d;
      const std::int64_t j = e["joint"].as_integer(0);
      if (j >= static_cast<std::int64_t>(scene.joints.size()))
        e["joint"].fail("no joint " + std::to_string(j) + " (the scene has " +
                        std::to_string(scene.joints.size()) + ")");
      if (seen[static_cast<std::size_t>(j)]++)
        e["joint"].fail("joint " + std::to_string(j) + " is given water twice");
      d.joint = static_cast<int>(j);
      if (e.has("pressure") == e.has("fill_depth"))
        e.fail("give either \"pressure\" (Pa, or a table [[distance along the joint, Pa], ...]) or "
               "\"fill_depth\" (m), not both");
      const Range pressure = interval(0, true, kMaxStrength, true);
      if (e.has("fill_depth")) {
        if (!(g > 0)) e["fill_depth"].fail("fill_depth needs gravity (the pressure is ρw·g·depth)");
        d.fill_depth = e.number("fill_depth", interval(0, true, kMaxCoordinate, true));
      } else if (e["pressure"].value().is_number()) {
        d.at.push_back(0);
        d.pressure.push_back(e.number("pressure", pressure));
      } else {
        const Reader t = e["pressure"];
        t.expect_array();
        if (t.size() == 0) t.fail("a pressure table needs at least one row [distance, Pa]");
        for (std::size_t k = 0; k < t.size(); ++k) {
          const Vec2 row = t[k].as_pair("a row [distance along the joint (m), pressure (Pa)]");
          t[k][0].as_number(interval(0, true, kMaxCoordinate, true));
          t[k][1].as_number(pressure);
          if (!d.at.empty() && !(row.x > d.at.back())) t[k][0].fail("distances must increase strictly");
          d.at.push_back(row.x);
          d.pressure.push_back(row.y);
        }
      }
      w.joints.push_back(std::move(d));
    }
  }
  return w;
}

/// insitu_stress: {sxx, syy, sxy, y_ref, gradient: [gxx, gyy, gxy]} or the overburden shortcut
/// {k0, y_ref, density (default: the first material's), syy (at y_ref, default 0), g (default
/// |gravity|, else 9.81)}: σyy = syy − ρ·g·(y_ref − y), σxx = k0·σyy, σxy = 0.
InsituStressDef read_insitu(const Reader& r, const SceneDef& scene) {
  InsituStressDef d;
  d.present = true;
  if (r.has("k0")) {
    r.check_keys({"k0", "y_ref", "density", "syy", "g"}, " with \"k0\"");
    const double k0 = r.number("k0", interval(0, true, 10, true));  // K0 of rock: 0.3 to 3
    d.y_ref = r["y_ref"].as_number(kCoordinate);
    const double rho = r.optional_number("density", scene.materials.front().density,
                                         interval(0, false, kMaxDensity, true));
    const double g_default =
        scene.has_gravity ? std::hypot(scene.gravity.x, scene.gravity.y) : 9.81;
    const double g = r.optional_number("g", g_default, interval(0, true, kMaxAcceleration, true));
    d.syy = r.optional_number("syy", 0, kStress);
    d.sxx = k0 * d.syy;
    d.gyy = -rho * g;
    d.gxx = k0 * d.gyy;
    return d;
  }
  r.check_keys({"sxx", "syy", "sxy", "y_ref", "gradient"});
  d.sxx = r.optional_number("sxx", 0, kStress);
  d.syy = r.optional_number("syy", 0, kStress);
  d.sxy = r.optional_number("sxy", 0, kStress);
  d.y_ref = r.optional_number("y_ref", 0, kCoordinate);
  if (const auto g = r.optional("gradient")) {
    g->expect_array();
    if (g->size() != 3) g->fail("expected [gxx, gyy, gxy] (Pa per m of depth)");
    d.gxx = (*g)[0].as_number(kStressGradient);
    d.gyy = (*g)[1].as_number(kStressGradient);
    d.gxy = (*g)[2].as_number(kStressGradient);
  }
  return d;
}

// ---- locating JSON syntax errors --------------------------------------------------------------

/// "line L, column C" (both 1-based, columns in bytes) of byte index `at` of `text`.
std::string line_column(const std::string& text, std::size_t at) {
  at = std::min(at, text.size());
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < at; ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(at - line_start + 1);
}

/// SAX handler that builds nothing and records the first error: its byte position, the token
/// read last, nlohmann's message and the JSON path of the value being read.
class ErrorLocator : public nlohmann::json_sax<json> {
 public:
  bool failed = false;
  int id = 0;                ///< nlohmann's error id (101: syntax, 406: number overflow, ...)
  std::size_t position = 0;  ///< bytes read when the error was found
  std::string token, message, path;

  bool null() override { return begin_value(); }
  bool boolean(bool) override { return begin_value(); }
  bool number_integer(number_integer_t) override { return begin_value(); }
  bool number_unsigned(number_unsigned_t) override { return begin_value(); }
  bool number_float(number_float_t, const string_t&) override { return begin_value(); }
  bool string(string_t&) override { return begin_value(); }
  bool binary(binary_t&) override { return begin_value(); }
  bool start_object(std::size_t) override {
    begin_value();
    frames_.push_back(Frame{false, 0, ""});
    return true;
  }
  bool key(string_t& k) override {
    frames_.back().key = k;
    return true;
  }
  bool end_object() override { return end_container(); }
  bool start_array(std::size_t) override {
    begin_value();
    frames_.push_back(Frame{true, 0, ""});
    return true;
  }
  bool end_array() override { return end_container(); }

  bool parse_error(std::size_t pos, const std::string& last_token,
                   const json::exception& ex) override {
    failed = true;
    id = ex.id;
    position = pos;
    token = last_token;
    message = ex.what();
    // Drop "[json.exception.parse_error.101] " and "parse error at line 1, column 2: ": the
    // position is reported on its own.
    const std::size_t bracket = message.find("] ");
    if (bracket != std::string::npos) message.erase(0, bracket + 2);
    const std::size_t colon = message.find(": ");
    if (message.rfind("parse error", 0) == 0 && colon != std::string::npos)
      message.erase(0, colon + 2);
    // The failing value is the next element of the innermost array (not yet counted) or the
    // value of the innermost object's last key; outer arrays are on their last element.
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      const bool innermost = i + 1 == frames_.size();
      path += "/" +
              (f.array ? std::to_string(innermost ? f.count : f.count - 1) : escape_pointer(f.key));
    }
    return false;
  }

 private:
  struct Frame {
    bool array;         ///< array or object
    std::size_t count;  ///< array: elements begun so far
    std::string key;    ///< object: the last key read
  };
  std::vector<Frame> frames_;

  bool begin_value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().count;
    return true;
  }
  bool end_container() {
    frames_.pop_back();
    return true;
  }
};

}  // namespace

// ---- public functions --------------------------------------------------------------------------

json parse_json_text(const std::string& text, const std::string& file) {
  try {
    return json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::exception&) {
    // Parse again only to find where: a number overflow (406) carries no position at all.
    ErrorLocator locator;
    json::sax_parse(text, &locator, json::input_format_t::json, /*strict=*/true,
                    /*ignore_comments=*/true);
    if (!locator.failed) throw;  // cannot happen: both passes run the same parser
    if (locator.id == 406) {
      // The position is just past the number; point at its first character instead.
      const std::size_t start = locator.position - std::min(locator.position, locator.token.size());
      throw InputError(file, locator.path,
                       "number " + locator.token + " is too large for a double (at " +
                           line_column(text, start) + ")");
    }
    // The position counts the bytes read, so the offending byte is the one before it (at the end
    // of the input it is one past the text).
    const std::size_t at = locator.position == 0 ? 0 : locator.position - 1;
    throw InputError(file, line_column(text, at), "invalid JSON: " + locator.message);
  }
}

SceneDef parse_scene(const std::string& text, const std::string& file) {
  return scene_from_json(parse_json_text(text, file), file);
}

SceneDef scene_from_json(const json& doc, const std::string& file) {
  const Reader root(doc, file, "");
  root.check_keys({"name", "gravity", "plane", "materials", "joint_sets", "bodies", "joints",
                   "interface_set", "mesh", "fixed_points", "loads", "measure_points", "solver",
                   "supports", "tractions", "insitu_stress", "excavate", "base_acceleration", "water",
                   "fracture", "bolts", "absorbing"});
  SceneDef scene;

  if (root.has("name")) scene.name = root["name"].as_string();
  if (root.has("gravity")) {
    scene.has_gravity = true;
    scene.gravity = root["gravity"].as_bounded_pair("[gx, gy]", kMaxAcceleration);
  }
  if (root.has("plane"))
    scene.plane = root["plane"].as_choice({"strain", "stress"}, "plane") == 0 ? PlaneKind::strain
                                                                              : PlaneKind::stress;

  const Reader materials = root["materials"];
  for (const auto& [name, r] : materials.members())
    scene.materials.push_back(read_material(name, r));
  if (scene.materials.empty()) materials.fail("at least one material is required");

  if (const auto sets = root.optional("joint_sets"))
    for (const auto& [name, r] : sets->members())
      scene.joint_sets.push_back(read_joint_set(name, r));

  const Reader bodies = root["bodies"];
  bodies.expect_array();
  if (bodies.size() == 0) bodies.fail("at least one body is required");
  for (std::size_t i = 0; i < bodies.size(); ++i)
    scene.bodies.push_back(read_body(bodies[i], scene.materials));

  if (const auto joints = root.optional("joints")) {
    joints->expect_array();
    for (std::size_t i = 0; i < joints->size(); ++i)
      scene.joints.push_back(read_joint((*joints)[i], scene.joint_sets));
  }

  if (const auto iface = root.optional("interface_set"))
    scene.interface_set = find_by_name(scene.joint_sets, *iface, "joint set", "joint_sets");

  const Reader mesh = root["mesh"];
  mesh.check_keys({"size"});
  scene.mesh_size = mesh.number("size", kPositive);
  // Every number derived from the mesh size (triangle and node counts, node coordinates) is
  // checked here, where the message can name /mesh/size (common/lattice.h).
  const std::string lattice = lattice_problem(scene.bodies, scene.mesh_size);
  if (!lattice.empty()) mesh["size"].fail(lattice);

  // Generated joint sets: the expected joint count over the bodies' bounding box stays bounded.
  for (const JointSetDef& set : scene.joint_sets) {
    if (!set.generated) continue;
    const Box box = bodies_box(scene.bodies);
    const JointGenerationDef& g = set.generate;
    const double intensity = g.p21 > 0 ? g.p21 : 1 / g.mean_spacing;
    const double expected = intensity * (box.x1 - box.x0) * (box.y1 - box.y0) / mean_of(g.length);
    if (expected > kMaxGeneratedJoints)
      root["joint_sets"][set.name]["generate"].fail(
          "about " + format_number(expected) + " joints expected over the bodies' box, more than " +
          format_number(kMaxGeneratedJoints) + "; lower p21 or raise the trace length");
  }

  if (const auto fixed = root.optional("fixed_points")) scene.fixed_points = read_points(*fixed);

  if (const auto loads = root.optional("loads")) {
    loads->expect_array();
    for (std::size_t i = 0; i < loads->size(); ++i) {
      const Reader load = (*loads)[i];
      load.check_keys({"point", "force", "table"});
      scene.loads.push_back(
          LoadDef{load["point"].as_point(), load["force"].as_bounded_pair("[fx, fy]", kMaxForce)});
      scene.load_tables.emplace_back();
      if (const auto t = load.optional("table")) scene.load_tables.back() = read_time_table(*t);
    }
  }

  if (const auto measure = root.optional("measure_points"))
    scene.measure_points = read_points(*measure);

  if (const auto solver = root.optional("solver")) scene.solver = read_solver(*solver);

  if (const auto r = root.optional("supports")) scene.supports = read_supports(*r);
  if (const auto r = root.optional("tractions")) scene.tractions = read_tractions(*r);
  if (const auto r = root.optional("insitu_stress")) scene.insitu_stress = read_insitu(*r, scene);
  if (const auto r = root.optional("excavate")) {
    r->expect_array();
    for (std::size_t i = 0; i < r->size(); ++i) {
      const std::int64_t b = (*r)[i].as_integer(0);
      if (b >= static_cast<std::int64_t>(scene.bodies.size()))
        (*r)[i].fail("no body " + std::to_string(b) + " (the scene has " +
                     std::to_string(scene.bodies.size()) + ")");
      scene.excavate.push_back(static_cast<int>(b));
    }
  }
  if (const auto r = root.optional("base_acceleration")) {
    r->check_keys({"x", "y"});
    if (const auto t = r->optional("x")) scene.base_acceleration_x = read_time_table(*t);
    if (const auto t = r->optional("y")) scene.base_acceleration_y = read_time_table(*t);
  }
  if (const auto r = root.optional("water")) scene.water = read_water(*r, scene);
  if (const auto r = root.optional("fracture")) {
    r->check_keys({"crack_set"});
    scene.fracture.present = true;
    scene.fracture.crack_set = find_by_name(scene.joint_sets, (*r)["crack_set"], "joint set", "joint_sets");
    // A crack is cut into the covers as they were cut, and its new covers take the cover
    // function of the cover they came from: constant cover functions only (docs/fracture.md).
    if (scene.solver.cover_order != 0)
      (*r).fail("fracturing needs cover order 0 (solver.cover_order is " +
                std::to_string(scene.solver.cover_order) + ")");
  }
  if (const auto r = root.optional("bolts")) scene.bolts = read_bolts(*r);
  if (const auto r = root.optional("absorbing")) scene.absorbing = read_absorbing(*r);
  // A crack re-cuts the elements a bolt is tied to and the boundary edges a dashpot acts on; the
  // solver carries neither over yet (docs/fracture.md "Not yet").
  if (scene.fracture.present && (!scene.bolts.empty() || !scene.absorbing.empty()))
    root["fracture"].fail(std::string("fracturing with ") + (!scene.bolts.empty() ? "bolts" : "absorbing boundaries") +
                          " is not built yet: leave out one or the other");
  return scene;
}

double ring_signed_area(const Ring& ring) {
  // Shoelace relative to the first vertex: round-off proportional to the ring's own size rather
  // than to its distance from the origin.
  double twice = 0;
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) {
    const double ax = ring[i].x - ring[0].x, ay = ring[i].y - ring[0].y;
    const double bx = ring[i + 1].x - ring[0].x, by = ring[i + 1].y - ring[0].y;
    twice += ax * by - ay * bx;
  }
  return 0.5 * twice;
}

double body_area(const BodyDef& body) {
  double area = std::fabs(ring_signed_area(body.outer));
  for (const Ring& hole : body.holes) area -= std::fabs(ring_signed_area(hole));
  return area;
}

}  // namespace nmm
