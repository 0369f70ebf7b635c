// Contacts: penalty springs, Mohr–Coulomb friction, the open–close states, and their transfer
// from step to step. See contact.cpp for the equations.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/discretisation/configuration.h"
#include "solver/contact/contact_detection.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/element_integration.h"
#include "solver/contact/joint_law.h"
#include "common/mesh.h"
#include "solver/discretisation/model.h"
#include "common/scene.h"
#include "solver/discretisation/system_matrix.h"

namespace nmm::solve {

enum class ContactState : std::uint8_t { open, locked, sliding };

/// What a contact carries from one accepted step to the next: all a step needs of the past
/// (ContactSet::history(); with the rows' diagnostics, the checkpoint's CONTACT section). The
/// next step finds it again by its vertex, against the same block.
struct ContactHistory {
  std::int32_t vertex = -1;  ///< loop vertex P
  std::int32_t block = -1;   ///< block of the edge P was against
  ContactState state = ContactState::open;
  bool broken = false;       ///< cohesion and tensile strength lost (it reached its peak at an
                             ///< accepted state, or opened)
  std::int8_t slip_sign = 0; ///< direction of sliding along the edge (±1, 0 never slid)
  double shear_el = 0;       ///< m, elastic shear of the shear spring (return mapping)
  double normal_force = 0;   ///< N, compression > 0: the next step's first friction strength
  JointMemory joint;         ///< the joint law's own history (travel, dilation, largest closure)
};

/// One contact of the step being solved: rebuilt by every begin_step() from the detection and
/// the history, iterated by the solve, read by output and diagnostics after the step. Its
/// linearisation rows (unknowns, cn, cs) and the inner solve's working values (ContactWork) are
/// ContactSet's flat arrays, index-aligned with contacts(); what it carries to the next step is
/// a ContactHistory.
struct Contact {
  // Where, and the law (this step's detection).
  ContactCandidate at;  ///< vertex P, edge, elements, ω, gap at the start of the step
  /// The vertex of the other face at the same point whose contact against P's element would be
  /// this one seen from the other side (element_of(mirror) = at.elem_b), −1 if none: the same
  /// gap, shear and spring rows (contact.cpp begin_step), so a swap between the two is no change.
  std::int32_t mirror = -1;
  int law = 0;          ///< index into ContactSet::laws()
  double length = 0;    ///< m, tributary joint length of the contact point
  // State: from the history at the start of the step, the solution's at its end.
  ContactState state = ContactState::open;
  ContactState start_state = ContactState::open;  ///< state at the start of the step
  bool broken = false;       ///< cohesion and tensile strength lost: from the history, then set
                             ///< by break_at_peak() and settle_states() at the step's solution
  double shear_el = 0;       ///< m, elastic shear of the shear spring at the start of the step
                             ///< (at its end after end_step())
  int slip_sign = 0;         ///< direction of sliding along the edge (±1)
  JointMemory joint;         ///< the joint law's history at the start of the step (at its end
                             ///< after end_step()); the gap below is net of joint.dilation
  // The last solve (output and diagnostics).
  double normal_force = 0;   ///< N, compression > 0
  double gap = 0;            ///< m, gap after the last solve (< 0: penetration), net of the
                             ///< joint's dilation (the faces stand apart by it at gap 0)
  double shear = 0;          ///< m, trial elastic shear after the last solve (shear_el + slip)
  double shear_force = 0;    ///< N
  double kn_now = 0;         ///< N/m, tangent normal stiffness at the last solve
  double ks_now = 0;         ///< N/m, tangent shear stiffness at the last solve (0 sliding)
  bool capped = false;       ///< closure held below Vm at the last solve
  double dilation_step = 0;  ///< m, the joint's dilation over the accepted step (end_step();
                             ///< Barton–Bandis, < 0 sliding back toward the start; energy.h)
};

/// The inner solve's working values of one contact: set by begin_step(), assign_groups(),
/// start_strengths() and the Newton iterations, read by nothing after the step. Kept apart from
/// Contact (the step's rows and results, what output and the next step's history read) as Box2D
/// keeps its solver's constraints apart from its contacts: the solve's loops touch only these
/// and the rows.
struct ContactWork {
  double strength = 0;          ///< N, shear strength of the inner solve (tanφ·N + c·L, 0 if open)
  bool bonded = false;          ///< normal spring holds tension (unbroken, tensile strength, closed)
  double gap0 = 0, shear0 = 0;  ///< m, gap = gap0 + cnᵀd, shear = shear0 + csᵀd
  int group = -1;               ///< coupling group of its element pair in the system matrix
  double start_normal_force = 0;  ///< N, the normal force carried into the step (start_strengths())
  bool start_broken = false;    ///< broken at the start of the step (end_step() counts new breaks)
  double rate_gap = 0, rate_shear = 0;  ///< m per unit α, Δg and Δs of the line search direction
};

/// All contacts of a run.
class ContactSet {
 public:
  /// The contacts of `model`'s run (its laws; the model must outlive this set).
  explicit ContactSet(const Model& model);

