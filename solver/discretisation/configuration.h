// The configuration of a step: the approximation space (cover_space.h) placed on the covers'
// current positions. Each element's frame is its triangle of cover nodes x_c0, x_c1, x_c2 (each
// cover's own node, also for a tied cover: its weight function is its own), with origin x_c0,
// and the linear weights w_k of that triangle (element_integration.h); its basis multiplies
// them by the cover polynomials, centred on each cover's master node (cover_space.h):
//   φ_(k,j)(x) = w_k(x) · p_j((x − x_m(k)) / h)        order n = 0: φ_k = w_k
// One object for what the step assembles and updates with, the contacts linearise with and the
// energy meter integrates with.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/element_integration.h"
#include "common/mesh.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

/// The element's triangle in the configuration at the start of a step.
struct ElementFrame {
  double ox = 0, oy = 0;  ///< m, origin: the node of its first cover
  TriangleWeights w;      ///< weights relative to (ox, oy)
};

class Configuration {
 public:
  Configuration() = default;
  /// `space` may be null where only frames are wanted (basis() then may not be called); both
  /// must outlive the configuration.
  Configuration(const Mesh& mesh, const CoverSpace* space);

  /// Places every element's frame on the cover nodes cover_xy ([2·c] m). Returns the first
  /// element whose triangle has folded over (twice its area not > 0), or -1.
  std::int64_t place(const std::vector<double>& cover_xy);
  /// The first element whose triangle the increment d (the space's unknowns) would fold over if
  /// the step were accepted: place() on the cover nodes moved as move_cover_nodes() moves them,
  /// with place()'s own arithmetic, so a step this passes starts the next attempt unfolded. -1 if
  /// none. Step control rejects such a step (step_control.h) instead of the next one stopping.
  std::int64_t folded_by(const Eigen::VectorXd& d) const;

  const ElementFrame& frame(std::size_t e) const { return frame_[e]; }
  /// The shape functions of element e in its frame, in a scratch object reused by the next call
  /// (no allocation per element).
  const ElementBasis& basis(std::size_t e) const;
  /// The element's shape function values at (x, y) (m) into out[0 .. element_dofs()/2): the
  /// weights themselves at order 0 (with the first-order code's round-off).
  void shape_values(std::size_t e, double x, double y, double* out) const;
  const CoverSpace& space() const { return *space_; }

  /// Moves tracked points by the displacement increment d (the space's unknowns) of their
  /// element, evaluated in this configuration.
  void move_points(const Eigen::VectorXd& d, std::vector<TrackedPoint>& points) const;
  /// Moves the cover nodes cover_xy ([2·c] m, the positions place() was given) by their cover
  /// function at the node: its constant term for an untied cover (the basis is centred there); a
  /// tied cover evaluates its master's polynomial.
  void move_cover_nodes(const Eigen::VectorXd& d, std::vector<double>& cover_xy) const;

 private:
  const Mesh* mesh_ = nullptr;
  const CoverSpace* space_ = nullptr;
  std::vector<double> cover_xy_;   // [2·c] m, the cover nodes place() was given
  std::vector<ElementFrame> frame_;  // [me]
  mutable ElementBasis scratch_;   // basis()'s result
};

}  // namespace nmm::solve
