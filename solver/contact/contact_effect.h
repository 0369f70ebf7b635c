// The contacts as an effect of the step (solver/discretisation/effect.h): the ContactSet
// (contact_set.h: detection, each contact's history from one accepted step to the next) and the
// step's ContactProblem (contact_problem.h: rows, the Newton kernels) behind the one interface
// the stepper loops over. At the step's start it detects the contacts within the search distance
// and grows the sparse pattern by the element pairs they couple (the rule below, update_pattern);
// it solves the step's system its own way — the convex contact problem by Newton iterations on a
// reused factorisation (contact_solve.cpp), solved again while bonds break at the peak; step
// control judges its penetration; the accepted step commits its contacts' history.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "solver/contact/contact_problem.h"
#include "solver/contact/contact_set.h"
#include "solver/contact/contact_solve.h"
#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/effect.h"
#include "solver/discretisation/model.h"

namespace nmm::solve {

class ContactEffect final : public Effect {
 public:
  /// The contacts of `model`'s scene on `space` (both outlive it).
  ContactEffect(const Model& model, const CoverSpace& space);

  /// Contacts are detected where the scene has them and two faces can touch (a block with an
  /// opening excavated from it and no joint has none: the plain solve).
  bool active() const override { return contacts_.active() && model_.contacts_can_arise(); }
  void number(const RunState& s, int first_unknown, std::size_t first_group) override;
  std::size_t groups(const RunState& s) const override { return s.pattern_pairs.size(); }
  void add_groups(const RunState& s, std::vector<int>& offsets, std::vector<int>& dofs) const override;
  Outcome begin_step(EffectStep& step) override;
  void add_at_rest(EffectStep& rest) override;
  bool solves() const override { return true; }
  Outcome solve(EffectStep& step, bool again, StepSolution& x) override;
  StepPenetration penetration(EffectStep& step) const override;
  void rejected(const EffectStep& step, const Eigen::VectorXd& covers_d) const override;
  void commit(EffectStep& step, const Eigen::VectorXd& d) override;
  /// summary.json "contacts" (counts, the joint at the end, state changes), "contact_solve" (what
  /// the solves cost and what the tolerance allowed: docs/interface.md) and
  /// "max_contacts_at_closure_cap"; with or without contacts.
  void summarise(const RunState& s, nlohmann::json& summary) const override;
  /// summary.json "effects": contact, friction, cohesion, tension and the joint laws it uses.
  void effect_names(const RunState& s, std::vector<std::string>& names) const override;
  /// contacts.csv (or contacts.csv.gz: nmm-solve --contacts-gzip).
  std::vector<std::string> output_files() const override { return {"contacts.csv", "contacts.csv.gz"}; }
  /// contacts.csv at an output step of a run with contacts: one row per closed contact
  /// (contact_readout.h), numbered from 0 in the set's order; an output step without closed
  /// contacts has none (docs/interface.md lists the columns).
  void write_outputs(OutputStep& out) const override;
  /// The faces of its closed contacts: each contact's edge and the two edges at its vertex.
  void loaded_faces(const RunState& s, std::vector<std::uint8_t>& loaded) const override;
  /// Energy (effect_energy.h): the springs of the closed contacts hold ½ N·closure + ½ |T·s_el|
  /// (N normal force, closure = −gap, T shear force, s_el elastic shear: exact for constant
  /// springs, the secant energy for nonlinear laws).
  void energy_state(const EnergyState& e, EnergyTerms& t) const override;
  /// Energy of the step: the work of friction in sliding contacts, ½(|T0| + |T|)·|s − s_el| (s
  /// the trial elastic shear, s_el the shear left at the limit: the step's slip; T0 the shear
  /// force the step started with, 0 where it started open with none; |T| where it turned), and
  /// ½ T0·s in one that slid into the step and opens in it (its spring keeps no shear), less
  /// what the asperities return as opening — a Barton–Bandis joint that dilates by Δv
  /// (joint_law.h) pushes its faces apart with N over it (and takes N·|Δv| back sliding down
  /// toward its start) — into t.friction; what softening crack faces dissipated (cohesive_law.h D(κ)), and the work their
  /// cohesion did in slip, which is not friction's, into t.fracture. In a step that cut new cracks,
  /// a new face's contact that slides from its zero start force books ½|T|·slip less in
  /// t.fracture (the static step's friction force went from 0 to T: crack_release.h). Into
  /// t.damped: the work of the end forces of the last accepted step's closed contacts that this
  /// step started without, ½ (0 − c_end)·d (below), and the energy their springs held at that
  /// end, which left S with no work (released_energy), in a step that re-cut the mesh too; of the
  /// contacts it found sunk with no force carried (a vertex that chattered),
  /// ½ c0·d less the ½ N0·closure0 their springs started with from no work, c0·d taken up to the
  /// gap's close (0 for one the step opens); and of those that close from open (gap0 > 0, no
  /// force carried), ½ N1·gap0: the implicit step applies their end force N1 over its whole
  /// motion, the part before the faces touched too, of which their springs keep ½ N1·closure1;
  /// and of a vertex that ended closed on one edge and starts closed on another (moved_on_work),
  /// ½ (c0 − c_prev)·d + S_prev − S0, and the same of one that starts closed on the same edge with
  /// its springs set afresh (reloaded_work: a tributary length a re-cut shortened); of one found open
  /// with no force at rest on the edge it ended closed on while its vertex or mirror starts closed
  /// elsewhere, which commit does not release, the same ½ (0 − c_end)·d + S_end (open_on_edge_work);
  /// and in a dynamic step, of those that start closed under a carried N0 and end open,
  /// −½ N0·(Δg − closure0): the scheme's trapezoid of their start force beyond the gap's opening
  /// (opened_work).
  void energy_step(const EnergyStep& e, EnergyTerms& t) const override;

