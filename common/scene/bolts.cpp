// Rock bolts and cables of a scene: see bolts.h.
#include "common/scene/bolts.h"

#include <cstddef>
#include <limits>
#include <string>

#include "common/number_format.h"
#include "common/scene/json_reader.h"

namespace nmm {

std::vector<BoltDef> read_bolts(const JsonReader& r) {
  r.expect_array();
  const ValueRange force = interval(0, false, kMaxForce, true);  // N per bolt
  std::vector<BoltDef> out;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const JsonReader b = r[i];
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
    const JsonReader pts = b["points"];
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

}  // namespace nmm
