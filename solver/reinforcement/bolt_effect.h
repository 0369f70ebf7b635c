// The bolts as an effect of the step (effect.h): a BoltSystem (bolt_system.h) behind the one
// interface the stepper loops over — the bolts a run installs or carries on (bolt_layout.h),
// their slips as unknowns of their own after the covers', their coupling groups after the
// elements', each step's springs linearised at its start, judged at its solution (solve again
// while a spring switches, up to BoltSystem::kMaxRounds solves) and committed on the accepted
// step into RunState::bolts. When cracks re-cut the mesh, the bolts are tied again to the pieces
// of rock their points lie in (carry_over), so a bolt holds the pieces a crack parts.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "solver/discretisation/effect.h"
#include "solver/discretisation/model.h"
#include "solver/reinforcement/bolt_system.h"

namespace nmm::solve {

class BoltEffect final : public Effect {
 public:
  /// The bolts of `model`'s scene on `space` (both outlive it); `scene_name` names the scene in
  /// an error about a bolt's points.
  BoltEffect(const Model& model, const CoverSpace& space, const std::string& scene_name)
      : model_(model), scene_name_(scene_name), bolts_(model, space) {}

  bool active() const override { return count_ > 0; }
  bool install(RunState& s, const std::string& name) override;
  void number(const RunState& s, int first_unknown, std::size_t first_group) override;
  int unknowns() const override { return bolts_.unknowns(); }
  std::size_t groups(const RunState& /*s*/) const override { return bolts_.groups(); }
  void add_groups(const RunState& s, std::vector<int>& offsets, std::vector<int>& dofs) const override;
  std::string describe_unknown(int unknown) const override { return bolts_.describe_unknown(unknown); }
  /// After cracks re-cut the mesh: each bolt's points tied again to the pieces of rock that hold
  /// them (bolt_layout.h retie_bolts); its forces, slips and history carried unchanged.
  void carry_over(const MeshPieces& from, RunState& s) const override;
  Outcome begin_step(EffectStep& step) override;
  void add_at_rest(EffectStep& rest) override;
  void assemble(EffectStep& step) override;
  bool judge(const Eigen::VectorXd& d) override { return bolts_.judge(d); }
  int max_solves() const override { return BoltSystem::kMaxRounds; }
  Outcome not_settled(double t) const override;
  void commit(EffectStep& step, const Eigen::VectorXd& d) override;
  /// summary.json "bolts" (docs/interface.md "Rock bolts and cables"): per bolt its largest axial
  /// force so far (N per bolt), whether its steel yielded (grouted) or it broke (anchored); and
  /// beyond the contract its type, the step it was installed at and a cable's largest grout slip (m).
  void summarise(const RunState& s, nlohmann::json& summary) const override;
  std::vector<std::string> output_files() const override { return {"bolts.csv"}; }
  void effect_names(const RunState& s, std::vector<std::string>& names) const override {
    if (!s.bolts.empty()) names.push_back("bolts");
  }
  /// bolts.csv at an output step (docs/interface.md): one row per point of each bolt
  /// (bolt_readout.h), bolts in the scene's order; beyond the contract each point's position and
  /// displacement (m).
  void write_outputs(OutputStep& out) const override;
  /// BOLTS (docs/checkpoint-format.md), with bolts: u32 layout 1, u64 n, per bolt its type, the
  /// scene's points it was installed for, installation step, flags, largest force, plastic work,
  /// its nodes (as POINTS) and its axial forces, slips and grout forces.
  void checkpoint_sections(const RunState& s, const Mesh& mesh, CheckpointSections& sections) const override;
  void restore_sections(const CheckpointSections& sections, const Mesh& mesh, const std::string& name,
                        RunState& s) const override;
  /// Energy (effect_energy.h): the springs' elastic energy into t.stored (bolt_elastic_energy:
  /// N²/(2k) per spring over the spacing), the plastic work the steps counted in the state
  /// (grout slip, steel yield: BoltState::plastic_work) into t.friction.
  void energy_state(const EnergyState& e, EnergyTerms& t) const override;

 private:
  const Model& model_;
  std::string scene_name_;
  BoltSystem bolts_;
  std::size_t first_group_ = 0;  // the bolts' first coupling group: after the elements'
  std::size_t count_ = 0;        // bolts of the run (0: none installed, nothing to do)
};

}  // namespace nmm::solve
