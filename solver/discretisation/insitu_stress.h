// In-situ stress (scene key "insitu_stress"), put into every element before step 1:
//
//   σ(x, y) = σ0 + (y_ref − y)·gradient      (σxx, σyy, σxy; Pa, tension positive)
//
// or the overburden shortcut {k0, y_ref, density, syy, g}: σyy = syy − ρ·g·(y_ref − y),
// σxx = k0·σyy, σxy = 0 (common/scene/insitu_stress.cpp turns it into σ0 and the gradient).
//
// Cover order n = 0: each element takes the field at its centroid. Its stress is constant
// (constant strain elements) and B is constant, so ∫ Bᵀσ dA over the element equals
// A·Bᵀσ(centroid) exactly for the linear field: the internal forces are those of the exact field.
// Cover order n ≥ 1: the element's stress is a polynomial of degree n in its scaled coordinates
// (ξ, η) = (x − o)/h about its first cover's node o (cover_space.h, time_stepper.h); the field is
// linear, so its coefficients hold it exactly:
//   σ(ξ, η) = [σ0 + (y_ref − o_y)·gradient]·1 + 0·ξ − h·gradient·η   (higher terms 0)
// and the internal force ∫ Bᵀσ dA is integrated exactly (element_integration.h).
// Boundary tractions t = σ·n on every face (tractions with "from_insitu": true) and, for a
// gradient, gravity with ρ·g = −∂σyy/∂y balance them cover by cover at every order:
//   ∫ Bᵀσ dA = ∮ Nᵀ σ·n ds − ∫ Nᵀ div σ dA
// is exact for polynomial shape functions N and linear σ, the edge integrals are exact Gauss
// rules (boundary_conditions.h), and the edges inside a body cancel (N is continuous there), so
// such a model does not move at t = 0.
//
// Supports carry the field's reaction σ·n in their held directions from the start (locked in,
// integrators.cpp support_terms), so a model on rollers needs no first movement to load them.
// Faces where two bodies touch carry t = σ_insitu·n on both sides as a locked-in interface
// traction (contacts start with no force; UDEC likewise initialises its contact stresses from
// the in-situ field), so touching bodies start in equilibrium too. Excavation releases it
// (excavation.h). Joints inside a body get no such initial force: their springs take up the
// in-situ stress during the first (consolidation) steps, closing by σ·l/kn.
#pragma once

#include <array>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::solve {

/// σxx, σyy, σxy at (x, y), Pa.
std::array<double, 3> insitu_stress_at(const InsituStressDef& s, double x, double y);

/// Sets the stress of every element to the field, in the mesh as cut. `order` is the cover
/// order n; stress holds 3·T values per element, T = (n+1)(n+2)/2 polynomial coefficients
/// (stress[3·(T·e + t) + r], r = σxx, σyy, σxy). n = 0: the field at the element's centroid;
/// n ≥ 1: the field's exact coefficients in the element's frame scaled by `scale` (m, the
/// cover space's h).
void apply_insitu_stress(const InsituStressDef& s, const Mesh& mesh, int order, double scale,
                         std::vector<double>& stress);

}  // namespace nmm::solve
