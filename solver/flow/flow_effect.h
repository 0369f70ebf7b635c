// Fluid flow along the joints as an effect of the step (effect.h; docs/flow.md): the flow
// network (flow_network.h) carries a pressure field that the step's volume balance
// (flow_balance.h) moves on, and the pressure loads both faces of every joint.
//
// Coupling scheme: staggered, one flow solve per mechanical step. At the start of each attempt
// (begin_step) the balance is solved over the attempt's Δt; the resulting pressures at the
// step's end load the joint faces as a traction t = −p·n (linear between the nodes, integrated
// like a boundary traction: boundary_conditions.h) in every solve round of the step; commit keeps
// the pressures and apertures of the accepted step. A rejected step solves the flow again with
// its shorter Δt. Why staggered: the flow unknowns stay out of the mechanical system, whose
// pattern, factorisation and contact solve are unchanged, and the flow matrix (symmetric, of the
// network's nodes) is factorised on its own, once per attempt.
// Apertures: in a steady run (`steady`) they are those of the faces at the step's start, one
// step behind the mechanics; the steady pressures lie between the boundaries' (and grow with
// the injections), whatever the apertures, so the lag settles as the faces do. In a transient
// run they stay at the run's start: a staggered split that lets them follow the faces is
// unstable wherever an open joint is more compliant than its fluid is compressible (one node:
// pressure changes grow by the factor c·K_f/V per step, c the joint's opening per pressure, V its
// fluid volume — thousands for an opened joint), and the fixed-stress prediction that cures it
// needs a compliance we could not yet estimate well enough (docs/flow.md "Not yet"). So transient
// coupling is one-way: the pressure loads the faces, the faces do not change the flow.
// `coupled: false`: the apertures stay those at the run's start and the pressure does not load
// the faces (flow alone).
// With fracture, a re-cut builds the effect again on the cut mesh, whose network holds the new
// cracks; continue_from carries the pressures and apertures onto it (flow_transfer.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "solver/discretisation/cover_space.h"
#include "solver/discretisation/effect.h"
#include "solver/discretisation/model.h"
#include "solver/flow/flow_balance.h"
#include "solver/flow/flow_network.h"

namespace nmm::solve {

class FlowEffect final : public Effect {
 public:
  /// The flow of `model`'s scene on `space` (both outlive it).
  FlowEffect(const Model& model, const CoverSpace& space);
  ~FlowEffect() override;

  bool active() const override { return model_.scene().flow.present; }
  /// Starts the flow (initial pressure, the apertures and volumes of the state) or carries on a
  /// checkpoint's; a checkpoint of another network is an InputError naming `name`.
  bool install(RunState& s, const std::string& name) override;
  Outcome begin_step(EffectStep& step) override;
  void add_at_rest(EffectStep& rest) override;
  void assemble(EffectStep& step) override;
  void commit(EffectStep& step, const Eigen::VectorXd& d) override;
  /// summary.json "flow" (docs/interface.md "Fluid flow in joints and cracks").
  void summarise(const RunState& s, nlohmann::json& summary) const override;
  /// flow.csv: per output step one row per node of the network, step,time,node,x,y,pressure,
  /// aperture — x, y where the node is in the mesh as cut (m), its pressure (Pa) and the mean
  /// hydraulic aperture of the segments that end there (m), as the accepted state holds them.
  std::vector<std::string> output_files() const override { return {"flow.csv"}; }
  void write_outputs(OutputStep& out) const override;
  /// The frame's part "flow" (frames/flow_<step>.vtu): one line cell per segment between the
  /// nodes where the faces are (the mesh as cut plus the nodes' displacement). Point data
  /// "pressure" (Pa), "aperture" (m, as in flow.csv), "boundary" (the `boundaries` entry that
  /// holds the node, −1 free), "displacement" (m); cell data "joint", "aperture" (m, the mean
  /// of the segment's ends), "flux" (m²/s = m³/s per m of thickness, the cubic law's rate
  /// C·(φ_a − φ_b) along the segment's direction a → b, a vector for ParaView's glyphs).
  void frame_parts(const OutputStep& out, std::vector<FramePart>& parts) const override;
  void effect_names(const RunState& /*s*/, std::vector<std::string>& names) const override {
    if (active()) names.push_back("flow");
  }
  /// FLOW (docs/checkpoint-format.md), with flow: the network's pressures, apertures and boundary
  /// rates, then the volumes and the work since step 0 (sizes checked against the network by
  /// install()).
  void checkpoint_sections(const RunState& s, const Mesh& mesh, CheckpointSections& sections) const override;
  void restore_sections(const CheckpointSections& sections, const Mesh& mesh, const std::string& name,
                        RunState& s) const override;

  /// |stored − (injected − outflow)| over the volume exchanged (injected and through the
  /// boundaries either way) or stored, whichever is larger (summary.json balance_error).
  double balance_error(const RunState& s) const;
  /// After cracks re-cut the mesh: the flow state of `before` (the effect on the mesh before)
  /// in `s` carried onto this network (flow_transfer.h).
  void continue_from(const FlowEffect& before, RunState& s) const;
  /// The network (flow.csv, tests); empty without a flow block.
  const FlowNetwork& network() const { return network_; }
  void face_pressures(const RunState& s, std::vector<double>& pressure) const override;
  /// Energy (effect_energy.h): the work of the fluid's pressure on the joint and crack faces the
  /// steps counted in the state (RunState::flow_load_work) into t.work.
  void energy_state(const EnergyState& e, EnergyTerms& t) const override;

 private:
  /// N per unknown of the covers: the pressure `p` ([node] Pa) on every joint face of the state s.
  Eigen::VectorXd face_forces(const StepContext& context, const RunState& s, const std::vector<double>& p) const;

  const Model& model_;
  const CoverSpace& space_;
  FlowNetwork network_;
  std::unique_ptr<FlowBalance> balance_;
  // The attempt's solution (begin_step), committed if the step is accepted.
  FlowStepResult step_;
  std::vector<double> aperture_;
  Eigen::VectorXd load_;  // N per cover unknown, the step's face forces
};

}  // namespace nmm::solve
