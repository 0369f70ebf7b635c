// What the outputs read of a bolt: see bolt_readout.h.
#include "solver/reinforcement/bolt_readout.h"

#include "solver/reinforcement/bolt_layout.h"

namespace nmm::solve {

std::vector<BoltReading> bolt_readout(const BoltDef& def, const BoltState& b) {
  const std::size_t n = b.nodes.size();
  std::vector<BoltReading> out(n);
  const bool grouted = def.type == BoltType::grouted;
  for (std::size_t i = 0; i < n; ++i) {
    const TrackedPoint& p = b.nodes[i];
    BoltReading& r = out[i];
    r.s = installed_length(b.nodes[0], p);
    r.x = p.x;
    r.y = p.y;
    r.ux = p.x - p.x0;
    r.uy = p.y - p.y0;
    if (!grouted) {
      r.axial = b.axial[0];
      continue;
    }
    const double before = i > 0 ? b.axial[i - 1] : 0.0, after = i + 1 < n ? b.axial[i] : 0.0;
    r.axial = 0.5 * (before + after);
    const double tributary = tributary_length(b.nodes, i);
    r.bond = tributary > 0 ? -b.bond[i] / tributary : 0.0;  // on the cable: −G (bolt_system.cpp)
  }
  return out;
}

}  // namespace nmm::solve
