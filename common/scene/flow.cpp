// Fluid flow along the joints of a scene: see flow.h.
//
// A pressure or a rate is a number (constant) or a time table ([[t, value], ...] or a CSV file's
// name: time_tables.h), held in both cases as a table (a number: one row at t = 0).
#include "common/scene/flow.h"

#include <algorithm>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "common/number_format.h"
#include "common/scene.h"
#include "common/scene/json_reader.h"

namespace nmm {

namespace {

// A number (one row at t = 0) or a time table, every value within `range`.
TimeTable number_or_table(const JsonReader& r, const ValueRange& range) {
  if (r.value().is_number()) return TimeTable{{0.0}, {r.as_number(range)}};
  TimeTable t = read_time_table(r);
  for (std::size_t k = 0; k < t.value.size(); ++k) {
    if (range.contains(t.value[k])) continue;
    if (r.value().is_array()) r[k][1].as_number(range);  // names the row's value
    r.fail("row " + std::to_string(k + 1) + " of the table: the value must be " + range.text());
  }
  return t;
}

}  // namespace

FlowDef read_flow(const JsonReader& r, const SceneDef& scene) {
  r.check_keys({"fluid", "aperture", "initial_pressure", "initially_dry", "boundaries", "injections", "steady"});
  if (scene.water.present)
    r.fail("\"flow\" and \"water\" both set the joints' water pressure: give one (flow computes it)");
  FlowDef f;
  f.present = true;
  const ValueRange pressure = interval(-kMaxStrength, true, kMaxStrength, true);
  if (const auto fl = r.optional("fluid")) {
    fl->check_keys({"viscosity", "bulk_modulus", "density", "cavitation_pressure"});
    f.viscosity = fl->optional_number("viscosity", f.viscosity, interval(0, false, 1e12, true));
    f.bulk_modulus = fl->optional_number("bulk_modulus", f.bulk_modulus, interval(0, false, kMaxModulus, true));
    f.density = fl->optional_number("density", f.density, interval(0, true, kMaxDensity, true));
    if (fl->has("cavitation_pressure")) {
      f.cavitation = true;
      // Above −K_f, so that the fluid's volume V·(1 + p/K_f) stays positive at the floor.
      f.cavitation_pressure =
          fl->optional_number("cavitation_pressure", 0, interval(-std::min(kMaxStrength, 0.5 * f.bulk_modulus), true, kMaxStrength, true));
    }
  }
  if (const auto ap = r.optional("aperture")) {
    ap->check_keys({"residual", "max", "coupled"});
    f.residual = ap->optional_number("residual", f.residual, interval(0, false, kMaxClosure, true));
    f.max_aperture = ap->optional_number("max", std::max(f.max_aperture, f.residual),
                                         interval(0, false, kMaxClosure, true));
    if (f.max_aperture < f.residual)
      (*ap)["max"].fail("the cap " + format_number(f.max_aperture) + " m is below the residual aperture " +
                        format_number(f.residual) + " m");
    if (ap->has("coupled")) f.coupled = (*ap)["coupled"].as_bool();
  }
  f.initial_pressure = r.optional_number("initial_pressure", 0, pressure);
  if (f.cavitation && !(r.has("initially_dry") && r["initially_dry"].as_bool()) &&
      f.initial_pressure < f.cavitation_pressure)
    r["fluid"]["cavitation_pressure"].fail("the cavitation pressure " + format_number(f.cavitation_pressure) +
                                           " Pa is above the initial pressure " + format_number(f.initial_pressure) + " Pa");
  if (r.has("steady")) f.steady = r["steady"].as_bool();
  if (r.has("initially_dry")) f.initially_dry = r["initially_dry"].as_bool();
  if (f.initially_dry && !f.cavitation)
    r["initially_dry"].fail("a dry joint holds vapour at the fluid's cavitation pressure: give /flow/fluid/cavitation_pressure");
  if (f.initially_dry && r.has("initial_pressure"))
    r["initial_pressure"].fail("a dry joint starts at the fluid's cavitation pressure: leave initial_pressure out");
  if (f.initially_dry) f.initial_pressure = f.cavitation_pressure;
  if (f.cavitation && f.steady)
    r["fluid"]["cavitation_pressure"].fail("a fluid lag needs storage: give it in a transient run (\"steady\": false)");
  if (const auto bs = r.optional("boundaries")) {
    bs->expect_array();
    for (std::size_t i = 0; i < bs->size(); ++i) {
      const JsonReader b = (*bs)[i];
      b.check_keys({"points", "pressure"});
      FlowBoundaryDef d;
      d.points = b["points"].as_point_list(2, false, "a flow boundary");
      d.pressure = number_or_table(b["pressure"], pressure);
      f.boundaries.push_back(std::move(d));
    }
  }
  if (const auto is = r.optional("injections")) {
    is->expect_array();
    for (std::size_t i = 0; i < is->size(); ++i) {
      const JsonReader e = (*is)[i];
      e.check_keys({"point", "rate"});
      FlowInjectionDef d;
      d.point = e["point"].as_point();
      d.rate = number_or_table(e["rate"], interval(-1e6, true, 1e6, true));
      f.injections.push_back(std::move(d));
    }
  }
  return f;
}

}  // namespace nmm
