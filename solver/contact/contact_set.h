// The contacts of a run: detection, the history carried from one accepted step to the next, and
// the step's contacts (contact.h), as the output reads them. The step's linearisation and Newton
// kernels are its ContactProblem's (contact_problem.h). Equations: contact_set.cpp (detection and
// transfer), contact_problem.cpp (springs, friction, states).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/mesh.h"
#include "solver/contact/contact.h"
#include "solver/contact/contact_detection.h"
#include "solver/contact/joint_law.h"
#include "solver/discretisation/effect.h"
#include "solver/discretisation/model.h"

namespace nmm::solve {

class ContactProblem;

/// All contacts of a run.
class ContactSet {
 public:
  /// The contacts of `model`'s run (its scene's laws; the model must outlive this set).
  explicit ContactSet(const Model& model);

  bool active() const { return active_; }
  const std::vector<ContactLaw>& laws() const { return laws_; }
  /// The joint a contact lies on: that of the edge P faces, else of an edge at P; -1: none (a
  /// body boundary). Its joint set is the contact's law.
  std::int32_t joint_of(const ContactCandidate& at) const;
  /// "contact", and "friction", "cohesion", "tension", the joint laws' names when a law in use
  /// has them.
  std::vector<std::string> effects() const;
  /// True if some law's tangent softens with the load or the travel (Bandis–Barton closure,
  /// hyperbolic or Barton–Bandis shear): there the force tolerance alone does not bound a
  /// contact's displacement error, and the contact solve checks it (contact_solve.h
  /// displacement_tolerance). A constant spring's error is at most F_tol/k (max_gap_error).
  bool softening() const { return nonlinear_ || memory_laws_ || cohesive_; }
  /// True if an open contact can carry history that a contact new to the set would not have: a
  /// softening or memory law's (above), or a bond's (a law with cohesion or tensile strength:
  /// a broken bond found again as new would hold again). Detection then keeps Shi's search
  /// distance for open contacts (contact_effect.cpp begin_step). So does a run whose rock can
  /// crack: with the narrower search the fracturing matrix's slope h 0.3 m static slow cell's
  /// wedge is 18.9 / 22.6 mm across Haswell / Prescott (2026-12-02). Not the reach's own fault:
  /// step 4's first solve parts by 1e-5 of the displacement across kernels (1.5e-6 with d0)
  /// from states 1e-13 apart, every count alike (a contact solve stopped at its tolerance, as
  /// far as traced); its crack exits lie up to 2e-6 m apart, beyond the exit grid (journal
  /// docs/notes/2026-12-fracture-robustness.md). The dynamic cell whose re-cut check failed
  /// passes since the check's full cut snaps its growths (cover_cutter.cpp joint_curves).
  bool open_history() const { return softening() || bonds_ || fracturing_; }
  /// True if a material that can break has a fracture energy: new cracks' faces soften
  /// (cohesive_law.h), and the checkpoint's CONTACT section carries their damage.
  bool cohesive() const { return cohesive_; }
  /// The cohesive law of the rock a contact's vertex lies in (off where it has none).
  const CohesiveLaw& cohesive_law(const Contact& c) const;
  /// The cohesive law of the material of loop vertex v's element.
  const CohesiveLaw& cohesive_law_of_vertex(std::int32_t v) const;
  /// A contact whose faces still hold a cohesive traction (on, damage below w_c).
  bool cohesive_holds(const Contact& c) const;
  /// m, the largest w_c of a contact still holding: detection looks that much farther, so a
  /// softening crack's contacts are found until their traction is gone.
  double cohesive_reach() const;

  // ---- the step's contacts -----------------------------------------------------------------
  /// Detects contacts in the current configuration (loop vertices xy; search distance d0, new
  /// contacts at most `shallow` deep, m; model half-size w0), carries over the states of the last
  /// accepted step and gives each its tributary length. The step's ContactProblem linearises them.
  /// `open_gap` (m, ≤ d0; < 0: d0): contacts open wider are not found (detect_contacts).
  void begin_step(const std::vector<double>& xy, double d0, double shallow, double w0, double open_gap = -1);
  /// The contacts of the step being solved, or of the last step taken.
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// The same, for the step's ContactProblem to write its solution into.
  std::vector<Contact>& step_contacts() { return contacts_; }
  /// Of the step's contacts, those touching at its start: closed, or within the gap tolerance of
  /// touching.
  bool touching_at_start(const Contact& c) const;
  std::size_t touching_at_start() const;
  /// Element pairs of the step's contacts (open or closed), sorted and unique: the pairs the
  /// system matrix's pattern must hold (docs/contact.md "Sparse pattern"); `accepted`: of the
  /// last accepted step's contacts (accepted()).
  std::vector<std::pair<std::int32_t, std::int32_t>> element_pairs(bool accepted = false) const;
  /// Accepts the step: the step's problem writes its results into the contacts (joint memory,
  /// elastic shear; a sliding contact's spring is left loaded at the friction limit), and they
  /// are what the next step starts from. A step that is not accepted (cut and redone) leaves the
  /// history as it was.
  void end_step(ContactProblem& step);