  /// Carries on from the contacts of the run's mesh before a re-cut: `history` (mapped onto the
  /// new mesh), the events and what the solves have cost; with `from` (the re-cut's map: null
  /// at a restart) the closed contacts the last accepted step ended with, carried onto the new
  /// mesh (carry_ended).
  void continue_from(const ContactEffect& before, std::vector<ContactHistory> history,
                     const MeshPieces* from = nullptr);
  /// N/m: adds to f (the covers' unknowns) the end forces c_end = N·cn − T·cs of the closed
  /// contacts the last accepted step ended with, carried onto this mesh: the forces the step's
  /// start was in balance with, where they act (crack_release.h: B of a step that re-cut).
  void add_ended_forces(Eigen::VectorXd& f) const;
  /// N/m on the covers' n unknowns, after an accepted step: the end forces of the closed
  /// contacts the step before it ended with, as this step started from them (carried onto the
  /// mesh now where the step re-cut it) — those it released (`released`: its detection found the
  /// vertex closed nowhere) or the others. What tests check the carry with.
  Eigen::VectorXd started_end_forces(Eigen::Index n, bool released) const;
  /// A closed contact at a step's end as the next step starts from it: its edge's point in the
  /// mesh's reference coordinates (which a re-cut keeps), its end shear force and springs' energy.
  struct EndedShear {
    double bx, by;       // m
    double shear_force;  // N, T at that end
    double stored;       // J/m, ½ N·closure + ½ |T·s_el| at that end
  };
  /// After an accepted step: its closed contacts at its end (`started` false), or those of the
  /// step before as this step started from them, carried onto the mesh now where it re-cut.
  std::vector<EndedShear> ended_shear(bool started) const;
  ContactSet& set() { return contacts_; }
  const ContactSet& set() const { return contacts_; }
  const ContactProblem& problem() const { return problem_; }
  /// What the contact solves of the run have cost (summary.json "contact_solve").
  const ContactSolveStats& stats() const { return stats_; }

 private:
  /// Grows the pattern by the step's new element pairs (the rule at update_pattern in
  /// contact_effect.cpp); true: s.pattern_pairs changed.
  bool update_pattern(RunState& s);
  /// Adds contact k's friction, fracture and damped terms of the step to t (energy_step).
  void book_contact(const EnergyStep& e, std::size_t k, EnergyTerms& t) const;
  /// m, the change of contact k's gap over the step's motion d (its row's cn·d).
  double gap_change(std::size_t k, const Eigen::VectorXd& d) const;
  /// m, the change of contact k's gap and shear over the step's motion d (cn·d, cs·d on its row).
  std::pair<double, double> row_motion(std::size_t k, const Eigen::VectorXd& d) const;
  /// J/m, what `damped` gives back for contact k in a dynamic step that it starts closed under
  /// its carried normal force N0 and ends open: −½ N0·(Δg − closure0), the part of the time
  /// scheme's trapezoid of its start force beyond where its gap opened (0 otherwise).
  double opened_work(std::size_t k, const Eigen::VectorXd& d) const;
  /// With NMM_TRACE_ENERGY set: each contact's share of the step's energy, on stderr.
  void trace_energy_step(const EnergyStep& e, const EnergyTerms& t) const;
  /// With NMM_TRACE_PEN set: what a rejected step moved most and its deepest contacts, on stderr.
  void trace_rejected_step(const RunState& s, const Eigen::VectorXd& covers_d) const;

