// Strength reduction and the bracket / k-section search (equations and rules in the header).
#include "studies/strength_reduction.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "common/math_constants.h"

namespace nmm::studies {

namespace {

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
}  // namespace

std::vector<SetStrength> set_strengths(const nlohmann::json& scene,
                                       const std::vector<std::string>& sets,
                                       const std::string& source) {
  if (!scene.contains("joint_sets") || !scene["joint_sets"].is_object() ||
      scene["joint_sets"].empty())
    throw InputError(source, "/joint_sets", "no joint sets: nothing to reduce");
  const nlohmann::json& all = scene["joint_sets"];
  std::vector<std::string> names = sets;
  if (names.empty())
    for (auto it = all.begin(); it != all.end(); ++it) names.push_back(it.key());
  std::vector<SetStrength> out;
  for (const std::string& name : names) {
    if (!all.contains(name))
      throw InputError("", "--sets", "joint set '" + name + "' is not in " + source);
    const nlohmann::json& js = all[name];
    SetStrength s;
    s.name = name;
    const double phi = js.value("friction_deg", 0.0);
    s.tan_phi = std::tan(phi * kPi / 180);
    s.cohesion = js.value("cohesion", 0.0);
    s.tensile_strength = js.value("tensile_strength", 0.0);
    s.residual_cohesion = js.value("residual_cohesion", 0.0);
    s.shear_model = js.contains("shear") ? js["shear"].value("model", "constant") : "constant";
    if (js.contains("shear")) s.strength_factor = js["shear"].value("strength_factor", 1.0);
    out.push_back(s);
  }
  return out;
}

std::vector<std::string> reduction_sets(const std::vector<SetStrength>& sets, double factor) {
  std::vector<std::string> out;
  for (const SetStrength& s : sets) {
    const std::string p = "joint_sets." + s.name + ".";
    if (s.shear_model == "barton_bandis")  // the whole τ(σn), roughness included (header)
      out.push_back(p + "shear.strength_factor=" + number(s.strength_factor * factor));
    else
      out.push_back(p + "friction_deg=" + number(std::atan(s.tan_phi / factor) * 180 / kPi));
    out.push_back(p + "cohesion=" + number(s.cohesion / factor));
    out.push_back(p + "tensile_strength=" + number(s.tensile_strength / factor));
    // The residual cohesion is strength too (and may not exceed the reduced cohesion).
    if (s.residual_cohesion > 0) out.push_back(p + "residual_cohesion=" + number(s.residual_cohesion / factor));
  }
  return out;
}

SearchResult search_factor_of_safety(
    const SearchOptions& o,
    const std::function<std::vector<TrialRecord>(const std::vector<double>&, int)>& run_round) {
  SearchResult r;
  const int k = std::max(1, o.per_round);
  double lo = 0, hi = 0;  // largest stable below the smallest failing; smallest failing
  auto update = [&] {
    hi = 0;
    for (const TrialRecord& t : r.trials)
      if (t.failing && (hi == 0 || t.factor < hi)) hi = t.factor;
    lo = 0;
    r.monotone = true;
    for (const TrialRecord& t : r.trials) {
      if (t.failing) continue;
      if (hi != 0 && t.factor > hi) {
        r.monotone = false;
        continue;
      }
      lo = std::max(lo, t.factor);
    }
  };
  for (;;) {
    std::vector<double> factors;
    if (lo == 0 && hi == 0) {
      // First round: the start factor and k − 1 doublings above it.
      for (int j = 0; j < k; ++j) factors.push_back(o.start * std::pow(2.0, j));
    } else if (hi == 0) {
      if (lo >= o.max_factor) {
        r.status = "stable up to F = " + number(lo) + " (no failing trial)";
        break;
      }
      for (int j = 1; j <= k; ++j) factors.push_back(std::min(o.max_factor, lo * std::pow(2.0, j)));
    } else if (lo == 0) {
      if (hi <= o.min_factor) {
        r.status = "failing down to F = " + number(hi) + " (no stable trial)";
        break;
      }
      for (int j = 1; j <= k; ++j) factors.push_back(std::max(o.min_factor, hi * std::pow(0.5, j)));
    } else {
      if (hi - lo <= o.tolerance * lo) {
        r.found = true;
        r.status = "ok";
        r.fos = 0.5 * (lo + hi);
        break;
      }
      for (int j = 1; j <= k; ++j) factors.push_back(lo + (hi - lo) * j / (k + 1));
    }
    // Never repeat a factor already tried (the clamps at max/min can produce one).
    std::sort(factors.begin(), factors.end());
    factors.erase(std::unique(factors.begin(), factors.end()), factors.end());
    factors.erase(std::remove_if(factors.begin(), factors.end(),
                                 [&](double f) {
                                   for (const auto& t : r.trials)
                                     if (t.factor == f) return true;
                                   return false;
                                 }),
                  factors.end());
    if (factors.empty()) {
      r.status = lo == 0 ? "failing down to F = " + number(hi) : "stable up to F = " + number(lo);
      break;
    }
    ++r.rounds;
    std::vector<TrialRecord> got = run_round(factors, r.rounds);
    for (TrialRecord& t : got) {
      t.round = r.rounds;
      r.trials.push_back(t);
    }
    update();
  }
  r.lo = lo;
  r.hi = hi;
  return r;
}

}  // namespace nmm::studies
