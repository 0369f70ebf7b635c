// A manifold element's geometry as cracks need it: the map from the mesh as cut (the reference
// configuration, where cracks are cut: preprocess/recut.h) to the element's current place, and
// rays through its reference loop.
//
// At cover order 0 an element moves affinely: every step moves its loop vertices by the linear
// weights of its triangle on its covers' node displacements (state_update.cpp), so a point X of
// the element as cut is now at
//     x(X) = Σ_k λ_k(X) · c_k,
// λ the barycentric coordinates of X in the element's mathematical triangle (as cut) and c_k the
// current nodes of the element's three covers (RunState::cover_xy). A direction D as cut maps to
// d = A·D, A = [c1 − c0, c2 − c0]·[N1 − N0, N2 − N0]⁻¹ (N: the triangle's nodes as cut).
//
// At cover order n ≥ 1 the displacement in an element is a polynomial of degree n + 1 and its
// covers' nodes no longer fix it; what the run tracks exactly is where the element's loop
// vertices are (state_update.cpp moves each by the element's shape functions). A point on an
// edge of the loop as cut then goes to the same fraction of that edge where it is now, so the
// elements either side of an edge put a crack's vertex at one place; any other point, and a
// direction, go by the affine map that fits the loop as cut to the loop now (least squares over
// its vertices X_i → x_i, exact for a triangle):
//     A = [Σ (x_i − x̄)(X_i − X̄)ᵀ]·[Σ (X_i − X̄)(X_i − X̄)ᵀ]⁻¹,   x(X) = x̄ + A·(X − X̄),
// which differs from the element's own map by O(h²·|∇²u|), a strain gradient's share of the
// displacement across the element.
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "common/vec2.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// x(X): where the point X of element e as cut is now, in the run state s of cover order
/// `order` (order 0: by its covers' current nodes s.cover_xy; n ≥ 1: by its loop, s.loop_xy).
Vec2 current_point(const Mesh& mesh, const RunState& s, int order, std::size_t e, const Vec2& X);

/// The unit direction as cut of the current direction d in element e (A⁻¹·d, normalised).
Vec2 direction_as_cut(const Mesh& mesh, const RunState& s, int order, std::size_t e, const Vec2& d);

/// Where the ray from p along d (unit) first leaves element e's loop as cut, beyond t_min (m):
/// the point, its distance t, and the loop vertex starting the edge it leaves through. False when
/// it never leaves beyond t_min.
struct RayExit {
  Vec2 at;
  double t = 0;
  std::int32_t edge = -1;  ///< global loop vertex v of the edge v → next
};
bool ray_exit(const Mesh& mesh, std::size_t e, const Vec2& p, const Vec2& d, double t_min, RayExit& out);

/// A point inside element e's loop as cut: its centroid if that lies inside, else a point a
/// little inside the middle of its longest edge.
Vec2 inside_point(const Mesh& mesh, std::size_t e);

/// The element among `candidates` whose loop as cut holds p, or -1.
std::int32_t element_holding(const Mesh& mesh, const std::vector<std::int32_t>& candidates, const Vec2& p);

}  // namespace nmm::solve
