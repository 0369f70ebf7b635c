// Fracturing in a scene: see fracture.h.
#include "common/scene/fracture.h"

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
  // Any cover order: a new cover takes the cover function of the cover it is a piece of, and a
  // piece of an element its parent's stress polynomial (solver/fracture/state_transfer.h).
  return f;
}

}  // namespace nmm
