// Materials of a scene ("materials": {NAME: {...}}): the elastic constants every body needs and,
// optionally, the strength of intact rock, where it breaks (docs/fracture.md).
#pragma once

#include <string>

namespace nmm {

class JsonReader;

/// The strength of intact rock (a material's "strength"): where it breaks (docs/fracture.md).
struct StrengthDef {
  bool present = false;         ///< the material can break (a scene "fracture" block is needed too)
  double tensile = 0;           ///< Pa, > 0: the tension cut-off, σ1 ≥ tensile (tension positive)
  double cohesion = 0;          ///< Pa, ≥ 0: Mohr–Coulomb's c
  double friction_deg = 0;      ///< degrees, in [0, 90): Mohr–Coulomb's φ
  double fracture_energy = 0;   ///< J/m², G_f of a new crack's cohesive softening (0: none, brittle)
  double toughness = 0;         ///< Pa·√m, K_Ic (0: none): crack tips grow by LEFM (docs/crack-tips.md)
};

struct MaterialDef {
  std::string name;
  double density = 0;  ///< kg/m³, > 0
  double young = 0;    ///< Pa, > 0
  double poisson = 0;  ///< –, in [0, 0.5)
  StrengthDef strength;  ///< absent: the material never breaks
};

/// materials.NAME: {density, young, poisson, strength: {tensile, cohesion, friction_deg,
/// fracture_energy, toughness}}.
MaterialDef read_material(const std::string& name, const JsonReader& r);

}  // namespace nmm
