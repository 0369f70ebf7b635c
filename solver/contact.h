// Contacts: penalty springs, Mohr–Coulomb friction, the open–close states, and their transfer
// from step to step. See contact.cpp for the equations.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "contact_detection.h"
#include "element_integration.h"
#include "joint_law.h"
#include "mesh.h"
#include "scene.h"
#include "system_matrix.h"

namespace nmm::solve {

/// The element's triangle in the configuration at the start of a step.
struct ElementFrame {
  double ox = 0, oy = 0;  ///< m, origin: the node of its first cover
  TriangleWeights w;      ///< weights relative to (ox, oy)
};

enum class ContactState : std::uint8_t { open, locked, sliding };

struct Contact {
  ContactCandidate at;  ///< vertex P, edge, elements, ω, gap at the start of the step
  int law = 0;          ///< index into ContactSet::laws()
  double length = 0;    ///< m, tributary joint length of the contact point
  ContactState state = ContactState::open;
  ContactState start_state = ContactState::open;  ///< state at the start of the step
  bool broken = false;       ///< cohesion and tensile strength lost (it slid or opened)
  double shear_el = 0;       ///< m, elastic shear of the shear spring at the start of the step
  int slip_sign = 0;         ///< direction of sliding along the edge (±1)
  double normal_force = 0;   ///< N, compression > 0, from the last solve
  double friction_normal = 0;  ///< N, normal force the shear strength of the inner solve uses
  double gap = 0;            ///< m, gap after the last solve (< 0: penetration)
  double strength = 0;       ///< N, shear strength of the inner solve (tanφ·N + c·L, 0 if open)
  bool bonded = false;       ///< normal spring holds tension (unbroken, tensile strength, closed)
  double kn_now = 0;         ///< N/m, tangent normal stiffness at the last solve
  double ks_now = 0;         ///< N/m, tangent shear stiffness at the last solve (0 sliding)
  double shear_force = 0;    ///< N, shear force at the last solve
  bool capped = false;       ///< closure held below Vm at the last solve
  double shear = 0;          ///< m, trial elastic shear after the last solve (shear_el + slip)
  // Linearisation for this step: gap = gap0 + cnᵀd, shear = shear0 + csᵀd over 12 unknowns.
  std::array<int, 12> dofs{};
  std::array<double, 12> cn{}, cs{};
  double gap0 = 0, shear0 = 0;
  int group = -1;  ///< coupling group of its element pair in the system matrix
  double rate_gap = 0, rate_shear = 0;  ///< m per unit α, Δg and Δs of the line search direction
};

/// All contacts of a run.
class ContactSet {
 public:
  ContactSet(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name);

  bool active() const { return active_; }
  /// The x unknown of each physical cover (y is the next); without a call, cover c has 2c.
  void use_unknowns(const std::vector<std::int32_t>& unknown) { unknown_ = unknown; }
  /// "contact", and "friction", "cohesion", "tension" when a law in use has them.
  std::vector<std::string> effects() const;
  const std::vector<ContactLaw>& laws() const { return laws_; }
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// The contacts as the last accepted step left them (saved by contact_history.h).
  const std::vector<Contact>& committed() const { return committed_; }
  /// A restart: the next step starts from these contacts and states.
  void restore_committed(std::vector<Contact> c) {
    committed_ = c;
    contacts_ = std::move(c);
  }
  /// [me] 1 for elements of excavated bodies: no contact is detected on them.
  void set_removed_elements(std::vector<std::uint8_t> removed) { removed_ = std::move(removed); }

  /// Detects contacts in the current configuration (search distance d0, new contacts at most
  /// `shallow` deep, m; model half-size w0), carries over the states of the previous step and linearises each
  /// contact with the element frames.
  void begin_step(const std::vector<double>& loop_xy, const std::vector<ElementFrame>& frames,
                  double d0, double shallow, double w0);

  /// Element pairs coupled by the current contacts and those near enough to touch soon
  /// (within the search distance), sorted and unique: the pairs the pattern should hold.
  std::vector<std::pair<std::int32_t, std::int32_t>> element_pairs() const;
  /// Sets each contact's coupling group: first_group + the index of its pair in `pairs` (sorted,
  /// a superset of element_pairs()).
  void assign_groups(const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs, int first_group);

