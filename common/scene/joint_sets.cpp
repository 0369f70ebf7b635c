// Joint sets of a scene: see joint_sets.h.
//
// Mean of a power-law length on [min, max], p(L) ∝ L^-a:
//   E[L] = (a − 1)/(2 − a) · (max^(2−a) − min^(2−a)) / (min^(1−a) − max^(1−a)),
//   and ln(max/min) / (1/min − 1/max) at a = 2.
#include "common/scene/joint_sets.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "common/number_format.h"
#include "common/scene/json_reader.h"

namespace nmm {

namespace {

/// A length distribution (trace length or spacing), m; a bare number is a constant.
LengthDef read_length_distribution(const JsonReader& r) {
  const ValueRange length = interval(0, false, kMaxCoordinate, true);
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

/// joint_sets.NAME.generate (common/joint_generation.h, docs/joint-networks.md).
JointGenerationDef read_joint_generation(const JsonReader& r) {
  r.check_keys({"region", "orientation", "p21", "spacing", "length", "position", "termination",
                "seed"});
  JointGenerationDef g;
  if (r.has("region")) g.region = r["region"].as_ring();
  const JsonReader o = r["orientation"];
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
  const ValueRange p21 = interval(0, false, 1e3, true);
  if (g.position == PositionModel::poisson) {
    if (r.has("p21") == r.has("spacing")) r.fail("give either p21 or spacing (one of them)");
    if (r.has("p21")) g.p21 = r.number("p21", p21);
    if (r.has("spacing")) {
      g.spacing_distribution = read_length_distribution(r["spacing"]);
      g.mean_spacing = mean_length(g.spacing_distribution);
      g.p21 = 1 / g.mean_spacing;
    }
  } else {
    if (g.dispersion != DispersionKind::none)
      o.fail("the spacing position model makes parallel joints: no kappa or spread_deg");
    g.spacing_distribution = read_length_distribution(r["spacing"]);
    g.mean_spacing = mean_length(g.spacing_distribution);
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

}  // namespace

double mean_length(const LengthDef& d) {
  if (d.kind != LengthDistribution::power_law) return d.mean;
  const double a = d.exponent;
  if (std::fabs(a - 2) < 1e-12) return std::log(d.max / d.min) / (1 / d.min - 1 / d.max);
  return (a - 1) / (2 - a) * (std::pow(d.max, 2 - a) - std::pow(d.min, 2 - a)) /
         (std::pow(d.min, 1 - a) - std::pow(d.max, 1 - a));
}

JointSetDef read_joint_set(const std::string& name, const JsonReader& r) {
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

}  // namespace nmm
