// Absorbing boundaries of a scene: see absorbing.h.
#include "common/scene/absorbing.h"

#include <cstddef>

#include "common/scene/json_reader.h"

namespace nmm {

std::vector<AbsorbingDef> read_absorbing(const JsonReader& r) {
  r.expect_array();
  std::vector<AbsorbingDef> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const JsonReader a = r[i];
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

}  // namespace nmm
