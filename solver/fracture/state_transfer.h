// What a run carries over when cracks re-cut its mesh (docs/fracture.md "What a new crack
// inherits"): every new physical cover takes the cover function of the cover it is a piece of
// (its coefficients — displacement, velocity, acceleration, at cover order n the 2·(n+1)(n+2)/2
// of cover_space.h about the same node — and its node), every new element the stress of the
// element it is a piece of (at n ≥ 1 the parent's stress polynomial, re-expanded about the
// piece's own origin where that is another node: σ(ξ) = Σ_t s_t ξ^p η^q with ξ_old = ξ_now −
// (o_old − o_now)/h), so the displacement, velocity and stress fields are the same functions
// before and after the cut and no energy appears or vanishes with it. A vertex the crack made is
// placed where its element's map puts it (element_geometry.h: affine at n = 0; at n ≥ 1 on the
// element's loop as it is now); the others keep their place.
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "preprocess/recut.h"
#include "solver/contact/contact.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// s, a state on `old`, carried onto `now` (map: preprocess/recut.h); dofs_per_cover: the run's
/// (2, 6, 12 at cover order 0, 1, 2). The sparse pattern's element pairs and the blocks' handed-on forces are
/// dropped: the next step grows the pattern again, and a step's hand-on is no state of the rock.
void transfer_state(const Mesh& old, const Mesh& now, const pre::RecutMap& map, int dofs_per_cover, RunState& s);

/// The map from the mesh after two re-cuts back to the mesh before both: `later` leads from the
/// newest mesh to the middle one, `earlier` from the middle one to the oldest. Each index of
/// `later` is an index into the middle mesh, so it is read through `earlier` (a vertex the later
/// cut made stays -1); T and R's diagnostics are summed. A step that re-cuts several times hands
/// its observers this composition, so that what they kept of the mesh at the last accepted step
/// is read at the right index (energy.h carry_over).
pre::RecutMap compose(const pre::RecutMap& later, const pre::RecutMap& earlier);

/// The contact history carried onto `now`: an entry follows its vertex (dropped where the vertex is
/// gone) and the block of the element it was against; a vertex at the start of a new crack face's
/// edge (a joint from `first_new_joint` on) starts closed and locked against the element across —
/// a fresh crack starts closed, and opens, slides or closes again as its contacts decide.
/// `cohesive` (a rock that can break has a fracture energy): the new faces' entries soften
/// (cohesive_law.h), and each face edge's end vertex gets one as well as its start.
std::vector<ContactHistory> transfer_history(const std::vector<ContactHistory>& history, const Mesh& old,
                                             const Mesh& now, const pre::RecutMap& map,
                                             std::size_t first_new_joint, bool cohesive = false);

}  // namespace nmm::solve
