// The in-situ stress of a scene: see insitu_stress.h.
//
//   σ(x, y) = σ0 + (y_ref − y)·gradient                     (Pa, tension positive)
//   K0 shortcut: σyy = syy − ρ·g·(y_ref − y), σxx = K0·σyy, σxy = 0
#include "common/scene/insitu_stress.h"

#include <cmath>

#include "common/scene.h"
#include "common/scene/json_reader.h"

namespace nmm {

InsituStressDef read_insitu(const JsonReader& r, const SceneDef& scene) {
  InsituStressDef d;
  d.present = true;
  if (r.has("k0")) {
    r.check_keys({"k0", "y_ref", "density", "syy", "g"}, " with \"k0\"");
    const double k0 = r.number("k0", interval(0, true, 10, true));  // K0 of rock: 0.3 to 3
    d.y_ref = r["y_ref"].as_number(kCoordinate);
    const double rho = r.optional_number("density", scene.materials.front().density,
                                         interval(0, false, kMaxDensity, true));
    const double g_default =
        scene.has_gravity ? std::hypot(scene.gravity.x, scene.gravity.y) : 9.81;
    const double g = r.optional_number("g", g_default, interval(0, true, kMaxAcceleration, true));
    d.syy = r.optional_number("syy", 0, kStress);
    d.sxx = k0 * d.syy;
    d.gyy = -rho * g;
    d.gxx = k0 * d.gyy;
    return d;
  }
  r.check_keys({"sxx", "syy", "sxy", "y_ref", "gradient"});
  d.sxx = r.optional_number("sxx", 0, kStress);
  d.syy = r.optional_number("syy", 0, kStress);
  d.sxy = r.optional_number("sxy", 0, kStress);
  d.y_ref = r.optional_number("y_ref", 0, kCoordinate);
  if (const auto g = r.optional("gradient")) {
    g->expect_array();
    if (g->size() != 3) g->fail("expected [gxx, gyy, gxy] (Pa per m of depth)");
    d.gxx = (*g)[0].as_number(kStressGradient);
    d.gyy = (*g)[1].as_number(kStressGradient);
    d.gxy = (*g)[2].as_number(kStressGradient);
  }
  return d;
}

}  // namespace nmm
