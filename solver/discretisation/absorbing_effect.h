// The absorbing boundaries as an effect of the step (effect.h): their dashpots and input traction
// are integrators of the form (absorbing_boundary.h absorbing_terms); what they keep from step to
// step is the carried reaction — the force that balances the state's out-of-balance force on the
// boundary's elements, taken once at the step that starts the run (or when the polylines change:
// absorbing_reaction_due) from the host's force at rest — and the work the dashpots take out and
// the input traction and the reaction do, summed on each accepted step (absorbing_work).
#pragma once

#include <string>

#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/effect.h"
#include "solver/discretisation/model.h"

namespace nmm::solve {

class AbsorbingEffect final : public Effect {
 public:
  /// The absorbing boundaries of `model`'s scene on `space` (both outlive it).
  AbsorbingEffect(const Model& model, const CoverSpace& space) : model_(model), space_(space) {}

  bool active() const override { return !model_.scene().absorbing.empty(); }
  /// A checkpoint's carried reaction where its scene had the same polylines (else it is taken
  /// again at the first step); none kept, and no work, when the scene has no absorbing boundary.
  bool install(RunState& s, const std::string& name) override;
  /// After cracks re-cut the mesh: the carried reaction onto the new covers (absorbing_boundary.h
  /// absorbing_reaction_onto; the dashpots are laid by the new model on the re-cut edges); the
  /// work so far is the state's and carries on unchanged.
  void carry_over(const MeshPieces& from, RunState& s) const override;
  Outcome begin_step(EffectStep& step) override;
  void commit(EffectStep& step, const Eigen::VectorXd& d) override;
  void effect_names(const RunState& /*s*/, std::vector<std::string>& names) const override {
    if (active()) names.push_back("absorbing");
  }
  /// ABSORB (docs/checkpoint-format.md), once a reaction has been taken: the polylines it was
  /// taken for, the reaction, the dashpots' and the input's work.
  void checkpoint_sections(const RunState& s, const Mesh& mesh, CheckpointSections& sections) const override;
  void restore_sections(const CheckpointSections& sections, const Mesh& mesh, const std::string& name,
                        RunState& s) const override;
  /// energy.csv's absorbed column with absorbing boundaries.
  unsigned energy_columns() const override { return active() ? kAbsorbedColumn : kNoEnergyColumn; }
  /// Energy (effect_energy.h): what the steps counted in the state (absorbing_boundary.h
  /// absorbing_work) — the dashpots' take Σ_steps v1ᵀC_e d into t.absorbed, the work of the input
  /// traction and the carried reaction into t.work.
  void energy_state(const EnergyState& e, EnergyTerms& t) const override {
    t.absorbed += e.s.absorbed_work;
    t.work += e.s.absorbing_load_work;
  }

 private:
  const Model& model_;
  const CoverSpace& space_;
};

}  // namespace nmm::solve
