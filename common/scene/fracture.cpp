// Fracturing in a scene: see fracture.h.
#include "common/scene/fracture.h"

#include <string>

#include "common/scene.h"
#include "common/scene/json_reader.h"

namespace nmm {

FractureDef read_fracture(const JsonReader& r, const SceneDef& scene) {
  r.check_keys({"crack_set", "tip_step", "viscous_tip"});
  FractureDef f;
  f.present = true;
  f.crack_set = find_by_name(scene.joint_sets, r["crack_set"], "joint set", "joint_sets");
  f.tip_step = r.optional_number("tip_step", 0, interval(0, false, 1e6, true));
  if (r.has("viscous_tip")) f.viscous_tip = r["viscous_tip"].as_bool();
  // A crack is cut into the covers as they were cut, and its new covers take the cover
  // function of the cover they came from: constant cover functions only (docs/fracture.md).
  if (scene.solver.cover_order != 0)
    r.fail("fracturing needs cover order 0 (solver.cover_order is " +
           std::to_string(scene.solver.cover_order) + ")");
  return f;
}

}  // namespace nmm
