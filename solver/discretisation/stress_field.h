// The stress field of a run state. Element e carries σ (σxx σyy τxy, Pa) as a polynomial of
// degree n (the cover order) in the scaled coordinates ξ = (x − x_c0)/h, η = (y − y_c0)/h about
// its first cover's node x_c0 where that node is now (h: the space's scale, cover_space.h):
//   σ_e(x) = Σ_t s_{e,t} ξ^p_t η^q_t,    t < T = (n+1)(n+2)/2
//   mean   σ̄_e = ∫_e σ dA / A_e = Σ_t s_{e,t} M_t / M_0   (M_t the element's monomial moments)
// At n = 0 the stress is the element's constant stress and its mean is itself.
#pragma once

#include <array>
#include <vector>

#include "solver/discretisation/cover_space.h"
#include "common/mesh.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// [3·me] Pa, the mean stress of each element.
std::vector<double> mean_stress(const Mesh& mesh, const CoverSpace& space, const RunState& s);
/// The same for a run of cover order `order` (its bases scaled by basis_scale(mesh)): for code
/// that holds the mesh and the state but not the space (fracturing).
std::vector<double> mean_stress(const Mesh& mesh, int order, const RunState& s);

/// Pa, σxx σyy τxy of element e at the point (x, y) (m) of the state's configuration.
std::array<double, 3> stress_at(const Mesh& mesh, const CoverSpace& space, const RunState& s,
                                std::size_t e, double x, double y);
/// The same for a run of cover order `order` (bases scaled by basis_scale(mesh)), as mean_stress.
std::array<double, 3> stress_at(const Mesh& mesh, int order, const RunState& s, std::size_t e, double x, double y);

}  // namespace nmm::solve
