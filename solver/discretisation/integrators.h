// The step's integrators, one per term: the kernels a Form (form.h) walks to assemble the system.
// Each integrates exactly over the element polygon in the step's configuration
// (configuration.h, element_integration.h) and has its order-0 fast path inside: at cover order
// n = 0 the element is constant strain and the terms take the first-order code's closed forms
// (and its round-off), overloaded on the 6×6 element matrix; at n ≥ 1 the polynomial shape
// functions φ_a (cover_space.h), with B_{a,s} = Σ_i ∂_iφ_a·E_{s,i} (E picks the strain row:
// u_x → εxx, u_y → γxy, v_x → γxy, v_y → εyy):
//
//   elasticity      K(2a+s, 2b+t) += Σ_ij D(r(s,i), r(t,j)) ∫ ∂_iφ_a ∂_jφ_b dA    (n = 0: A BᵀDB)
//   initial stress  F(2a+s) −= Σ_i ∫ ∂_iφ_a σ_r(s,i) dA      σ of degree n        (n = 0: A Bᵀσ)
//   body force      F(2a+s) += ρ b_s ∫ φ_a dA                b = g − a_base(t)
//   inertia         K += c_d M,  F += M (c_v v0 + c_a a0),  M(a, b) = ρ ∫ φ_a φ_b dA per direction
//                   (Newmark: c_d = 1/(βΔt²), c_v = 1/(βΔt), c_a = 1/(2β) − 1; newmark.h)
//   fixed point     K += k_f φφᵀ,  F −= k_f φ (p − P)       penalty spring back to where it started
//   point load      F += φ(p) f(t)
//   edges           supports, tractions, water on joint faces, in-situ traction of faces between
//                   bodies (the edge integrals are boundary_conditions.h's)
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "solver/discretisation/configuration.h"
#include "solver/discretisation/elasticity.h"
#include "solver/discretisation/element_integration.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/newmark.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/system_matrix.h"

namespace nmm::solve {

/// What the element integrators need of one element in the step's configuration.
struct ElementGeometry {
  int order = 0;
  // n = 0
  const ElementFrame* frame = nullptr;
  PolygonMoments pm;  ///< moments of the polygon about the frame's origin
  Mat36 B;            ///< constant strain matrix of the frame's weights
  // n ≥ 1
  const ElementBasis* basis = nullptr;  ///< the configuration's scratch: valid until its next call
  MonomialMoments m;                    ///< monomial moments up to degree 2n + 2
};

/// The geometry of element e (loop_xy: the current loop vertices, m).
ElementGeometry element_geometry(const Configuration& config, const Mesh& mesh,
                                 const std::vector<double>& loop_xy, std::size_t e);

/// m/s², the body force per unit mass at time t: gravity, and −a_base(t) for a shaken base (the
/// model moves relative to its base, which the supports and fixed points hold).
std::array<double, 2> body_force_per_mass(const SceneDef& scene, double t);

namespace integrators {

/// Each kernel adds its term into the element's k (N/m) and f (N), which the form starts at zero.

/// k += the elasticity matrix.
void elasticity(const ElementGeometry& g, const Mat3& D, Mat6& k);
void elasticity(const ElementGeometry& g, const Mat3& D, Eigen::MatrixXd& k);
/// f −= ∫ Bᵀσ dA; sigma: the element's [3·T] stress coefficients, Pa.
void initial_stress(const ElementGeometry& g, const double* sigma, Vec6& f);
void initial_stress(const ElementGeometry& g, const double* sigma, Eigen::VectorXd& f);
/// f += ρ b ∫ φ dA; b in m/s².
void body_force(const ElementGeometry& g, double rho, double bx, double by, Vec6& f);
void body_force(const ElementGeometry& g, double rho, double bx, double by, Eigen::VectorXd& f);
/// k += c_d M, f += M (c_v v0 + c_a a0): covers ec (the element's three), dpc unknowns per cover,
/// v0 and a0 per cover ([dpc·c], the state's).
void inertia(const ElementGeometry& g, double rho, const InertiaCoefficients& c, const std::int32_t* ec,
             const RunState& s, Mat6& k, Vec6& f);
void inertia(const ElementGeometry& g, double rho, const InertiaCoefficients& c, const std::int32_t* ec,
             const RunState& s, int terms, Eigen::MatrixXd& k, Eigen::VectorXd& f);

}  // namespace integrators

/// The edge frame of element e: its basis in the configuration's scratch (valid until the next
/// call), and a Gauss rule exact for the shape functions (degree n + 1) and the linear field.
EdgeFrame edge_frame(const Configuration& config, std::int32_t e);
/// rhs += factor·f (N) over element e's unknowns.
void add_edge_force(const CoverSpace& space, std::int32_t e, const std::vector<double>& f, double factor,
                    Eigen::VectorXd& rhs);

// The point and edge terms, each into the system's element groups and rhs (N); `removed`: [me] 1
// for excavated elements, whose edges carry nothing; t_end: s, the step's end (load tables,
// moving supports).

/// The fixed points' penalty springs back to where they started.
void fixed_point_terms(const Model& model, const Configuration& config, const RunState& s,
                       SystemMatrix& system, Eigen::VectorXd& rhs);
/// The point loads at t_end.
void point_load_terms(const Model& model, const Configuration& config, const RunState& s, double t_end,
                      Eigen::VectorXd& rhs);
/// The supports' penalty springs (moving supports: the displacement less velocity·t_end) and,
/// with an in-situ stress, its locked-in reaction in their held directions.
void support_terms(const Model& model, const Configuration& config, const RunState& s,
                   const std::vector<std::uint8_t>& removed, double t_end, SystemMatrix& system,
                   Eigen::VectorXd& rhs);
/// The tractions at t_end (given, or the in-situ field's σ·n).
void traction_terms(const Model& model, const Configuration& config, const RunState& s,
                    const std::vector<std::uint8_t>& removed, double t_end, Eigen::VectorXd& rhs);
/// Water pressure on the joint faces (joint_water.h).
void water_terms(const Model& model, const Configuration& config, const RunState& s,
                 const std::vector<std::uint8_t>& removed, Eigen::VectorXd& rhs);
/// The locked-in in-situ traction of faces between bodies, released after an excavation
/// (excavation.h).
void interface_traction_terms(const Model& model, const Configuration& config, const RunState& s,
                              const std::vector<std::uint8_t>& removed, Eigen::VectorXd& rhs);

}  // namespace nmm::solve
