// The re-cut's check mode (docs/fracture.md "Re-cutting"): with NMM_CHECK_RECUT=1 in the
// environment, every re-cut of a run's mesh is compared with a full cut of the scene with every
// crack segment as a joint (common/mesh_compare.h). The fracturing matrix in CTest runs with it.
// The full cut is a pre::GrowingCut the run keeps: each check's scene is the last one's with the
// new crack segments appended, so only those are inserted into the kept exact arrangement (the
// same cut as pre::build_mesh's, cover_cutter.h); any other scene is cut from nothing.
#pragma once

#include <string>

#include "common/mesh.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"

namespace nmm::solve {

/// Whether NMM_CHECK_RECUT is set (and not "0"), read once.
bool recut_check_enabled();

/// "" when `recut` (cut from `before` where new cracks grew) is the full cut of `cracked` (by
/// `full_cut`, the run's); else the first difference in words. With NMM_CHECK_RECUT_DUMP=PREFIX
/// set, a difference also writes PREFIX.before.nmm, PREFIX.recut.nmm, PREFIX.full.nmm (each with
/// the run's scene and its digest, so nmm-inspect reads them) and PREFIX.joints.txt (every joint
/// segment of `cracked`, one a line: joint x0 y0 x1 y1).
std::string recut_difference(const Mesh& before, const Mesh& recut, const SceneDef& cracked,
                             const std::string& scene_name, pre::GrowingCut& full_cut);

}  // namespace nmm::solve