  const Model& model_;
  const CoverSpace& space_;
  ContactSet contacts_;         // detection and the history carried between steps
  ContactProblem problem_;      // the step's rows and Newton kernels
  ContactSolveStats stats_;     // what the contact solves of the run have cost
  Eigen::VectorXd rhs_base_;    // N/m, the right-hand side without contacts
  int first_group_ = 0;         // the first contact-pair group: after the elements' and the bolts'
  // Contacts released between steps (energy_step, `damped`). An accepted step ends in balance
  // with its closed contacts' end forces c_end = N·cn − T·cs on its rows. The next step detects
  // them again in the moved geometry; a vertex that slid past its edge's end onto the next face
  // of a kinked crack finds that face open (the step's linearised edge ran on straight: uniaxial
  // compression h 0.125 m, static, the step after the first crack), so its contact starts the
  // step with no force, and the step starts out of balance by −c_end there besides what the
  // last step's inertia left (which `damped` books from the velocities). The step releases
  // ½ (0 − c_end)·d of it, d its motion: a static step throws that motion away, a dynamic one
  // damps it as any other (energy.cpp (1) with g0 = M a1,prev − c_end). Where such a contact
  // closes again in the step and slides, friction books its slip at the end force, |T|·slip,
  // of which the linear path from 0 took ½: `damped` gives that half back. Not across a
  // restart. Across a re-cut within the step (a crack) the same holds for the contacts the cut
  // mesh's detection does not find closed again: the re-cut carries each of them onto the new
  // mesh (carry_ended) — its vertex by the map's vertex_parent (of a crack's two faces where the
  // crack ends inside its element, its own face's vertex), its edge's point to the piece of
  // the element it was on whose loop runs through it, its row's values to the same local
  // unknowns of the piece (an element's pieces keep its triangle's nodes and cover functions, so
  // w_k p_j at a point are the same numbers) — and the step releases ½ (0 − c_end)·d of them.
  // The cut itself moves no energy: the release is the step's motion against the force it lost.
  struct EndedContact {
    std::int32_t vertex, mirror, edge;  // loop vertices of the mesh now
    std::int32_t elem_a, elem_b;        // the vertex's element, the edge's element
    double bx, by;                      // m, the edge's point in the mesh's reference coordinates
    std::vector<double> force;          // N/m of c_end, [2·element_dofs]: elem_a's local unknowns, elem_b's
    double shear_force = 0;             // N, its T at that end
    double stored = 0;                  // J/m, its springs' ½ N·closure + ½ |T·s_el| at that end
  };
  /// The closed contacts `ended` (of the mesh before a re-cut) carried onto this mesh by `from`;
  /// one whose vertex or edge the re-cut left in no element is dropped.
  std::vector<EndedContact> carry_ended(const std::vector<EndedContact>& ended, const MeshPieces& from) const;
  /// Contact k of the step, found open at its start, is held there by its law (a Barton–Bandis
  /// joint, a force at rest: a cohesive face's traction): an end force on its vertex and edge is
  /// not released.
  bool held_open(std::size_t k) const;
  /// J/m, `damped`'s booking for `e` released at this step's start: ½ (0 − c_end)·d + e.stored.
  double released_energy(const EndedContact& e, const Eigen::VectorXd& d, int nd) const;
  /// J/m, c_end·d of `e` on this space's unknowns (nd: element_dofs()).
  double ended_work(const EndedContact& e, const Eigen::VectorXd& d, int nd) const;
  /// J/m into `damped` (the moved-on rule, contact_effect.cpp): for each vertex the last step
  /// ended closed on one edge (ended_, not released, its pair not among this step's) that starts
  /// this step closed on another (its history carried, its pair not among the ended ones this
  /// step did not release: had()), ½ (c0 − c_prev)·d + S_prev − S0: the old spring released,
  /// the new one loaded at its start gap. Called by commit() before ended_ is replaced, with
  /// ended_pairs_ and commit_released_ set.
  double moved_on_work(const Eigen::VectorXd& d);
  /// J/m into `damped` (the reloaded rule, contact_effect.cpp): for each contact that starts this
  /// step closed on the vertex and edge an ended contact of ended_ this step did not release
  /// (had()) ended on, ½ (c0 − c_prev)·d + S_prev − S0 — its springs set afresh by the
  /// detection (c0, S0: on its tributary length now, which a re-cut that ends a crack on its face
  /// shortens) while the step started in balance with the end force c_prev it carries. Called by
  /// commit() before ended_ is replaced.
  double reloaded_work(const Eigen::VectorXd& d);
  /// J/m into `damped` (contact_effect.cpp): for each contact the last step ended closed with,
  /// not released by commit (its vertex or mirror starts closed elsewhere), that this step finds
  /// open on the same edge with no force at rest (not held_open): its release,
  /// ½ (0 − c_end)·d + S_end. Called by commit() after commit_released_ is set.
  double open_on_edge_work(const Eigen::VectorXd& d);
  /// (vertex, edge) pairs found by their vertex: each loop vertex heads a chain of its few pairs
  /// (a vertex has at most a contact per block). commit() and moved_on_work() look contacts up
  /// in it instead of binary searches over the step's sorted pairs.
  class PairIndex {
   public:
    /// Empties it, for a mesh of `vertices` loop vertices.
    void reset(std::size_t vertices) {
      for (const Entry& e : entries_) head_[static_cast<std::size_t>(e.vertex)] = -1;
      entries_.clear();
      head_.resize(vertices, -1);
    }
    /// Adds (vertex, edge) as `item` (a vertex outside the mesh is left out: no contact of the
    /// mesh has it).
    void add(std::int32_t vertex, std::int32_t edge, std::size_t item) {
      if (vertex < 0 || static_cast<std::size_t>(vertex) >= head_.size()) return;
      std::int32_t& h = head_[static_cast<std::size_t>(vertex)];
      entries_.push_back({vertex, edge, h, static_cast<std::uint32_t>(item)});
      h = static_cast<std::int32_t>(entries_.size() - 1);
    }
    /// visit(item) for each item added as (vertex, edge).
    template <class Visit>
    void for_each(std::int32_t vertex, std::int32_t edge, const Visit& visit) const {
      if (vertex < 0 || static_cast<std::size_t>(vertex) >= head_.size()) return;
      for (std::int32_t i = head_[static_cast<std::size_t>(vertex)]; i >= 0; i = entries_[static_cast<std::size_t>(i)].next)
        if (entries_[static_cast<std::size_t>(i)].edge == edge) visit(static_cast<std::size_t>(entries_[static_cast<std::size_t>(i)].item));
    }
    bool contains(std::int32_t vertex, std::int32_t edge) const {
      bool found = false;
      for_each(vertex, edge, [&](std::size_t) { found = true; });
      return found;
    }

