// Intact rock that breaks, as a change of the run's mesh (mesh_change.h; docs/fracture.md): at
// the solution of a step the rock breaks where its stress exceeds its strength (Fracture::find,
// solver/fracture/fracture.h), the new crack segments are cut into the mesh as joints of the
// scene's crack set (preprocess/recut.h, the one cutting code), and the state and contact history
// of the step's start are carried onto the cracked mesh (solver/fracture/state_transfer.h). With
// NMM_CHECK_RECUT set every re-cut is compared with a full cut (recut_check.h).
//
// What the run writes of it (effect_output.h): cracks.csv and cracked_mesh.nmm at the end;
// crack_tips.csv — K_I, K_II at every tip inside a body at every output step
// (solver/fracture/crack_tip_readout.h), for every run that has such a tip, whether or not its
// rock can break (the tips of the scene's joints); summary.json's "fracture" block (with the
// cohesive rock's Hillerborg length; the contacts add what their solve measured of the
// softening: contact_effect.h); the checkpoint's MESH and FRACTURE sections, and the FRACTURE
// bytes in the state hash.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "preprocess/cover_cutter.h"
#include "solver/flow/flow_network.h"
#include "solver/fracture/crack_tip_readout.h"
#include "solver/fracture/fracture.h"
#include "solver/stepping/mesh_change.h"

namespace nmm::solve {

struct RunView;

class FractureEffect final : public MeshChange {
 public:
  /// The cracks of a run on `mesh` (the file's) of `scene`.
  FractureEffect(const Mesh& mesh, const SceneDef& scene);

  bool active() const override { return fracture_.active(); }
  std::size_t joints_added() const override { return fracture_.segments().size(); }
  const std::vector<std::uint8_t>& removed() const override { return fracture_.debris(); }
  /// The uniaxial specimen of docs/fracture.md's matrix took up to 54 re-cuts at its peak; a
  /// bound far above that only stops a cascade that a shorter step would spread.
  int max_per_step() const override { return 200; }
  Outcome cascade(double t) const override;
  bool change(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name, const RunState& solved,
              const std::vector<std::uint8_t>& removed, int dofs_per_cover, RunState& start,
              const std::vector<ContactHistory>& history, const std::vector<Effect*>& effects, NewMesh& out,
              StepTimings& timings) override;
  void book(double seconds, StepTimings& timings) const override { timings.add(kTiming, seconds); }
  void count_resolve() override { fracture_.count_resolve(); }
  /// The cracks and tips (the FRACTURE bytes) once the rock has cracked.
  std::string hashed_state() const override { return fracture_.segments().empty() ? std::string() : fracture_.save(); }
  bool restart(const CheckpointSections& sections, const Mesh& mesh, const SceneDef& scene, const std::string& path,
               NewMesh& out) override;

