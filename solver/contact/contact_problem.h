// The step's contact problem: each contact of the step (ContactSet::contacts()) linearised on the
// unknowns of its two elements, the inner solve's working values, and the kernels of the convex
// minimisation that contact_solve.cpp iterates with (forces and tangents, line search, friction
// fixed point, breaking at the peak, the states the step ends in). Built by every attempt after
// ContactSet::begin_step(); read by ContactSet::end_step() when the step is accepted.
// Equations: contact_problem.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "solver/contact/contact.h"
#include "solver/contact/contact_set.h"
#include "solver/discretisation/configuration.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/system_matrix.h"

namespace nmm::solve {

/// The inner solve's working values of one contact: set by build(), assign_groups(),
/// start_strengths() and the Newton iterations, read by nothing after the step but end_step().
/// Kept apart from Contact (the step's rows and results, what output and the next step's history
/// read) as Box2D keeps its solver's constraints apart from its contacts: the solve's loops touch
/// only these and the rows.
struct ContactWork {
  double strength = 0;          ///< N, shear strength of the inner solve (tanφ·N + c·L, 0 if open)
  bool bonded = false;          ///< normal spring holds tension (unbroken, tensile strength, closed)
  double gap0 = 0, shear0 = 0;  ///< m, gap = gap0 + cnᵀd, shear = shear0 + csᵀd
  int group = -1;               ///< coupling group of its element pair in the system matrix
  double start_normal_force = 0;  ///< N, the normal force carried into the step (start_strengths())
  bool start_broken = false;    ///< broken at the start of the step (end_step() counts new breaks)
  double rate_gap = 0, rate_shear = 0;  ///< m per unit α, Δg and Δs of the line search direction
  // A new crack's face that still holds a cohesive traction (cohesive_law.h): its damage follows
  // each iterate's opening and slip, κ = max(κ at the step's start, λ), and is committed only with
  // the accepted step (commit()).
  const CohesiveLaw* cohesive = nullptr;  ///< its rock's law (null: not a softening face)
  double k_len = 0;   ///< Pa/m, the crack set's normal stiffness per unit length
  double slip = 0;    ///< m, plastic slip since the crack formed, at the last iterate
  double kappa = 0;   ///< m, damage at the last iterate
  double c_coh = 0;   ///< N, the softened shear cohesion c·factor(κ)·L, in the strength
  // A contact whose springs are straight lines (not a softening face; a constant or penalty
  // normal spring, a linear shear spring): the Newton kernels evaluate it inline from these
  // (contact_problem.cpp straight_normal, straight_shear), the same numbers as its law's.
  bool linear = false;
  double kn0 = 0;     ///< N/m, its normal spring (initial_normal_stiffness), when `linear`
  double ks0 = 0;     ///< N/m, its shear spring (initial_shear_stiffness), when `linear`
};

class ContactProblem {
 public:
  /// The problem of `contacts`' steps on `space`'s unknowns (both must outlive it).
  ContactProblem(ContactSet& contacts, const CoverSpace& space) : set_(contacts), space_(space) {}

  /// Steps without inertia (static_mode "equilibrium"): a block resting on contacts it has just
  /// met is held sideways only by their shear springs, which have no strength before the
  /// friction fixed point has a normal force. Touching contacts (gap ≤ 1e-10·w0 at the start of
  /// the step) that start open then stick in the first inner solve (an elastic predictor, as for a
  /// contact with unbounded strength); the fixed point gives them their real strength from its
  /// normal force. Without it the first solve of such a block is singular ("not positive
  /// definite"). With inertia (dynamic, DDA static) the mass holds the block: off.
  void set_elastic_predictor(bool on) { elastic_predictor_ = on; }

