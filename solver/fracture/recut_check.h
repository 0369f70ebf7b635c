// The re-cut's check mode (docs/fracture.md "Re-cutting"): with NMM_CHECK_RECUT=1 in the
// environment, every re-cut of a run's mesh is compared with a full cut of the scene with every
// crack segment as a joint (common/mesh_compare.h). The fracturing matrix in CTest runs with it.
#pragma once

#include <string>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::solve {

/// Whether NMM_CHECK_RECUT is set (and not "0"), read once.
bool recut_check_enabled();

/// "" when `recut` (cut from `before` where new cracks grew) is the full cut of `cracked`; else
/// the first difference in words. With NMM_CHECK_RECUT_DUMP=PREFIX set, a difference also writes
/// PREFIX.before.nmm, PREFIX.recut.nmm, PREFIX.full.nmm and PREFIX.joints.txt (every joint
/// segment of `cracked`, one a line: joint x0 y0 x1 y1) for a look with nmm-inspect.
std::string recut_difference(const Mesh& before, const Mesh& recut, const SceneDef& cracked,
                             const std::string& scene_name);

}  // namespace nmm::solve