  bool active() const { return active_; }
  /// The approximation space of the run (unknowns of each element; it must outlive this set).
  void use_space(const CoverSpace& space) { space_ = &space; }
  /// Unknowns of one contact's rows: both elements' (CoverSpace::element_dofs() each).
  int row_size() const { return row_; }
  /// Contact i's unknowns (A's element unknowns, then B's) and the coefficients of its gap and
  /// slip on them, row_size() each, for the step being solved.
  const int* row_dofs(std::size_t i) const { return dofs_.data() + i * static_cast<std::size_t>(row_); }
  const double* row_cn(std::size_t i) const { return cn_.data() + i * static_cast<std::size_t>(row_); }
  const double* row_cs(std::size_t i) const { return cs_.data() + i * static_cast<std::size_t>(row_); }
  /// "contact", and "friction", "cohesion", "tension" when a law in use has them.
  std::vector<std::string> effects() const;
  const std::vector<ContactLaw>& laws() const { return laws_; }
  /// The joint a contact lies on: that of the edge P faces, else of an edge at P; -1: none (a
  /// body boundary). Its joint set is the contact's law.
  std::int32_t joint_of(const ContactCandidate& at) const;
  /// The contacts of the step being solved, or of the last step taken.
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// What the last accepted step left for the next (one entry per contact of accepted()).
  const std::vector<ContactHistory>& history() const { return history_; }
  /// The (vertex, block) pairs in closed contact after the last accepted step (what contact
  /// detection is given to let a vertex stay inside a block it was against).
  ClosedContacts closed_contacts() const;
  /// The contacts of the last accepted step (contacts() unless an attempt was cut since).
  const std::vector<Contact>& accepted() const { return rows_accepted_ ? contacts_ : accepted_; }
  /// A restart: the next step starts from this history; `rows` (the accepted step's contacts,
  /// one per history entry) are shown until then.
  void restore(std::vector<ContactHistory> history, std::vector<Contact> rows) {
    history_ = std::move(history);
    contacts_ = std::move(rows);
    rows_accepted_ = true;
  }
  /// [me] 1 for elements of excavated bodies: no contact is detected on them.
  void set_removed_elements(std::vector<std::uint8_t> removed) { removed_ = std::move(removed); }

  /// Detects contacts in the current configuration (search distance d0, new contacts at most
  /// `shallow` deep, m; model half-size w0), carries over the states of the previous step and
  /// linearises each contact with the shape functions of its two elements in the step's
  /// configuration `config` (configuration.h).
  void begin_step(const std::vector<double>& loop_xy, const Configuration& config, double d0,
                  double shallow, double w0);

