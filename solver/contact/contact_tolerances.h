// The tolerances of contact detection and of the contact springs, in one place with the reason
// for each. Lengths are relative to the mesh size h (what the geometry of one element
// is measured in) or to the model half-size w0 (Shi's scale for displacements and gaps); the
// rest are cosines and fractions. The convergence tolerances of the step's contact problem
// (residual, friction fixed point) belong to the solve: solver/contact/contact_solve.cpp.
#pragma once

namespace nmm::solve {

struct ContactTolerances {
  // ---- Detection (contact_detection.cpp) ------------------------------------------------
  /// ×h, the deepest a new contact may start: a vertex missed for one step. A vertex deeper
  /// inside another element without having come in through a contact is near that edge from the
  /// wrong side (e.g. a corner of a block near the far side of the same block).
  double new_depth = 1e-3;
  /// ×h, the deepest a vertex that was closed against that block may be and still keep its
  /// contact, and never deeper than the search distance d0 (penetration is limited to g2·w0 per
  /// step, below d0 = 2.5·g2·w0: both are beyond any accepted one; detection's Verlet list holds
  /// no edge farther than d0 plus its margin).
  double closed_depth = 0.3;
  /// –, and at most this fraction of how far element B and the elements of its block around it
  /// (sharing a mesh node with B: a sliver's neighbours too) reach behind the edge (the largest
  /// depth of their vertices below the edge's line). A full triangle reaches 0.87·h behind each
  /// edge, so 0.35 of it is above closed_depth·h and this bites only where B's block is smaller
  /// than a triangle behind the edge — a mesh coarser than the blocks, where 0.3·h can exceed a
  /// brick's height and a corner closed against a brick's side would otherwise be taken as 0.5 m
  /// deep below its top face (a 20 × 20 wall at h = 2 m then cut Δt below its floor).
  double closed_extent = 0.35;
  /// ×h, how deep a vertex on the upward (master) side of a flat stretch must poke into the other
  /// side before it too is held: beyond what a spring lets a face sink under any load, so faces
  /// pressed together carry one set of contacts (2·Vm is added for Bandis–Barton joints).
  double master_depth = 1e-4;
  /// ×h, a vertex that sank through an edge at a mesh node may be found in the element below the
  /// node (which does not own the edge) only this shallow, and only near an end of the edge
  /// (ω below node_sink_omega or above 1 − node_sink_omega).
  double node_sink_depth = 0.05;
  double node_sink_omega = 0.25;  ///< –
  /// –, detection's Verlet list holds the edges within this many times the search need (the
  /// search distance d0 plus beside_edge·h) of each vertex, and is reused while no vertex has
  /// moved more than half the difference: at 2, half of d0 = 1.25·g2·w0, more than a settling
  /// wall moves in many steps, and about 2–4 edges per vertex on a brick wall.
  double list_reach = 2.0;
  /// –, how far past the ends of an edge (in ω) a vertex still lies beside it: a vertex right
  /// above a vertex of the other face projects onto both neighbouring edges at ω ≈ 0 or 1, and
  /// round-off must not push it off the one whose element holds it.
  double beside_edge = 1e-3;
  /// ×h, round-off of a gap computed from coordinates of size h: below it a vertex counts as
  /// touching (not inside), and two edges at gaps within it are equally near.
  double gap_round_off = 1e-9;
  /// ×h, an edge shorter than this has no direction (a degenerate loop edge): skipped.
  double degenerate_edge = 1e-12;
  /// –, the edge must face P: the cosine between the edge's normal and P's own normal below
  /// this (about 100° apart), so a vertex never contacts an edge it is beside but not facing.
  double facing_cos = -0.2;
  /// –, two candidate edges whose facing cosines differ by less are tied (then the lower index).
  double facing_tie = 1e-12;
  /// –, P's mean normal shorter than this: the tip of a slit (both faces are its own element's).
  double slit_tip_normal = 1e-9;
  /// ×h, two vertices this close are one point: the two faces of a joint at one of its points
  /// (one contact, not two), and the angle–angle rule.
  double same_point = 1e-2;
  /// degrees, two candidate edges at a boundary point turning by less make a flat stretch (its
  /// vertex is no corner): mesh lines cutting a straight boundary or joint.
  double flat_turn_deg = 10;
  /// –, two edge directions with a cosine above 1 − this are the same edge seen from both ends'
  /// elements; two weights within it are equal (continuity of a vertex with an element).
  double same_direction = 1e-9;
  double same_weight = 1e-9;

  // ---- Springs (contact_problem.cpp) ---------------------------------------------------------------
  /// ×w0, a closed contact whose gap at the start of a step is above this has separated and
  /// starts the step open (kept closed, its spring would pull the faces together: glue).
  double open_gap = 1e-10;
  /// ×w0, τ: the normal spring's closure is smoothed over ±τ around touching so force and
  /// tangent are continuous (a contact touching with no force does not switch kn on and off with
  /// round-off); its force at touching, kn·τ/4, is far below any load.
  double skin = 1e-12;
  /// –, a candidate edge at P adds half its length to P's tributary length only if its normal
  /// is opposed to the contacted edge's by a cosine below this (about 134°): a corner's other
  /// side is not on this joint.
  double tributary_cos = -0.7;
  /// ×h, the tributary length of a bare corner (no edge at P faces the contacted one): a point.
  double corner_length = 1e-3;
  /// –, a contact that slid into this step and whose shear force is within this fraction below
  /// its strength (round-off: the return mapping left it exactly at the limit) takes the slip
  /// branch's tangent 0 at the kink, not the stick branch's ks: the shear energy has no second
  /// derivative there and either one-sided one gives a descent direction, but picking "stick" by
  /// round-off put ~18 springs per step into the Newton matrix that the first iteration took out
  /// again (20 × 20 brick wall), each a rank in H − P the factorisation cannot reuse.
  double slip_kink = 1e-9;
  /// –, a hyperbolic shear law (Rf = 1) only approaches its strength: a trial force at this
  /// fraction of it counts as sliding.
  double hyperbola_slip = 0.999;
  /// –, a shear strength moving by less than this fraction within a step is settled (the friction
  /// fixed point), and a shear force within near_limit of the strength is at the limit, where a
  /// change of strength matters.
  double strength_change = 1e-3;
  double near_limit = 0.99;
};

/// The tolerances every contact of a run uses.
inline constexpr ContactTolerances kContactTolerances{};

}  // namespace nmm::solve
