// Where the bolts are (docs/reinforcement.md): the rock points each bolt is tied to, located in
// the elements of the configuration it is installed in, and which bolts a run continues and
// which it installs.
//
//   anchored   its two ends, the points the axial spring pulls on (DDA's point-anchored bolt)
//   grouted    n + 1 segment points, evenly spaced from the first point to the second; the
//              grout ties the cable to the rock at each of them over its tributary length
//              (half of each adjacent segment). Default n: two segments per mesh size and two
//              per shear-lag length 1/λ, λ = √(k_bond/EA), whichever is more (at least 2, at most
//              1000): λ·Δs ≤ ½ keeps the lumped grout's decay constant within 1 % of the
//              continuous one's, 2·(cosh λ_h Δs − 1) = (λ Δs)² (docs/reinforcement.md)
//
// A bolt is installed at the step the run that adds it starts at — step 0 of the first run, or a
// restart (a tunnel is bolted after it is excavated) — so it carries no force from the rock's
// earlier deformation, only its pretension. Its points are points of the rock: the scene gives
// them in the mesh as cut (as its other points, model.h), each is tied to the element that held
// it there and starts where that point of the rock is now — a bolt head given on the tunnel wall
// as drawn is on the wall that has since converged by millimetres, and pictures draw it where
// the rock around it is drawn. They must lie in the rock of a body not excavated (within 1e-6·h: a point on a
// boundary); else the run's scene is bad input naming the bolt. A restart continues each
// checkpoint bolt whose type and points are still the scene's bolt of that number, and installs
// the others afresh (a bolt the scene no longer has is gone).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// m, the installed length between two of a bolt's points.
double installed_length(const TrackedPoint& a, const TrackedPoint& b);
/// m, the grout's tributary length at a cable's point i: half of each adjacent segment, installed.
double tributary_length(const std::vector<TrackedPoint>& points, std::size_t i);

/// The number of segments of a grouted cable (its own, or the default above); 1 for an anchored
/// bolt, whose spring is one segment between its ends.
int bolt_segments(const BoltDef& bolt, double mesh_size);

/// A run's bolts after cracks re-cut its mesh from `old` to `now` (element_parent: [now's
/// element] the old element it is a piece of; vertex_parent: [now's loop vertex] the old one at
/// its point or -1; preprocess/recut.h): each point is tied again to the piece of its element
/// that holds it as cut (x0, y0). A crack through the point itself (a face the re-cut made a
/// joint face within 1e-9·h of it, of a piece of its element or, for a point on its element's
/// edge, of an element across: a crack cut along that edge) is decided by the rock the bolt runs
/// into from it: the element holding the point moved 1e-6·h along the bolt towards its next
/// point (the last point: towards the one before), as cut — so the decision does not hang on the
/// rounding of a point on a crack face, and an anchor on a crack stays with the rock its bolt
/// runs through.
/// Nothing else of a bolt changes: its current points, forces, slips, yield and plastic work are
/// those of the same rock, carried unchanged (the pieces' cover functions are their parent's:
/// solver/fracture/state_transfer.h).
void retie_bolts(const Mesh& old, const Mesh& now, const std::vector<std::int32_t>& element_parent,
                 const std::vector<std::int32_t>& vertex_parent, std::vector<BoltState>& bolts);

/// The bolts of a run at state s (its step s.step, excavated bodies s.body_removed): `previous`'s
/// where they are the scene's, the others installed now. InputError
/// naming `scene_name` and /bolts/i/points for a bolt point outside the rock.
std::vector<BoltState> bolts_for_run(const SceneDef& scene, const Mesh& mesh, const RunState& s,
                                     const std::vector<BoltState>& previous, const std::string& scene_name);

}  // namespace nmm::solve