  // ---- history -----------------------------------------------------------------------------
  /// What the last accepted step left for the next (one entry per contact of accepted()).
  const std::vector<ContactHistory>& history() const { return history_; }
  /// The contacts of the last accepted step (contacts() unless an attempt was cut since).
  const std::vector<Contact>& accepted() const { return rows_accepted_ ? contacts_ : accepted_; }
  /// The (vertex, block) pairs in closed contact after the last accepted step (what contact
  /// detection is given to let a vertex stay inside a block it was against).
  ClosedContacts closed_contacts() const;
  /// A restart: the next step starts from this history; `rows` (the accepted step's contacts,
  /// one per history entry) are shown until then. Without rows (a mesh cracks re-cut: no step on
  /// it yet) each entry's row holds only what the history says (its vertex, state, forces, and
  /// its depth as the gap) against the first element of its block.
  void restore(std::vector<ContactHistory> history, std::vector<Contact> rows);
  /// [me] 1 for elements of excavated bodies: no contact is detected on them.
  /// Detection leaves the vertices and edges of blocks wholly removed out of its list
  /// (contact_detection.h), so a list built for the elements removed before is built anew.
  void set_removed_elements(std::vector<std::uint8_t> removed) {
    if (removed != removed_) candidates_.xy.clear();
    removed_ = std::move(removed);
  }
  /// Largest dilation a contact carries (Barton–Bandis), m: its faces stand apart by it, so
  /// contact detection must look that much farther.
  double max_dilation() const;

  /// State changes of accepted and cut attempts (diagnostics, summary.json "contacts").
  struct Events {
    long closed = 0, opened = 0, slid = 0, stuck = 0;
    long broken = 0;  ///< bonds broken on accepted steps (tensile strength or peak shear
                      ///< strength reached, or opened), counted by end_step()
  };
  Events events;

  /// The step's contacts after the last solve: counts and the closed ones' joint.
  struct Totals {
    std::size_t closed = 0;         ///< contacts not open
    std::size_t capped = 0;         ///< closed contacts whose closure is held below Vm
    double max_penetration = 0;     ///< m, of all contacts
    double closed_length = 0;       ///< m, Σ of the closed contacts' tributary lengths
    double max_normal_stress = 0;   ///< Pa, largest N/L of a closed contact
    double max_shear_stress = 0;    ///< Pa, largest |T|/L of a closed contact
  };
  Totals totals() const;
  /// What the solved step did to its contacts' depths, as step control judges it (step_control.h
  /// rejection): the most it added to one contact's depth at the step's start (to touching, where
  /// the contact started open or is new), the deepest contact it deepened, and of those the one
  /// furthest past what `allowed` lets it reach from its depth at the start. A shorter step cannot
  /// undo the depth a contact started with (carried over a re-cut, or cut so by a crack), only
  /// what it adds.
  StepPenetration deepening(const PenetrationAllowance& allowed) const;
  /// Detection's counts and its seconds so far.
  const DetectionStats& detection_stats() const { return stats_; }
  /// A set built for a re-cut mesh goes on counting where `before` (the old mesh's) stopped:
  /// its events and detection's counts.
  void continue_from(const ContactSet& before) {
    events = before.events;
    stats_ = before.stats_;
  }

  /// The topology detection works on (the problem's rows need the edges' next vertices).
  const ContactTopology& topology() const { return topo_; }

 private:
  /// The joint memory of the nearest closed contact of the last accepted step between the same
  /// two blocks within a mesh size of vertex (own_memory if none): for a new or open contact.
  /// Looks in memory_cells_ (index_closed_memory()).
  JointMemory nearby_joint_memory(const std::vector<double>& xy, std::int32_t vertex, std::int32_t block_a,
                                  std::int32_t block_b, JointMemory own_memory) const;
  /// Files the closed history entries by mesh-size cell of their vertex's position (xy).
  void index_closed_memory(const std::vector<double>& xy);

  const Mesh& mesh_;
  const Model& model_;
  ContactTopology topo_;
  std::vector<ContactLaw> laws_;  // the scene's (joint_law.h contact_laws)
  std::vector<int> joint_law_;    // [joint] law index
  int interface_law_ = 0;
  bool interface_used_ = false;  // separate blocks can meet along their boundaries
  bool nonlinear_ = false;       // a law in use is not a constant spring
  bool memory_laws_ = false;     // a law carries a joint memory (Barton–Bandis shear, hysteresis)
  bool bonds_ = false;           // a law in use has cohesion or tensile strength (a bond that breaks)
  bool fracturing_ = false;      // the scene's rock can crack (fracture block present)
  bool cohesive_ = false;        // new cracks soften (a breakable material with a fracture energy)
  std::vector<CohesiveLaw> cohesive_laws_;  // [material] the cohesive law of its new cracks
  // (cell x, cell y, history index) of the closed history entries, sorted: nearby_joint_memory()'s
  std::vector<std::array<std::int64_t, 3>> memory_cells_;
  bool active_ = false;
  std::vector<Contact> contacts_;   // this step's, being iterated
  std::vector<Contact> accepted_;   // the last accepted step's, while contacts_ is a later attempt's
  bool rows_accepted_ = false;      // contacts_ are the last accepted step's
  std::vector<ContactHistory> history_;  // what the last accepted step left for the next
  std::vector<std::int32_t> history_at_;    // [v] first index into history_ of vertex v, or -1 (scratch)
  std::vector<std::int32_t> history_next_;  // [i] next history_ entry of the same vertex, or -1
  std::vector<std::uint8_t> removed_;  // [me] excavated elements (empty: none)
  ClosedContacts closed_;                   // (vertex, block) pairs closed after the last step
  double eps_ = 0;                          // m, gap tolerance (contact_tolerances.h open_gap·w0)
  DetectionStats stats_;
  CandidateList candidates_;  // detection's Verlet list (a cache: contact_detection.h)
};

}  // namespace nmm::solve
