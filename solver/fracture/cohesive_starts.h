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
// number following the step). The rules, in the materials with a fracture energy only:
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
//   4. an element in the band ahead of an active tip is that crack's (Fracture::find): where
//      it is beyond its strength, loading and not beside a face, the tip grows to its level
//      straight on, across the elements between that hold, instead of a second crack starting
//      beside the first (also in a step that started a crack already: it is growth), and the
//      element is disarmed as a crossed one is (its failure is that crack's). The band:
//      the element meets the strip of half-width h/2 about the tip's line (a crack laid anywhere
//      within its own element's width would cross it: at cover order 0 the crack's place across
//      its line is known to an element, Bažant & Oh's crack band), and its centroid lies ahead
//      of the tip within Hillerborg's l_ch = E·G_f/σt² (the order of a cohesive process zone's
//      length). Crossing rock that holds is what a cohesive crack may do and a brittle one may
//      not: faces cut through rock below its strength carry its stress at once on their elastic
//      branch (w = σ/kn ≤ w_e, 0.1 µm in the bar), so they change nothing until that rock would
//      break — an intrinsic cohesive interface laid ahead of the tip. Measured at h 0.05 m
//      (reference/cohesive_bar.h, Δt 1 ms, NMM_TRACE_CRACK_RULES=1): the first crack starts in
//      the top row at x 0.500 m (step 96, ratio 1.0074) and stops there, the elements below it
//      at 0.988; a step later the bottom row's clipped element at x 0.525 m (ratio 1.0021, the
//      cut elements along the bar's edges carry 1–3 % more than the inner ones) started a second
//      crack h/2 beside the first's line, a third started at x 0.475 m, and the section, cut by
//      three cracks over different heights, opened unevenly and bent the bar: its bottom row
//      then cracked an element a step at x 0.6–0.8 m (ratios 1.03–1.05).
//   5. no new crack in an element smaller than a debris block (Fracture::kDebrisArea·h², a
//      hundredth of an element): a sliver the body's boundary clips off a lattice triangle
//      takes its strain from covers whose stars lie mostly outside the body, and a crack
//      through it is a fraction of a millimetre long and relieves nothing (the bar at
//      h 0.025 m: its top edge passes 0.14 mm above a lattice row at x 0.5 m, and its first
//      three cracks started in slivers of 2e-4 of an element there, 0.27 mm long, one a step,
//      before any crack ran across it). It may still be reached by a tip (rule 4).
//   6. no new crack within Hillerborg's l_ch = E·G_f/σt² of a growing crack (one with an active
//      tip; its segments as cut, from the element's centroid). A cohesive crack's process zone
//      softens over a length of the order of l_ch, and while it softens it unloads the rock
//      about it: the crack band of Bažant & Oh (1983, "Crack band theory for fracture of
//      concrete") localises into one band for that reason, and smeared-crack codes that track
//      cracks enforce it as an exclusion radius about each crack inside which no new one starts
//      (Cervera, Pelà, Clemente & Roca 2010, "A crack-tracking technique for localized damage in
//      quasi-brittle materials"; Saloustros, Cervera & Pelà 2019). A crack that has started is the
//      one that fails: beyond its strength in the band ahead of its tip an element is its to
//      reach (rule 4), beside it one the softening crack will shield. Petersson's beam at
//      h 0.0125 m (docs/fracture.md): without it cracks started at both corners of the notch's
//      flat end and 17 mm either side while the tip's crack stayed one element long, a band 5 cm
//      wide; with it one crack runs up from the notch's tip.
//   7. no new crack in an element holding a physical cover that reaches round a gap of the body
//      (a slot, a notch narrower than h): a node's star reaches round the gap's end and stays one
//      cover (physical covers are the connected pieces of star ∩ body), so the pieces on both
//      sides take it and their constant strain carries the gap's opening as their own. Found
//      geometrically: two elements of the cover whose inside points see each other only across a
//      body boundary edge of the cover's elements. Their stress is the gap end's concentration
//      smeared over them, not the rock's: an element on a reflex corner of the outline (the
//      gap's end) keeps its start (kGapEnd), and a crack started there leaves from the gap's end
//      (its reflex corners within h of each other) along their bisector (gap_end), not along the
//      element's own σ1. It may still be reached by a tip. Petersson's beam (10 mm slot): at
//      h 0.025 and 0.0167 m the first crack started in such a piece beside a notch wall 10–30 mm
//      below the slot's end, and at h 0.025 m the end's own element cracked horizontally; now one
//      crack runs up from the slot's end at all three meshes. A tied piece beyond its strength
//      with a reflex corner within h of its vertices starts that crack too (kGapOnly: at the
//      gap's end or nowhere): the concentration it carries is the gap end's, and the end's own
//      element, wider than the slot, reached σt only at 24.2 kN/m at h 0.025 m (16.4 now; 14.9
//      and 14.2 kN/m at h 0.0167 and 0.0125 m). At cover order n ≥ 1 such an element is judged
//      by the stress at the point its crack would leave from (the middle of the gap's end), read
//      from the polynomial of the element there (stress_field.h stress_at), not by its mean: the
//      mean of an element h wide smears the end's concentration, and Petersson's beam at order 1,
//      h 0.025 m, started its crack at 0.273 mm, at its peak (19.63 kN/m, +15 % of the converged
//      17.09 kN/m of docs/cohesive_beam_reference.py); with the point at 0.191 mm.
//   8. a cohesive tip grows on where the rock at the tip has failed although the element ahead,
//      whose constant stress averages the tip's field over h, holds (Fracture::find, grow):
//      (a) a tip inside the star of a node whose cover the crack has not parted at an element
//      beyond its strength behind it (crack_parting.h: the faces cannot open over the crack's
//      last element, and that element carries the tip's concentration) crosses the holding
//      element ahead without a bridge; Petersson's beam at h 0.0167 m: a crack 1 cm long waited
//      140 steps, its own elements at 1.3–2.4 σt, the element ahead at 0.18 σt. Not into an
//      element shut across the tip's line (σ_nn ≤ 0): at cover order 1 (h 0.0167 m) the tip ran
//      through the compressed top to 1.3 mm below the top edge and the contact solve failed;
//      (b) the normal stress across the tip's line at the tip reaches σt: the tip crosses the
//      element ahead, one a solution. At cover order n ≥ 1 that stress is the element ahead's own
//      polynomial read at the tip (its field is linear or better); at order 0 it is recovered from
//      the two elements ahead on the line by linear extrapolation of their stresses (at their
//      inside points' distances) back to the tip. At order 1 the extrapolated means of two elements
//      held Petersson's beam at h 0.0167 m until 19.44 kN/m (+14 % of the converged 17.09); read
//      at the tip, 18.28 (docs/notes/2026-11-cohesive.md, beam50f).
//      A crack band element's stress is its band's mean (Bažant & Oh 1983); the tip of a
//      discrete cohesive crack advances where the stress at the tip reaches σt (Hillerborg,
//      Modéer & Petersson 1976), which the mean over an element ahead underestimates by its
//      gradient across h. A cohesive face cut through holding rock carries its stress on the
//      elastic branch (rule 4), so a tip one element early changes little.
//      (c) a tip whose element's own crack direction leaves that element at once (a tip on its
//      vertex) goes on straight (as rule 4's band tip did), instead of stopping for good.
//      (d) a tensile tip crosses an element that breaks along Erdogan & Sih's (1963) kink,
//      θ = 2·atan((σ_nn − √(σ_nn² + 8σ_tn²))/(4σ_tn)) from its line, σ_nn and σ_tn the element's
//      traction on the tip's line (in place of K_I and K_II), not normal to the element's σ1,
//      where the element is pulled open across the line (σ_nn > 0; one shut across it keeps its
//      own σ1 direction: holding the tip there instead raised Petersson's beam's work at order 0,
//      h 0.0167 m, from 11.22 to 14.02 J/m, its tip held 30 steps at y 0.148 m). σ1 is the direction a crack starts
//      in; a tip's kink is set by its opening and sliding, and the stress along its line (the
//      T-stress, positive along a deep crack in bending) does not turn it. Petersson's beam at cover
//      order 1, h 0.0125 m: the element ahead of the tip at y 0.162 m reached σt along the crack
//      (σyy 3.33 MPa, σxx across it 1.43, σxy 0) and the crack turned horizontal (step 575); at
//      order 0 the same at y 0.173 m (step 832).
//      (e) a tensile tip crosses the last holding element on its line, straight on to the body's
//      boundary, where that element is shut across the line (σ_nn ≤ 0) and its shear on the line
//      is under σt (β·σt, the least a closed face carries): faces cut through it close and carry
//      its compression by contact, so the cut changes nothing while that rock holds, and it takes
//      away a hinge an element wide. A bending member's compression zone shrinks towards a point
//      as its crack lets go (the converged beam's hinge is its top node,
//      docs/cohesive_beam_reference.py); an uncut element spans the crack's line and both halves'
//      covers, and turning them about it strains it. Petersson's beam at order 1, h 0.025 m: the
//      tip stopped at y 0.1949 m under the load strip (the element ahead at σ_nn −12 MPa, −8 MPa
//      at the tip), the load rose again from 1.47 kN/m at 2 mm to 2.93 at 4 mm while `fracture`
//      stayed 10.86 J/m and `strain` rose to 5.88 J/m, and at 4.2 mm the tip ran through in one
//      step (`fracture` 17.35 J/m, above G_f × ligament); with (e) it cuts to the top at step 801
//      (0.80 mm) and the load falls to 0.6 % of its peak at 6 mm, 12.46 J/m of load work.
// Runs without a fracture energy are not touched (bit for bit).
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "common/vec2.h"
#include "solver/discretisation/run_state.h"
#include "solver/fracture/fracture.h"