  /// Element pairs of the step's contacts (open or closed), sorted and unique: the pairs the
  /// system matrix's pattern must hold (docs/contact.md "Sparse pattern").
  std::vector<std::pair<std::int32_t, std::int32_t>> contact_pairs() const;
  /// The same of the last accepted step's contacts (accepted()).
  std::vector<std::pair<std::int32_t, std::int32_t>> accepted_pairs() const;
  /// Sets each contact's coupling group: first_group + the index of its pair in `pairs` (sorted),
  /// or -1 when its pair is not there (the pattern's growth waits for a few such contacts,
  /// time_stepper.cpp update_pattern): add_tangents() leaves such a contact out of the matrix,
  /// and the contact solve takes its springs by CG (tangent_times() has all contacts).
  void assign_groups(const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs, int first_group);
  /// Of the step's contacts touching at its start (closed, or within the gap tolerance of
  /// touching): how many there are, and how many of them assign_groups() left outside the
  /// pattern (group -1).
  std::size_t touching_at_start() const;
  std::size_t touching_outside_pattern() const;
  /// Spring terms (kn, ks) of the last forces_at() that add_tangents() leaves out (group -1).
  std::size_t springs_outside_pattern() const;

  // --- The step's contact problem as a convex minimisation (contact.cpp, contact_solve.cpp) ---
  /// Sets each contact's shear strength for the step's first inner solve from what it carries
  /// (warm start): the normal force of the last accepted step where it was closed.
  void start_strengths();
  /// Steps without inertia (static_mode "equilibrium"): a block resting on contacts it has just
  /// met is held sideways only by their shear springs, which have no strength before the
  /// friction fixed point has a normal force. Touching contacts (gap ≤ 1e-10·w0 at the start of
  /// the step) that start open then stick in the first inner solve (an elastic predictor, as for a
  /// contact with unbounded strength); the fixed point gives them their real strength from its
  /// normal force. Without it the first solve of such a block is singular ("not positive
  /// definite"). With inertia (dynamic, DDA static) the mass holds the block: off.
  void set_elastic_predictor(bool on) { elastic_predictor_ = on; }
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
  /// stops the step short of α = 1). Kinds: kLineKinds.
  static constexpr int kLineKinds = 6;
  static constexpr const char* kLineKindNames[kLineKinds] = {
      "closing", "opening", "normal other", "stick to slip", "slip reversed or stuck", "shear other"};
  struct LineModelError {
    std::array<int, kLineKinds> contacts{};
    std::array<double, kLineKinds> error{};  ///< N·m per unit α², summed
  };
  LineModelError line_model_error() const;
  /// Largest |N| and |T| of the last forces_at(), N (a scale for the residual tolerance).
  double force_scale() const;
  /// After an inner solve: shear strengths follow the normal forces (the friction fixed point).
  /// Bonds do not break here: an iterate is not the step (break_at_peak()). Returns the number of
  /// contacts whose strength changed where it matters (at or near the limit) by more than 0.1 %
  /// and more than `force_floor` (N).
  int update_strengths(double force_floor);
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

  /// Accepts the step: its contacts and states are what the next step starts from (a sliding
  /// contact's spring is left loaded at the friction limit). A step that is not accepted (cut and
  /// redone) leaves them as they were.
  void end_step();

  /// State changes of accepted and cut attempts (diagnostics, summary.json "contacts").
  struct Events {
    long closed = 0, opened = 0, slid = 0, stuck = 0;
    long broken = 0;  ///< bonds broken on accepted steps (tensile strength or peak shear
                      ///< strength reached, or opened), counted by end_step()
  };
  Events events;

