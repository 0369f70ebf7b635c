// What the flow tests read of a run's flow network: the run's flow effect and the network node
// nearest a point (solver/flow/flow_network.h; docs/flow.md).
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "solver/flow/flow_effect.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::test {

/// The run's flow effect (a scene with "flow"); throws without one.
inline const solve::FlowEffect& flow_of(const solve::TimeStepper& st) {
  for (const solve::Effect* e : st.view().effects)
    if (const auto* f = dynamic_cast<const solve::FlowEffect*>(e)) return *f;
  throw std::logic_error("no flow effect");
}

/// The network node nearest (x, y) m, as cut.
inline std::size_t node_near(const solve::FlowNetwork& net, double x, double y) {
  std::size_t best = 0;
  double d = 1e300;
  for (std::size_t i = 0; i < net.nodes(); ++i) {
    const double di = std::hypot(net.node_xy()[2 * i] - x, net.node_xy()[2 * i + 1] - y);
    if (di < d) d = di, best = i;
  }
  return best;
}

}  // namespace nmm::test
