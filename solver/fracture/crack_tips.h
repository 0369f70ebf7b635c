// The tips of the cracks that end inside a body (docs/crack-tips.md): the ends of the
// scene's joints and of the cracks grown during the run that lie inside a body — not on its
// boundary and not on another joint or crack — with the crack's direction there, the body, and
// the radius of the domain its stress intensity factors are integrated over
// (interaction_integral.h). A tip keeps its number as its crack grows.
//
// Tips are found on the mesh as cut (the reference configuration). An end within 1e-6·h of a
// body's boundary or of another joint or crack is no tip (a crack cut to a joint or a boundary
// overshoots it by 1e-8·h: fracture.h). The domain's radius is kDomainRadius·h, less where
// another crack, tip or the body's boundary is nearer: the ring where q falls (one triangle wide
// beyond the radius) must hold only the tip's own crack and no loaded boundary.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "common/vec2.h"

namespace nmm::solve {

struct CrackTip {
  int id = -1;              ///< numbered from 0 in the order tips appear, kept as the crack grows
  Vec2 at;                  ///< m, as cut
  Vec2 direction;           ///< unit, along the crack towards the tip (ahead of it)
  std::int32_t body = -1;   ///< the body it lies in
  double radius = 0;        ///< m, the interaction integral's domain
  /// m, the tip's own crack from the tip backwards (the tip first, then each point where it turns,
  /// along its joints and cracks as cut), as far as the domain's ring reaches: where the
  /// integral's auxiliary fields have their cut (interaction_integral.h TipDomain::behind).
  std::vector<Vec2> behind;
};

class CrackTipFinder {
 public:
  /// ×h, the domain's radius where nothing nearer limits it (docs/fracture.md: the tests'
  /// errors against the radius).
  static constexpr double kDomainRadius = 3.0;

  /// The tips of the scene's joints and of `cracks` (segments as cut, in the order cut; a joint of
  /// the scene that is one of them is taken once), on the mesh `mesh` of the scene's bodies;
  /// numbers kept from the last call.
  std::vector<CrackTip> find(const Mesh& mesh, const SceneDef& scene,
                             const std::vector<std::array<Vec2, 2>>& cracks);

 private:
  std::vector<CrackTip> known_;  // the last call's tips
  int next_id_ = 0;
};

}  // namespace nmm::solve
