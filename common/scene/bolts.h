// Rock bolts and cables of a scene ("bolts": [...]; docs/reinforcement.md): DDA's
// point-anchored bolt and UDEC's fully grouted cable, numbered from 0 in the scene's order.
// The solver's side is solver/reinforcement/.
#pragma once

#include <vector>

#include "common/vec2.h"

namespace nmm {

class JsonReader;

/// What a bolt is (docs/reinforcement.md): DDA's point-anchored bolt, an axial spring between
/// its two ends; or UDEC's fully grouted cable, axial segments tied along their length to the
/// rock by a grout shear spring.
enum class BoltType { anchored, grouted };

/// A straight rock bolt or cable from `a` to `b` (solver/reinforcement/). Forces and stiffnesses
/// are per bolt; in the plane-strain model each acts per metre of thickness divided by `spacing`.
/// A strength or yield force that is not given is none (infinity: never breaks, never yields).
struct BoltDef {
  Vec2 a, b;                         ///< m, its first and second point, both inside bodies
  BoltType type = BoltType::anchored;
  double spacing = 1;                ///< m between bolts out of the plane
  // anchored
  double stiffness = 0;              ///< N/m per bolt, of the axial spring
  double pretension = 0;             ///< N per bolt, its axial force when installed (tension > 0)
  double strength = 0;               ///< N per bolt: |axial force| at which it breaks (force 0 after)
  // grouted
  double ea = 0;                     ///< N per bolt, axial rigidity E·A of the steel
  double yield = 0;                  ///< N per bolt, axial yield force (tension and compression)
  double bond_stiffness = 0;         ///< N/m per m of bolt (Pa): grout shear stiffness
  double bond_strength = 0;          ///< N per m of bolt: grout shear strength
  int segments = 0;                  ///< axial segments; 0: the default (solver/reinforcement/bolt_layout.h)
};

/// bolts: [{points: [a, b], type: anchored | grouted, ...}] (BoltDef; docs/reinforcement.md).
/// The keys of one type are refused on the other, so that a grouted cable given a "stiffness"
/// (an anchored bolt's) is not silently a cable without it.
std::vector<BoltDef> read_bolts(const JsonReader& r);

}  // namespace nmm
