// Whether two meshes of one scene are the same cut: the same nodes and triangles, the same
// manifold elements (loops with their edges' origins and joints, whatever vertex a loop starts at
// and whatever order a triangle's elements come in), the same physical covers (as sets of element
// corners), the same blocks (as sets of elements) and the same contact edges (with the element
// across). Numbering may differ, and a vertex's coordinates by the rounding of a point the cut
// constructs (64 ulps: mesh_compare.cpp); nothing else may.
//
// Used to check that re-cutting a mesh where cracks grew (preprocess/recut.h) gives exactly the
// mesh a full cut of the scene with the crack segments as joints gives (docs/fracture.md
// "Re-cutting"; the solver's check mode NMM_CHECK_RECUT=1 and tests/test_recut.cpp).
#pragma once

#include <string>

#include "common/mesh.h"

namespace nmm {

/// "" when `a` and `b` are the same cut; otherwise the first difference found, in words (which
/// element, cover or block, where).
std::string mesh_difference(const Mesh& a, const Mesh& b);

}  // namespace nmm
