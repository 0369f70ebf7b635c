// Where a new crack may start in rock that softens (docs/fracture.md "Cohesive softening",
// "Where a cohesive crack may start"): the strength check of Fracture::find (rule 2) narrowed by
// what a softening crack does to the rock round it.
//
// A cohesive crack relieves the rock only as it opens: its new faces carry σt, so the step that
// started it leaves every other element where the step's load put it. In a member at uniform
// stress the elements' stresses scatter by 2–3 % about their mean, and within the next few steps
// (the bar's section unloads by about 1 % per µm of travel once its crack softens) elements
// beside the crack were beyond σt while it unloaded them, and each started a crack of its own,
// as many as the step's overshoot and the scatter allowed (the cohesive bar: 7–9 cracks, the
// number following the step). Three rules, in the materials with a fracture energy only:
//   1. at most one new crack a step: the step is solved again with it (time_stepper.cpp), and
//      the next crack is decided on the next step's state, in which the first one had a whole
//      step to soften and relieve the rest;
//   2. only an element that is loading starts a crack: its strength ratio at the step's
//      solution exceeds the one at the step's (accepted) start. An element that unloads while
//      it is beyond its strength is being relieved by a crack that softens;
//   3. no new crack in an element bordering a face of a crack of the run: the face is a plane
//      of the element's rock that is at or past its peak already, and the normal traction it
//      carries bounds the element's stress across it; a second crack beside it, less than an
//      element away, is the same failure twice. Its tips may still grow (rules 1, 4, 5 of
//      fracture.h).
// Growth of a crack's tips is not touched; nor are runs without a fracture energy (bit for bit).
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// [me] 1: element e of `mesh` may start a new crack at the step's solution `solved` (rules
/// 1–3 above for elements of a material with a fracture energy; 1 for every other element).
/// `start`: the step's accepted start carried onto `mesh`; `started_this_step`: a new crack
/// already started in this step; `first_crack`: the scene joint index of the run's first crack
/// segment. Empty where no material has a fracture energy.
std::vector<std::uint8_t> cohesive_starts(const Mesh& mesh, const SceneDef& scene, const RunState& start,
                                          const RunState& solved, bool started_this_step, std::size_t first_crack);

}  // namespace nmm::solve
