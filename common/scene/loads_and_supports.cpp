// Loads, supports, tractions and ground motion of a scene: see loads_and_supports.h.
#include "common/scene/loads_and_supports.h"

#include <cstddef>
#include <string>

#include "common/scene/json_reader.h"

namespace nmm {

void read_loads(const JsonReader& r, std::vector<LoadDef>& loads, std::vector<TimeTable>& tables) {
  r.expect_array();
  for (std::size_t i = 0; i < r.size(); ++i) {
    const JsonReader load = r[i];
    load.check_keys({"point", "force", "table"});
    loads.push_back(
        LoadDef{load["point"].as_point(), load["force"].as_bounded_pair("[fx, fy]", kMaxForce)});
    tables.emplace_back();
    if (const auto t = load.optional("table")) tables.back() = read_time_table(*t);
  }
}

std::vector<SupportDef> read_supports(const JsonReader& r) {
  r.expect_array();
  std::vector<SupportDef> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const JsonReader s = r[i];
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

std::vector<TractionDef> read_tractions(const JsonReader& r) {
  r.expect_array();
  std::vector<TractionDef> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const JsonReader s = r[i];
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

void read_base_acceleration(const JsonReader& r, TimeTable& x, TimeTable& y) {
  r.check_keys({"x", "y"});
  if (const auto t = r.optional("x")) x = read_time_table(*t);
  if (const auto t = r.optional("y")) y = read_time_table(*t);
}

}  // namespace nmm
