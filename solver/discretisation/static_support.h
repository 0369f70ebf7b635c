// Whether a step's system is held: a system without inertia (static_mode "equilibrium", or a
// static run without contacts) is singular unless every block is held, and a factorisation
// that fails names the cover left free. Both say so in one line a rock engineer can act
// on (which block or cover, where, and what to add).
//
//   held(b) = (fixed points in block b) + 2·(support edges on block b)
//   a block is held when held(b) ≥ 2: one point still lets it turn about that point; a support
//   along an edge holds what two points would (the system says so if it does not)
// In a run that can crack, a block a crack cut off a held body is a free piece (free_pieces) and
// takes DDA's static inertia instead of stopping the run.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// [block] held(b) above: fixed points in the block plus twice its support edges.
std::vector<int> block_holds(const Model& model, const RunState& s);

/// [me] 1: the element belongs to a free piece — a block held by fewer than two fixed points or
/// supports (held(b) < 2) of a body that some other block of it holds, in a run that can crack
/// (a fracture block and a strength) and takes no inertia in its steps (static_mode
/// "equilibrium"): a piece a crack cut off a held body. Such a piece has no support, and its
/// contacts may open, so K d = F is singular on its covers; it takes DDA's static inertia
/// 2M/Δt² in the step instead (form.cpp), from rest: a free piece under an out-of-balance force
/// F moves ½(F/m)·Δt² in a step, as in DDA's static analysis, and one held by closed contacts
/// settles onto them over steps. Empty where there is none.
std::vector<std::uint8_t> free_pieces(const Model& model, const RunState& s);

/// Why the system is singular, naming the first block of a body still there (s.body_removed)
/// held by fewer than two fixed points (s.fixed) or supports (model.support_edges()); "" when
/// every block is held.
std::string unheld_block(const Model& model, const RunState& s);

/// Why a factorisation failed at unknown `failed_unknown` (-1: not known): the cover and its
/// node, its elements and support, unconstrained.
std::string not_positive_definite_message(const Mesh& mesh, const CoverSpace& space,
                                          int failed_unknown);

/// m², the area of physical cover `cover`'s support (its elements'); `elements`: how many.
double cover_support(const Mesh& mesh, int cover, int& elements);

}  // namespace nmm::solve
