// Small scene pieces shared by the contact tests.
#pragma once

#include <vector>

#include "scene.h"

namespace nmm::test {

/// Axis-aligned rectangular body of material 0, m.
inline BodyDef box(double x0, double y0, double x1, double y1) {
  BodyDef b;
  b.material = 0;
  b.outer = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  return b;
}

/// Fixed points every 0.25 m along y = y0 from x0 to x1: a base held like a rigid foundation.
inline std::vector<Vec2> held_along(double x0, double x1, double y0) {
  std::vector<Vec2> p;
  for (double x = x0; x <= x1 + 1e-9; x += 0.25) p.push_back({x, y0});
  return p;
}

}  // namespace nmm::test
