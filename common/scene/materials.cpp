// Materials of a scene: see materials.h.
#include "common/scene/materials.h"

#include "common/scene/json_reader.h"

namespace nmm {

MaterialDef read_material(const std::string& name, const JsonReader& r) {
  r.check_keys({"density", "young", "poisson", "strength"});
  MaterialDef m;
  m.name = name;
  m.density = r.number("density", interval(0, false, kMaxDensity, true));
  m.young = r.number("young", interval(0, false, kMaxModulus, true));
  // 0.5 is incompressible: the plane-strain elasticity matrix blows up.
  m.poisson = r.number("poisson", interval(0, true, 0.5, false));
  if (const auto st = r.optional("strength")) {
    st->check_keys({"tensile", "cohesion", "friction_deg", "fracture_energy", "toughness"});
    StrengthDef& s = m.strength;
    s.present = true;
    s.tensile = st->number("tensile", kStrength);
    s.cohesion = st->number("cohesion", interval(0, true, kMaxStrength, true));
    s.friction_deg = st->number("friction_deg", interval(0, true, 90, false));  // tan 90° is infinite
    // J/m²: rock's is 10–500; the bound only refuses typing accidents. New cracks' faces soften
    // over it (solver/contact/cohesive_law.h, docs/fracture.md "Cohesive softening").
    s.fracture_energy = st->optional_number("fracture_energy", 0, interval(0, true, 1e9, true));
    // Pa·√m: rock's K_Ic is 0.1–3 MPa·√m; the bound only refuses typing accidents.
    s.toughness = st->optional_number("toughness", 0, interval(0, false, 1e10, true));
  }
  return m;
}

}  // namespace nmm
