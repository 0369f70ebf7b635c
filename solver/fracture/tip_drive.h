// Whether a crack tip crosses elements that hold on its way to a stop (docs/fracture.md "The
// rule", 6 and 7: a re-armed crack's tips, and a tip reaching for an element in line ahead of it).
//
// At cover order 0 a crack that has not parted its elements (crack_parting.h) carries no jump:
// the stress round it is the uncracked rock's, and the element ahead of its tip averages the tip's
// concentration away, so "ahead holds" does not say the crack is arrested. What the element's own
// stress does say is whether the rock there would open (or slide) along the crack's line at all.
// With t the unit direction the tip grows in, n = (−t_y, t_x) the normal of its line and σ the
// element's own stress (tension positive),
//     σ_nn = nᵀσn,   τ = tᵀσn;
// a straight crack ending there has K_I ∝ σ_nn and an effective K_II ∝ |τ| − tanφ·⟨−σ_nn⟩ (the
// intact rock's friction on the closed line). So the line ahead is driven
//     tensile:  σ_nn > 0                               (pulled open across it)
//     shear:    |τ| > tanφ·max(−σ_nn, 0)               (would slide)
// and a tip crosses holding elements only as a rock bridge: straight on through at most
// kBridgeElements of them, each driven so, to where the line reaches a stop (a body boundary, a
// joint or a crack face) or an element beyond its strength. A bridge that is shut across, or that
// a crack would have to cross more elements of rock to link, stays whole.
//
// Measured on data/brazilian_disc.json (2026-11-29): with the crossings unchecked (one holding
// element a re-solve, wherever the driving element stayed beyond its strength) the split set off
// 1,934 crossings, most of them through rock squeezed across the crack's line (σ_nn down to
// −3·σt beside the flats) or barely pulled (253 of 407 under 0.2·σt): 559 segments against 86
// before re-arming. With the bridge rule: 105 segments.
#pragma once

#include "common/scene.h"
#include "common/vec2.h"
#include "solver/fracture/rock_strength.h"

namespace nmm::solve {

/// Elements that hold a tip crosses at most to link its crack to a stop (above).
inline constexpr int kBridgeElements = 3;

/// True when σxx, σyy, σxy (Pa, tension positive), the stress of an element ahead of a tip that
/// grows along the unit vector `along`, drives the line ahead in `mode` (above).
bool drives_line_ahead(const StrengthDef& strength, double sxx, double syy, double sxy, const Vec2& along,
                       CrackMode mode);

}  // namespace nmm::solve
