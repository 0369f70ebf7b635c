// Whether a crack tip crosses elements that hold on its way to a stop (docs/fracture.md "The
// rule", 6–8: a re-armed crack's tips, and a tip reaching for an element in line ahead of it).
//
// At cover order 0 a crack that has not parted its elements (crack_parting.h) carries no jump:
// the stress round it is the uncracked rock's, and the element ahead of its tip averages the tip's
// concentration away, so "ahead holds" does not say the crack is arrested. What the element's own
// stress does say is whether the rock there would open along the crack's line at all. With t the
// unit direction the tip grows in, n = (−t_y, t_x) the normal of its line and σ the element's own
// stress (tension positive), a straight crack ending there has K_I ∝ σ_nn = nᵀσn, so the line
// ahead is pulled open where
//     σ_nn > 0.
// A tensile crack crosses holding elements only as a rock bridge: straight on through at most
// kBridgeElements of them, each pulled open so, to where the line reaches a joint or a crack
// face or an element beyond its strength, between joints only (below). A bridge that is shut
// across, or that the crack would have to cross more elements of rock to link, stays whole. A
// shear crack crosses none: in a compressed specimen nearly every line slides past the intact
// rock's friction once its cohesion is left out, and bridges on |τ| > tanφ·⟨−σ_nn⟩ linked
// everywhere (fracture_matrix uniaxial.h1.dynamic.fast, Haswell: 908 segments and 48 s of CPU
// against 409 and 4.4 s before re-arming; tensile bridges only: 415 and 6.4 s).
//
// Measured on data/brazilian_disc.json (2026-11-29): with the crossings unchecked (one holding
// element a re-solve, wherever the driving element stayed beyond its strength) the split set off
// 1,934 crossings, most of them through rock squeezed across the crack's line (σ_nn down to
// −3·σt beside the flats) or barely pulled (253 of 407 under 0.2·σt): 559 segments against 86
// before re-arming. With the bridge rule: 105 segments.
//
// Only a bridge between joints (2026-11-29): the tip's crack, or the joint or crack face the line
// reaches, must be tied to a scene joint — a crack grown from a joint's end, or one with an end on
// a scene joint or on a crack so tied (jointed_cracks below) — and the line must reach a joint or
// a crack face, or, from a jointed crack, an element beyond its strength; never a body boundary.
// The rock bridges of a step-path slope link joint to joint so; the notched beam's ligament, the
// discs' flats and the compression specimens have no scene joint, and there the rules cross no
// holding rock (measured with the bridges to any stop: a crack beside the beam's slot linked to the
// slot's face through two holding elements at ratio 1.0005, and the two kernel families' peaks
// parted, 101.4 / 90.2 kN/m at h 0.025 m dynamic slow, 28 / 47 segments; the disc between platens
// stopped on a contact at h D/20, dynamic slow).
#pragma once

#include <cstdint>
#include <vector>

#include "common/scene/bodies_and_joints.h"
#include "common/vec2.h"

namespace nmm::solve {

/// Holding elements a tip crosses at most to link its crack to a stop (above).
inline constexpr int kBridgeElements = 3;

/// True when σxx, σyy, σxy (Pa, tension positive), the stress of an element ahead of a tip that
/// grows along the unit vector `along`, pulls the line ahead open: σ_nn = nᵀσn > 0, n = (−t_y, t_x).
bool pulls_line_open(double sxx, double syy, double sxy, const Vec2& along);

/// [crack id] 1 where the crack is tied to a scene joint: one of its segments (ends `a`, `b`, id
/// `crack`, as cut) has an end within `tol` (m) of one of the first `scene_joints` joints'
/// polylines, or of a segment of a crack so tied (to a fixed point). Segments of id −1 (grown
/// from a joint's own end) are tied; ids run from 0 to `cracks` − 1.
std::vector<std::uint8_t> jointed_cracks(const std::vector<JointDef>& joints, std::size_t scene_joints,
                                         const std::vector<Vec2>& a, const std::vector<Vec2>& b,
                                         const std::vector<std::int32_t>& crack, int cracks, double tol);

}  // namespace nmm::solve