  /// Largest dilation a contact carries (Barton–Bandis), m: its faces stand apart by it, so
  /// contact detection must look that much farther.
  double max_dilation() const;
  /// Largest penetration of the contacts after the last solve, m.
  double max_penetration() const;
  std::size_t closed_count() const;
  /// The closed contacts' joint after the last solve: Σ of their tributary lengths (m) and the
  /// largest normal and shear stress N/L, |T|/L (Pa) among them.
  struct JointStresses {
    double closed_length = 0, max_normal_stress = 0, max_shear_stress = 0;
  };
  JointStresses joint_stresses() const;
  /// Contacts whose closure is held below Vm after the last solve.
  std::size_t capped_count() const;
  /// True if some law is nonlinear (Bandis–Barton or hyperbolic).
  bool nonlinear() const { return nonlinear_; }
  /// True if some law's tangent softens with the load or the travel (Bandis–Barton closure,
  /// hyperbolic or Barton–Bandis shear): there the force tolerance alone does not bound a
  /// contact's displacement error, and the contact solve checks it (contact_solve.h
  /// displacement_tolerance). A constant spring's error is at most F_tol/k (max_gap_error).
  bool softening() const { return nonlinear_ || memory_laws_; }
  double detection_seconds() const { return detection_seconds_; }
  const DetectionStats& detection_stats() const { return stats_; }

 private:
  /// The joint memory of the nearest closed contact of the last accepted step between the same
  /// two blocks within a mesh size of vertex (own_memory if none): for a new or open contact.
  /// Looks in memory_cells_ (index_closed_memory()).
  JointMemory nearby_joint_memory(const std::vector<double>& xy, std::int32_t vertex, std::int32_t block_a,
                                  std::int32_t block_b, JointMemory own_memory) const;
  /// Files the closed history entries by mesh-size cell of their vertex's position (xy).
  void index_closed_memory(const std::vector<double>& xy);

  const Mesh& mesh_;
  const CoverSpace* space_ = nullptr;  // unknowns of each element
  int row_ = 0;                        // unknowns per contact row: 2 × element_dofs()
  std::vector<int> dofs_;              // [contact · row_] this step's rows: unknowns,
  std::vector<double> cn_, cs_;        // [contact · row_] –, gap and slip per unit unknown
  mutable Eigen::MatrixXd block_;      // add_tangents()' scratch
  ContactTopology topo_;
  std::vector<ContactLaw> laws_;  // the scene's (joint_law.h contact_laws)
  std::vector<int> joint_law_;    // [joint] law index
  int interface_law_ = 0;
  bool interface_used_ = false;  // separate blocks can meet along their boundaries
  bool nonlinear_ = false;       // a law in use is not a constant spring
  bool memory_laws_ = false;     // a law carries a joint memory (Barton–Bandis shear, hysteresis)
  // (cell x, cell y, history index) of the closed history entries, sorted: nearby_joint_memory()'s
  std::vector<std::array<std::int64_t, 3>> memory_cells_;
  bool elastic_predictor_ = false;  // new touching contacts stick in the first inner solve
  bool active_ = false;
  std::vector<Contact> contacts_;   // this step's, being iterated
  std::vector<ContactWork> work_;   // [contact] contacts_'s inner-solve working values
  std::vector<Contact> accepted_;   // the last accepted step's, while contacts_ is a later attempt's
  bool rows_accepted_ = false;      // contacts_ are the last accepted step's
  std::vector<ContactHistory> history_;  // what the last accepted step left for the next
  std::vector<std::int32_t> history_at_;    // [v] first index into history_ of vertex v, or -1 (scratch)
  std::vector<std::int32_t> history_next_;  // [i] next history_ entry of the same vertex, or -1
  std::vector<std::uint8_t> removed_;  // [me] excavated elements (empty: none)
  ClosedContacts closed_;                   // (vertex, block) pairs closed after the last step
  bool touching_at_start(const Contact& c) const;
  double eps_ = 0;                          // m, gap tolerance (contact_tolerances.h open_gap·w0)
  double skin_ = 0;                         // m, smoothing of the normal spring (skin·w0)
  DetectionStats stats_;
  CandidateList candidates_;  // detection's Verlet list (a cache: contact_detection.h)
  double detection_seconds_ = 0;
};

}  // namespace nmm::solve