namespace nmm::solve {

/// Bits of cohesive_starts' answer for an element.
constexpr std::uint8_t kMayStart = 1;    ///< a new crack may start in it (rules 1–3, 5–7)
constexpr std::uint8_t kMayBeReached = 2;  ///< a tip may grow to it across rock that holds (rule 4: rules 2, 3)
constexpr std::uint8_t kGapEnd = 4;  ///< a crack started in it leaves from the gap's end (rule 7, gap_end)
constexpr std::uint8_t kGapOnly = 8;  ///< with kGapEnd: it starts a crack only there (rule 7: a piece tied round the gap)

/// [me] kMayStart | kMayBeReached bits: what element e of `mesh` may do at the step's solution
/// `solved` (rules above for elements of a material with a fracture energy; kMayStart alone for
/// every other element).
/// `start`: the step's accepted start carried onto `mesh`; `started_this_step`: a new crack
/// already started in this step; `first_crack`: the scene joint index of the run's first crack
/// segment; `cracks`: the segments of the growing cracks (Fracture::growing_segments, rule 6).
/// Empty where no material has a fracture energy.
std::vector<std::uint8_t> cohesive_starts(const Mesh& mesh, const SceneDef& scene, const RunState& start,
                                          const RunState& solved, bool started_this_step, std::size_t first_crack,
                                          const std::vector<CrackSegment>& cracks);

/// Rule 7: where a crack started in element e, which holds a reflex corner of the body's
/// outline (a notch's or slot's end), leaves from: `at` the mean of its corners, `dir` the unit
/// sum of their angles' bisectors into the body (a slot's flat end: along the slot). False where
/// e has no such corner.
bool gap_end(const Mesh& mesh, const SceneDef& scene, std::size_t e, Vec2& at, Vec2& dir);

/// Rule 4's band: element e meets the strip of half-width `half_width` (m) about the line
/// through `tip` along the unit `dir`, and the point a new crack in it would start from (its
/// centroid, element_geometry.h inside_point) lies ahead of `tip` along `dir` by more than 0 and
/// at most `reach` (m); `along` (m) is that distance.
bool in_crack_band(const Mesh& mesh, std::size_t e, const Vec2& tip, const Vec2& dir, double half_width, double reach,
                   double& along);

}  // namespace nmm::solve
