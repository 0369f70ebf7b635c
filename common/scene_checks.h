// Mistakes in a scene that parse and cut fine but make a useless or surprising model, caught
// before the cut (nmm-preprocess) instead of by the solver or not at all:
//   - a fixed, load or measure point, or a bolt's end, outside every body (error: the solver
//     could not hold, load, measure or anchor anything there);
//   - a joint touching no body (a warning naming it, an error with nmm-preprocess
//     --strict-joints: it is dropped — a coordinate typo, or a generated joint beyond the bodies);
//   - a mesh size larger than a body's inradius (warning: the body gets a handful of elements and
//     cannot bend; the estimate 2·area/perimeter is exact for triangles and regular polygons and
//     never below the true inradius, so the warning is never a false alarm).
// Plain double geometry (no CGAL): points on a boundary count as inside.
#pragma once

#include <string>
#include <vector>

#include "common/scene.h"

namespace nmm {

/// True when p lies in the body (inside its outer ring, not strictly inside a hole), with
/// boundary points counting as inside (tolerance `tol`, m).
bool point_in_body(const BodyDef& body, Vec2 p, double tol);

/// True when some part of the polyline lies in the body.
bool polyline_touches_body(const BodyDef& body, const std::vector<Vec2>& line, double tol);

/// 2·area/perimeter of the body (holes count in both), m: an upper bound of its inradius.
double body_inradius_estimate(const BodyDef& body);

/// Throws InputError(file, JSON path, what) for the first point outside every body, and for the
/// first joint touching no body unless `allow_stray_joints`. Returns the warnings (one line
/// each, "file: /json/path: what"), e.g. the mesh size above a body's inradius, and joints
/// touching no body when they are allowed.
std::vector<std::string> check_scene_usability(const SceneDef& scene, const std::string& file,
                                               bool allow_stray_joints);

}  // namespace nmm