  std::vector<std::string> output_files() const override { return {"cracks.csv", "cracked_mesh.nmm", "crack_tips.csv"}; }
  void effect_names(const RunState& /*s*/, std::vector<std::string>& names) const override {
    if (active()) names.push_back("fracture");
  }
  /// A cracked run's mesh (MESH: no longer the file's, it travels with the state) and its cracks
  /// (FRACTURE); nothing before the first crack.
  void checkpoint_sections(const RunState& s, const Mesh& mesh, CheckpointSections& sections) const override;
  /// The tips' rows of crack_tips.csv at an output step (step,time,tip,x,y,k1,k2,angle_deg).
  void write_outputs(OutputStep& out) const override;
  /// cracks.csv (a row per crack segment, where its ends were when it formed: docs/interface.md)
  /// and, once the rock has cracked, cracked_mesh.nmm: the mesh the run ended on, for
  /// nmm-inspect (nothing of these without a fracture block); crack_tips.csv when an output step
  /// found a tip.
  void write_files(const OutputStep& out, const std::string& dir) const override;
  /// summary.json "fracture" with a fracture block (docs/interface.md): segments, cracks, their
  /// length and modes, the first crack's step, the elements, the debris, the steps taken again;
  /// where new cracks soften, the rock's Hillerborg length, the longest body and whether a bar
  /// that long snaps back; and "tips" (the tips at the last output step) for a run that wrote
  /// output steps and has a fracture block or found a tip.
  void summarise(const RunState& s, nlohmann::json& summary) const override;
  /// Cohesive cracks that softened faster than the steps followed (summary.json
  /// fracture.snap_back_steps > 0), with what the rock's Hillerborg length predicts.
  void warnings(const nlohmann::json& summary, std::vector<std::string>& lines) const override;
  /// energy.csv's fracture column where the rock can break.
  unsigned energy_columns() const override { return active() ? kFractureColumn : kNoEnergyColumn; }
  /// At the end of a step that cut new cracks: the strain energy they released into t.fracture
  /// (crack_release.h; what softening faces dissipate the contacts book: contact_effect.h).
  void energy_step(const EnergyStep& e, EnergyTerms& t) const override;
  /// summary.json fracture.dissipated_j: energy.csv's fracture column at the last step, where the
  /// rock can break.
  void summarise_energy(const EnergyTerms& totals, nlohmann::json& summary) const override;

  /// The cracks so far and their tips (fracture_of).
  const Fracture& fracture() const { return fracture_; }
  /// summary.json timings: keeping each step's start, strength checks, crack paths, re-cutting
  /// and carrying the state over (s).
  static constexpr const char* kTiming = "fracture";
  std::vector<std::string> timing_names() const override { return {kTiming}; }

 private:
  /// [2·v] Pa: the fluid's pressure on the crack faces of `mesh` in the state s (flow_network.h
  /// face_pressures), empty without flow; the network is built once per mesh.
  std::vector<double> face_pressures(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name,
                                     const RunState& s);

  Fracture fracture_;
  // The check mode's full cut (recut_check.h), kept from one re-cut to the next: one per run.
  pre::GrowingCut full_cut_;
  std::unique_ptr<FlowNetwork> flow_network_;  // of the mesh below (the same derivation as the flow effect's)
  const Mesh* flow_mesh_ = nullptr;
  std::size_t flow_mesh_vertices_ = 0;
  std::size_t elements_ = 0;  // of the mesh the run is on now (the file's, or the last re-cut's)
  // Cohesive softening (docs/fracture.md "Snap-back"): new cracks soften; Hillerborg's length
  // l_ch = E·G_f/σt² of the rock that softens (the smallest), m; the longest body of it (the
  // larger side of its outer boundary's bounding box), m.
  bool cohesive_ = false;
  double characteristic_length_ = 0, longest_body_ = 0;
  // The step (its start's step number) in which a new crack last started: in rock that softens
  // one new crack a step (cohesive_starts.h rule 1). Between steps only, so a restart needs none.
  std::int64_t started_in_step_ = -1;
  // crack_tips.csv as the output steps wrote it: the output's, not the run's state (a restart
  // numbers the tips afresh), hence mutable in the const output stages.
  struct TipRows {
    CrackTipFinder finder;
    std::string rows;              // the CSV's rows so far
    std::int64_t last_step = -1;   // the output step last written (a step is written once)
    bool recorded = false;         // an output step was written
    bool any = false;              // a tip was found at some output step
    int now = 0;                   // tips at the last output step
  };
  mutable TipRows tips_;
};

/// The cracks so far and their tips of a run (its fracture effect; inactive without a fracture
/// block): what the pictures, the Python module, the tests and the benches read of them.
const Fracture& fracture_of(const RunView& run);

/// The tips of the run's state now and their K (crack_tip_readout.h), numbered by `finder`: the
/// crack faces the effects load (Effect::loaded_faces) counted, debris left out.
std::vector<TipReading> read_crack_tips(const RunView& run, CrackTipFinder& finder);

}  // namespace nmm::solve