  // --- The step's contact problem as a convex minimisation (contact.cpp, contact_solve.cpp) ---
  /// Sets each contact's shear strength for the step's first inner solve from what it carries
  /// (warm start): the normal force of the last accepted step where it was closed.
  void start_strengths();
  /// Evaluates every contact at the increment d: gap, shear, the forces on the constitutive
  /// curves and their tangents; adds the contact forces Σ N·cn − Σ T·cs to r (the residual).
  void forces_at(const Eigen::VectorXd& d, Eigen::VectorXd& r);
  /// Adds the tangent springs of the last forces_at() to the matrix.
  void add_tangents(SystemMatrix& k) const;
  /// y += (Σ kn·cn cnᵀ + ks·cs csᵀ)·v with the tangents of the last forces_at().
  void tangent_times(const Eigen::VectorXd& v, Eigen::VectorXd& y) const;
  /// Line search along δ from the point of the last forces_at(): stores each contact's rates
  /// Δg = cnᵀδ, Δs = csᵀδ.
  void set_direction(const Eigen::VectorXd& delta);
  /// Σ N(g + αΔg)·Δg − Σ T(s + αΔs)·Δs, the contacts' part of −dΠ/dα (non-increasing in α).
  double directional_force(double alpha) const;
  /// Largest |N| and |T| of the last forces_at(), N (a scale for the residual tolerance).
  double force_scale() const;
  /// After an inner solve: bonds beyond their tensile strength or cohesion break (for good), and
  /// shear strengths follow the normal forces (the friction fixed point). Returns the number of
  /// contacts whose strength changed where it matters (at or near the limit) by more than 0.1 %
  /// and more than `force_floor` (N); `largest_move` (if given) gets the largest such change, N.
  int update_strengths(double force_floor, double* largest_move = nullptr);
  /// Every contact's shear strength for the inner solve, N (the friction fixed point's unknowns).
  void strengths(Eigen::VectorXd& out) const;
  /// Sets the shear strengths (an accelerated fixed point step), N.
  void set_strengths(const Eigen::VectorXd& s);
  /// The states the step ends in (open, locked, sliding) and the events they make.
  void settle_states();

  /// Accepts the step: its contacts and states are what the next step starts from (a sliding
  /// contact's spring is left loaded at the friction limit). A step that is not accepted (cut and
  /// redone) leaves them as they were.
  void end_step();

  /// State changes of accepted and cut attempts (diagnostics, summary.json "contacts").
  struct Events {
    long closed = 0, opened = 0, slid = 0, stuck = 0;
    long broken = 0;  ///< bonds broken (tensile strength or cohesion exceeded)
  };
  Events events;

  /// Largest penetration of the contacts after the last solve, m.
  double max_penetration() const;
  std::size_t closed_count() const;
  /// Contacts whose closure is held below Vm after the last solve.
  std::size_t capped_count() const;
  /// True if some law is nonlinear (Bandis–Barton or hyperbolic).
  bool nonlinear() const { return nonlinear_; }
  double detection_seconds() const { return detection_seconds_; }
  const DetectionStats& detection_stats() const { return stats_; }

 private:
  const Mesh& mesh_;
  std::vector<std::int32_t> unknown_;  // [pc] x unknown of each cover (empty: 2·pc)
  ContactTopology topo_;
  std::vector<ContactLaw> laws_;
  std::vector<int> joint_law_;  // [joint] law index
  int interface_law_ = 0;
  bool interface_used_ = false;  // separate blocks can meet along their boundaries
  bool nonlinear_ = false;       // a law in use is not a constant spring
  bool active_ = false;
  std::vector<Contact> contacts_;   // this step's, being iterated
  std::vector<Contact> committed_;  // as the last accepted step left them
  std::vector<std::uint8_t> removed_;  // [me] excavated elements (empty: none)
  ClosedContacts closed_;                   // (vertex, block) pairs closed after the last step
  ElementPairs near_pairs_;                 // element pairs within the search distance
  double eps_ = 0;                          // m, gap tolerance (1e-10·w0)
  double skin_ = 0;                         // m, smoothing of the normal spring at touching (1e-12·w0)
  DetectionStats stats_;
  double detection_seconds_ = 0;
};

}  // namespace nmm::solve
