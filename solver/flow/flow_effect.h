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
// the injections), whatever the apertures, so the lag settles as the faces do.
// Transient and coupled: two-way, iterated within the step (fixed-stress split). The first
// solve round loads the faces with the lower, per node, of the start's pressure and the
// balance's at the start's apertures (begin_step says why); at each solution d
// (judge) the apertures a^k of the faces moved by d give the step's end volumes V^k and
// conductances, and the balance is solved again with the storage term of flow_balance.h,
//   [V^k(1 + p/K_f) − V⁰(1 + p⁰/K_f) + c·(p − p^k)] / Δt,
// c_i the node's compliance (m³/Pa per m): the volume its faces give when the pressure on every
// face rises by 1 Pa, Δw from one solve of the step's factorised system with that load (the
// row sums of the faces' compliance matrix, which bound it where its entries are positive — a
// crack or a joint between layers — so the split converges: error factor (D − A)(S + T + D)⁻¹,
// |·| < 1 for D ≥ A/2; the plain fixed point, c = 0, grows by c·K_f/V per iteration, thousands
// for an open joint). Where the faces touch at the step's start the factorisation holds their
// contact springs, and c is at least a Griffith crack's (compliance()). The pressures x that
// load the faces next are G(x), the balance's, mixed by Anderson (accelerate()). Converged when the volume the split still carries, Σ c_i·|p_i^{k+1} −
// p_i^k|, is at most kTolerance of the step's exchanged (and stored) volume; the mechanics is
// solved again with the new pressures until then, or until the error stalls at the mechanical
// solve's round-off within kStallTolerance (judge()), up to kMaxIterations solves, past which the
// step is cut (StopCode::flow_not_converged). The committed step has the last balance's
// pressures on the faces of the last solution: stored = injected − outflow to the tolerance.
// NMM_TRACE_FLOW=1 prints each iteration's error (stderr).
// `coupled: false`: the apertures stay those at the run's start and the pressure does not load
// the faces (flow alone).
// Fluid lag (`cavitation_pressure`): each balance solve is flow_balance.h's with the vapour
// RunState::flow_void of the step's start, its pressures never below p_c, and the iterate that
// loads the faces is held at p_c or above (Anderson's extrapolation could reach below); commit
// keeps the step's vapour with its pressures.
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
  /// Two-way transient coupling: the balance again at the apertures of the solution d; true
  /// while the pressures still move (header comment).
  bool judge(const Eigen::VectorXd& d) override;
  int max_solves() const override { return two_way() && !diverged_ ? kMaxIterations : 1; }
  Outcome not_settled(double t) const override;
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
  /// In a step that cut cracks, the fluid's part of what they released into t.fracture
  /// (crack_release.h: ½ ΔP·d, the change from the start's pressure on the new faces to the end's).
  void energy_step(const EnergyStep& e, EnergyTerms& t) const override;

  /// The two-way coupling's cost: accepted steps, and the balance solves (one per solve round
  /// of the mechanics) they took, since this effect was built (a re-cut builds it again).
  struct Iterations {
    long steps = 0, solves = 0, worst = 0;
  };
  const Iterations& iterations() const { return iterations_; }

  /// Relative volume tolerance of a step's coupling iterations (header comment).
  static constexpr double kTolerance = 1e-6;
  /// The round-off floor (judge()): a step whose split brought its smallest error down by no
  /// half over kStall solves is settled once that error is within kStallTolerance of the step's
  /// volume.
  static constexpr int kStall = 6;
  static constexpr double kStallTolerance = 1e-4;
  /// With a fluid lag, the factor on the compliance c of the split (judge()).
  static constexpr double kLagCompliance = 2;
  /// Balance solves of one step attempt before it is cut.
  static constexpr int kMaxIterations = 60;

 private:
  bool two_way() const {
    const FlowDef& f = model_.scene().flow;
    return active() && f.coupled && !f.steady;
  }
  /// The vapour at the step's start with a fluid lag (flow_balance.h), else null.
  const std::vector<double>* lag_start(const RunState& s) const {
    return model_.scene().flow.cavitation && s.flow_void.size() == network_.nodes() ? &s.flow_void : nullptr;
  }
  /// [2·v] m: `base` with the network's face vertices (at loop_xy, [2·v] m) moved by what the
  /// covers' increment d gives them.
  std::vector<double> moved_loop_u(const StepContext& context, const std::vector<double>& loop_xy,
                                   const std::vector<double>& base, const Eigen::VectorXd& d) const;
  /// The pressures to load the faces with next, from the last x and G(x) (Anderson mixing).
  std::vector<double> accelerate(const std::vector<double>& x, const std::vector<double>& g);
  /// [node] m³/Pa per m, the compliance c_i of the header comment, from the step's system.
  std::vector<double> compliance(EffectStep& step) const;
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
  // Two-way: the attempt's step (begin_step to commit), the volumes at its start, the compliance,
  // the solves so far and the split's last volume error (m³ per m).
  EffectStep* attempt_ = nullptr;
  std::vector<double> volume0_, compliance_;
  int solves_ = 0;
  double split_error_ = 0;
  bool diverged_ = false;  // the split gave a pressure that is not finite: cut the step
  std::vector<double> iterate_;  // Pa, the pressures on the faces of the solve round (x)
  // Anderson mixing's differences of the residuals and of G over the last kDepth iterates.
  static constexpr int kDepth = 8;
  std::vector<Eigen::VectorXd> history_f_, history_g_;
  Eigen::VectorXd last_f_, last_g_;
  bool have_last_ = false;
  std::vector<char> lagging_;  // [node] 1: at the cavitation pressure in the last G(x) (lag only)
  double last_carried_ = 0;  // m³ per m, the split's error at the last iterate
  double best_carried_ = 0;  // m³ per m, the smallest error of the attempt (halvings only)
  int best_at_ = 0;          // the solve that brought it
  Iterations iterations_;
  std::vector<double> joint_length_;     // [joint] m, its segments' lengths summed
  std::vector<double> segment_modulus_;  // [segment] Pa, D₁₁ of the stiffer element on its faces
  std::vector<std::int32_t> vertex_element_;  // [end vertex] its element (moved_loop_u)
};

}  // namespace nmm::solve