  // ---- the step's rows -----------------------------------------------------------------------
  /// Linearises each of the step's contacts with the shape functions of its two elements in the
  /// step's configuration `config` (configuration.h; loop vertices xy, model half-size w0), and
  /// resets the working values from what the contacts carry into the step.
  void build(const std::vector<double>& xy, const Configuration& config, double w0);
  /// Contact i's row: its unknowns (A's element unknowns, then B's), `size` of them, and the
  /// coefficients of its gap (cn) and slip (cs) on them: unknown 2a + s (shape value φ_a,
  /// direction s) has cn = φ_a·n_s and cs = φ_a·t_s, with B's shape values negated.
  struct Row {
    const int* dofs;
    const double* phi;  // [size / 2] φ_A,a(P) for A's shape functions, then −φ_B,a(P0) for B's
    double n[2], t[2];  // the edge's unit normal and tangent
    int size;
    double cn(int i) const { return phi[i >> 1] * n[i & 1]; }
    double cs(int i) const { return phi[i >> 1] * t[i & 1]; }
  };
  Row row(std::size_t i) const {
    const double tx = tangent_[2 * i], ty = tangent_[2 * i + 1];
    return {dofs_.data() + i * static_cast<std::size_t>(row_), phi_.data() + i * static_cast<std::size_t>(row_ / 2),
            {ty, -tx}, {tx, ty}, row_};
  }
  const ContactWork& work(std::size_t i) const { return work_[i]; }
  /// N, contact i's normal force at d = 0 on its law (its gap at the step's start, the joint's
  /// memory of the start): what its spring pushes with before the step moves anything. Non-zero
  /// for a contact found sunk at the start: the one closed at the last step's end (its force
  /// carried), or one that starts the step open but deep, with no force carried (energy.h; 0
  /// for a softening crack face, whose law has its own start).
  double normal_force_at_rest(std::size_t i) const;
  /// N, contact i's normal force at d = 0 by its law, a softening crack face's cohesive traction
  /// too (tension < 0): 0 where nothing holds it at the step's start.
  double law_force_at_rest(std::size_t i) const;
  /// N, contact i's shear force at d = 0: its spring at the elastic shear it starts with, on its
  /// length now, capped at its strength of the step's start (start_strengths()) — what the step
  /// starts from. 0 for one that starts open, and for a softening crack face (its cohesion has its
  /// own start).
  double shear_force_at_rest(std::size_t i) const;
  /// The step's contacts (ContactSet::contacts()), index-aligned with the rows.
  const std::vector<Contact>& contacts() const { return set_.contacts(); }
  /// Sets each contact's coupling group: first_group + the index of its pair in `pairs` (sorted),
  /// or -1 when its pair is not there (the pattern's growth waits for a few such contacts,
  /// contact_effect.cpp update_pattern): add_tangents() leaves such a contact out of the matrix,
  /// and the contact solve takes its springs by CG (tangent_times() has all contacts). Returns
  /// how many contacts it left outside (0: the pattern holds every pair of the step).
  std::size_t assign_groups(const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs, int first_group);
  /// Of the contacts touching at the step's start, those assign_groups() left outside the
  /// pattern (group -1); and the spring terms (kn, ks) of the last forces_at() that add_tangents()
  /// leaves out for it.
  struct OutsidePattern {
    std::size_t touching = 0, springs = 0;
  };
  OutsidePattern outside_pattern() const;

  // ---- the Newton kernels (contact_solve.cpp) -------------------------------------------------
  /// Sets each contact's shear strength for the step's first inner solve from what it carries
  /// (warm start): the normal force of the last accepted step where it was closed.
  void start_strengths();
  /// Evaluates every contact at the increment d: gap, shear, the forces on the constitutive
  /// curves and their tangents; adds the contact forces Σ N·cn − Σ T·cs to r (the residual).
  void forces_at(const Eigen::VectorXd& d, Eigen::VectorXd& r);
  /// Adds the tangent springs of the last forces_at() to the matrix (contacts with a group).
  void add_tangents(SystemMatrix& k) const;
  /// y += (Σ kn·cn cnᵀ + ks·cs csᵀ)·v with the tangents of the last forces_at().
  void tangent_times(const Eigen::VectorXd& v, Eigen::VectorXd& y) const;
  /// Line search along δ from the point of the last forces_at(): stores each contact's rates
  /// Δg = cnᵀδ, Δs = csᵀδ.
  void set_direction(const Eigen::VectorXd& delta);
  /// Σ N(g + αΔg)·Δg − Σ T(s + αΔs)·Δs, the contacts' part of −dΠ/dα (non-increasing in α).
  double directional_force(double alpha) const;
  /// What the Newton model missed along the direction (the contact solve's trace): per kind of
  /// spring change between α = 0 and α = 1, the contacts and their part of ψ(1) − ψ_model(1),
  /// ψ_model being linear in α with the tangents at α = 0 (ψ(1) − ψ_model(1) < 0: the change
  /// stops the step short of α = 1). Kinds: kLineKinds. A cohesive face (cohesive_law.h) whose
  /// own error exceeds 1e-3 of its force change is also printed on stderr, one line each: its
  /// gap, damage at the step's start and at the iterate (m), the direction's rate of its gap,
  /// its matrix stiffness at α = 0 and 1 (N/m) and forces (N), and its error.
  static constexpr int kLineKinds = 6;
  static constexpr const char* kLineKindNames[kLineKinds] = {
      "closing", "opening", "normal other", "stick to slip", "slip reversed or stuck", "shear other"};
  struct LineModelError {
    std::array<int, kLineKinds> contacts{};
    std::array<double, kLineKinds> error{};  ///< N·m per unit α², summed
  };
  LineModelError line_model_error() const;
  /// What the Newton model missed at the point the line search took (α along the direction of
  /// set_direction()), as forces on the unknowns (the contact solve's trace): per kind of spring
  /// change between 0 and α (kLineKinds), the largest |r_i| (N) of the residual those contacts'
  /// departure from their linear model leaves, Σ (N − N_lin)·cn − (T − T_lin)·cs over the kind.
  /// All kinds are also added to `total` (given: the linear model's residual r − αHδ; then the
  /// residual at the point taken, which the next iterate evaluates).
  std::array<double, kLineKinds> line_model_residual(double alpha, Eigen::VectorXd& total) const;
  /// Cohesive faces on the softening branch at the last forces_at() (damage past the elastic
  /// opening, below w_c).
  int softening_faces() const;
  /// Largest |N| and |T| of the last forces_at(), N (a scale for the residual tolerance).
  double force_scale() const { return force_scale_; }
  /// After an inner solve: shear strengths follow the normal forces (the friction fixed point).
  /// Bonds do not break here: an iterate is not the step (break_at_peak()). Returns the number of
  /// contacts whose strength changed where it matters (at or near the limit) by more than 0.1 %
  /// and more than `force_floor` (N).
  int update_strengths(double force_floor);

