// Water in the joints of a scene: see water.h.
//
// The phreatic surface must give one water level at each position across gravity: with the
// position s = (−x·gy + y·gx)/|g| (s = x for gravity pointing down), its points' s must be
// strictly monotone.
#include "common/scene/water.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/scene.h"
#include "common/scene/json_reader.h"

namespace nmm {

WaterDef read_water(const JsonReader& r, const SceneDef& scene) {
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
      const JsonReader e = (*js)[i];
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
      const ValueRange pressure = interval(0, true, kMaxStrength, true);
      if (e.has("fill_depth")) {
        if (!(g > 0)) e["fill_depth"].fail("fill_depth needs gravity (the pressure is ρw·g·depth)");
        d.fill_depth = e.number("fill_depth", interval(0, true, kMaxCoordinate, true));
      } else if (e["pressure"].value().is_number()) {
        d.at.push_back(0);
        d.pressure.push_back(e.number("pressure", pressure));
      } else {
        const JsonReader t = e["pressure"];
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

}  // namespace nmm
