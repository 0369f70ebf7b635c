// Intact rock that breaks, as a change of the run's mesh (mesh_change.h; docs/fracture.md): at
// the solution of a step the rock breaks where its stress exceeds its strength (Fracture::find,
// solver/fracture/fracture.h), the new crack segments are cut into the mesh as joints of the
// scene's crack set (preprocess/recut.h, the one cutting code), and the state and contact history
// of the step's start are carried onto the cracked mesh (solver/fracture/state_transfer.h). With
// NMM_CHECK_RECUT set every re-cut is compared with a full cut (recut_check.h).
#pragma once

#include <memory>

#include "solver/flow/flow_network.h"
#include "solver/fracture/fracture.h"
#include "solver/stepping/mesh_change.h"

namespace nmm::solve {

class FractureEffect final : public MeshChange {
 public:
  explicit FractureEffect(const SceneDef& scene) : fracture_(scene) {}

  bool active() const override { return fracture_.active(); }
  std::size_t joints_added() const override { return fracture_.segments().size(); }
  const std::vector<std::uint8_t>& removed() const override { return fracture_.debris(); }
  /// The uniaxial specimen of docs/fracture.md's matrix took up to 54 re-cuts at its peak; a
  /// bound far above that only stops a cascade that a shorter step would spread.
  int max_per_step() const override { return 200; }
  Outcome cascade(double t) const override;
  bool change(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name, const RunState& solved,
              const std::vector<std::uint8_t>& removed, int dofs_per_cover, RunState& start,
              const std::vector<ContactHistory>& history, NewMesh& out, StepTimings& timings) override;
  void book(double seconds, StepTimings& timings) const override { timings.fracture += seconds; }
  void count_resolve() override { fracture_.count_resolve(); }
  bool restart(const CheckpointSections& sections, const Mesh& mesh, const SceneDef& scene, const std::string& path,
               NewMesh& out) override;

  std::vector<std::string> output_files() const override { return {"cracks.csv", "cracked_mesh.nmm"}; }
  void effect_names(const RunState& /*s*/, std::vector<std::string>& names) const override {
    if (active()) names.push_back("fracture");
  }
  /// A cracked run's mesh (MESH: no longer the file's, it travels with the state) and its cracks
  /// (FRACTURE); nothing before the first crack.
  void checkpoint_sections(const Mesh& mesh, CheckpointSections& sections) const override;
  /// cracks.csv (a row per crack segment, where its ends were when it formed: docs/interface.md)
  /// and, once the rock has cracked, cracked_mesh.nmm: the mesh the run ended on, for
  /// nmm-inspect. Nothing without a fracture block.
  void write_files(const OutputStep& out, const std::string& dir) const override;

  /// The cracks so far and their tips (RunView::fracture).
  const Fracture& fracture() const { return fracture_; }

 private:
  /// [2·v] Pa: the fluid's pressure on the crack faces of `mesh` in the state s (flow_network.h
  /// face_pressures), empty without flow; the network is built once per mesh.
  std::vector<double> face_pressures(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name,
                                     const RunState& s);

  Fracture fracture_;
  std::unique_ptr<FlowNetwork> flow_network_;  // of the mesh below (the same derivation as the flow effect's)
  const Mesh* flow_mesh_ = nullptr;
  std::size_t flow_mesh_vertices_ = 0;
};

}  // namespace nmm::solve