  // ---- the step's end ------------------------------------------------------------------------
  /// What break_at_peak() broke.
  struct Breaks {
    int tensile = 0;      ///< bonds pulled beyond their tensile strength × length
    int shear = 0;        ///< contacts whose shear force reached the peak strength c·L + tanφ·N
    bool resolve = false; ///< a break changed a law's strength: the step must be solved again
  };
  /// At a solution of the step's contact problem (solve_contact_step converged): every unbroken
  /// contact with cohesion or tensile strength whose force reaches its peak — a bond in tension
  /// beyond T·L, or a shear force at c·L + tanφ·N — breaks (docs/contact.md "Cohesion and
  /// tensile bonds"). The caller solves the step again while `resolve` (the broken contacts'
  /// strengths changed), until no unbroken contact is beyond its peak.
  Breaks break_at_peak();
  /// The states the step ends in (open, locked, sliding) and the events they make: once per
  /// attempt, on its last solve. A contact that was closed and ends open loses its cohesion.
  void settle_states();
  /// The accepted step's results written into its contacts (ContactSet::end_step() calls it):
  /// the joint law's memory, the elastic shear (a sliding contact's spring left loaded at the
  /// friction limit: the return mapping), the cohesive faces' damage, slip and the energy their
  /// softening dissipated, and the bonds broken in it counted.
  void commit();
  /// –, the largest growth of a softening face's damage in the committed step, over its w_c.
  double max_damage_jump() const { return max_damage_jump_; }

 private:
  ContactSet& set_;
  const CoverSpace& space_;
  int row_ = 0;                  // unknowns per contact row: 2 × element_dofs()
  // This step's rows (Row): a contact's gap and slip coefficients are products of its shape
  // values and its edge's direction, formed where they are used, in the same rounding as when
  // they were stored (cn, cs: 2 × row_ doubles; now row_ / 2 + 2): the Newton kernels' passes
  // over the rows read 112 bytes per contact at cover order 0 instead of 240, for the same bits.
  std::vector<int> dofs_;        // [contact · row_] unknowns
  std::vector<double> phi_;      // [contact · row_ / 2] –, shape values (B's negated)
  std::vector<double> tangent_;  // [contact · 2] –, the edge's unit tangent (tx, ty); n = (ty, −tx)
  mutable std::vector<double> cn_, cs_;  // [row_] add_tangents()' scratch: one row's cn, cs
  mutable Eigen::MatrixXd block_;  // add_tangents()' scratch
  // The Newton kernels' short lists, so that their loops touch only the contacts that count (a
  // wall's step has many open ones): the contacts with a tangent spring (kn or ks ≠ 0) at the
  // last forces_at(), with those springs (tangent_times() reads nothing else), in the contacts'
  // order; and, of set_direction(), the contacts whose normal force, or shear force, may be
  // non-zero somewhere along the direction (directional_force()). Leaving out a term that is
  // exactly zero leaves each sum the same, bit for bit.
  struct TangentSprings {
    std::size_t contact;
    double kn, ks;  // N/m
  };
  std::vector<TangentSprings> springs_;
  // set_direction()'s terms of ψ, in the order directional_force() sums them (contact by
  // contact, normal before shear): each with the values it reads along α, so that a line
  // search's evaluations read one short array, not the contacts (kind: LineTerm::Kind).
  struct LineTerm {
    enum Kind : std::uint8_t { linear_normal, linear_shear, normal, shear };
    double x;       // m, the gap or the shear at α = 0
    double rate;    // m per unit α
    double k;       // N/m, the linear spring (linear kinds)
    double cap;     // N, the shear strength (linear_shear)
    std::uint32_t contact;
    Kind kind;
    bool bonded;    // linear_normal: the spring holds tension
  };
  std::vector<LineTerm> along_;
  double force_scale_ = 0;          // N, forces_at()'s largest |N| and |T|
  std::vector<ContactWork> work_;  // [contact] the step's contacts' inner-solve working values
  std::vector<std::int32_t> group_run_;  // [element + 1] assign_groups()' scratch: CSR into its pairs
  bool elastic_predictor_ = false;  // new touching contacts stick in the first inner solve
  double eps_ = 0;                  // m, gap tolerance (contact_tolerances.h open_gap·w0)
  double skin_ = 0;                 // m, smoothing of the normal spring (skin·w0)
  double max_damage_jump_ = 0;      // –, commit()'s largest Δκ/w_c
  /// A cohesive face's softened cohesion at its damage w.kappa: w.c_coh (N).
  void set_cohesion(const Contact& c, ContactWork& w) const;
  /// m, the plastic slip of contact c in the step so far (0 unless it slides).
  double plastic_slip(const Contact& c, const ContactWork& w) const;
};

}  // namespace nmm::solve