   private:
    struct Entry {
      std::int32_t vertex, edge, next;
      std::uint32_t item;
    };
    std::vector<std::int32_t> head_;  // [loop vertex] its chain's last entry, −1: none
    std::vector<Entry> entries_;
  };
  /// Contact c's (vertex, edge) is among the ended contacts this step did not release (commit()).
  bool had(const Contact& c) const;
  std::vector<EndedContact> ended_;   // the last accepted step's closed contacts
  Eigen::Index end_unknowns_ = -1;    // the unknowns of that step (-2: carried across a re-cut)
  // The list ended_ held before the last commit: the last accepted step's, where that commit was
  // an attempt a re-cut throws away (continue_from carries it, not the attempt's).
  std::vector<EndedContact> start_ended_;
  Eigen::Index start_end_unknowns_ = -1;
  std::vector<std::int32_t> released_;  // sorted vertices of the contacts released at this step's start
  double released_work_ = 0;          // J/m, ½ (0 − c_end)·d of them over this step and their springs' end energy
  std::vector<double> start_shear_;   // N, [contact] the shear force T0 this step started with (commit)
  Eigen::VectorXd trace_d_;           // NMM_TRACE_ENERGY: the accepted step's motion
  std::vector<double> trace_sunk_;    // J/m, NMM_TRACE_ENERGY: [contact] its found-sunk or opened booking (commit)
  // commit()'s scratch, kept between steps: the vertices closed at the step's start (by loop
  // vertex) and sorted (vertex, edge) pairs.
  std::vector<std::uint8_t> commit_closed_;
  std::vector<std::pair<std::int32_t, std::int32_t>> commit_pairs_;
  std::vector<std::size_t> commit_ended_index_;  // commit: the contact each entry of ended_ is
  PairIndex ended_pairs_;  // commit: ended_ by (vertex, edge), as carried into the step (else empty)
  // moved_on_work()'s scratch: this step's contacts by (vertex, edge), the group of each loop
  // vertex, and each group's old and new parts (J/m).
  PairIndex step_pairs_;
  std::vector<std::int32_t> moved_group_;
  std::vector<double> moved_old_, moved_new_;
  std::vector<std::uint8_t> commit_released_;    // commit: [ended_] 1 where this step released it
  std::vector<double> reloaded_n0_;  // N, [contact] N0 its springs were set afresh at (reloaded_work; NaN: not)
  std::vector<std::pair<std::pair<std::int32_t, std::int32_t>, std::size_t>> open_pairs_;  // open_on_edge_work: ((vertex, edge), contact)
};

}  // namespace nmm::solve
