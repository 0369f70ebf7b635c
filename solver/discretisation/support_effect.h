// The supports' reactions as an effect of the step (effect.h): the supports' penalty springs are
// an integrator of the step's form (integrators.h support_terms); what this adds is what they
// carry — at each accepted step's solution the force each support exerts on the body
// (support_reaction.h), kept for the run's outputs: reactions.csv at every output step, one row
// per support (docs/interface.md "Support reactions": step,time,support,fx,fy,travel), and
// summary.json "supports" at the end. It adds no term and no unknown, and keeps nothing in the
// run state: of a state no step has reached yet (a run's start, a restart's) the reactions are
// the state's own (support_reaction.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/discretisation/effect.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/support_reaction.h"

namespace nmm::solve {

class SupportEffect final : public Effect {
 public:
  /// The supports of `model`'s scene (it outlives this).
  explicit SupportEffect(const Model& model) : model_(model) {}

  bool active() const override { return !model_.support_edges().empty(); }
  /// The reactions at the accepted step's solution d (before the covers move).
  void commit(EffectStep& step, const Eigen::VectorXd& d) override;

  /// Every support's reaction in state s: those of the step that reached it, else the state's own.
  std::vector<SupportReaction> reactions(const RunState& s) const;

  std::vector<std::string> output_files() const override { return {"reactions.csv"}; }
  /// reactions.csv: one row per support at the output step.
  void write_outputs(OutputStep& out) const override;
  /// summary.json "supports": per support at the end, "fx_n_per_m", "fy_n_per_m", "travel_m",
  /// "direction" (the unit vector of its velocity; [0, 0] held) and "load_n_per_m" (the force
  /// along it: what a loading platen applies).
  void summarise(const RunState& s, nlohmann::json& summary) const override;

 private:
  const Model& model_;
  std::vector<SupportReaction> last_;  // at the solution of the last accepted step
  std::int64_t last_step_ = -1;        // the step number of the state it reached
};

}  // namespace nmm::solve
