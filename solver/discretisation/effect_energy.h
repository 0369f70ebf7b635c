// An effect's part of the run's energy balance (energy.csv; solver/output/energy.h has the
// balance, docs/energy.md its columns): the energy meter sums what the effects report and names
// none of them. With S_e the elastic energy an effect holds, W_e the work it does on the rock
// and D_e what it dissipates, in the column it books it in (friction, absorbed, fracture):
//
//   springs    S = S_meter + Σ_e S_e(state)                     (the meter's own: fixed points, supports)
//   load_work  W = W_meter + Σ_steps Σ_e ΔW_e(step) + Σ_e [W_e(state) − W_e(first row)]
//   friction   D = Σ_steps Σ_e ΔD_e(step) + Σ_e [D_e(state) − D_e(first row)]      (same for A, F)
//   residual   R = W − D − A − Q − F − Δ(K + U + V + S)         (Q, the time scheme's, is the meter's)
//
// Two ways to report, as the effect keeps its books:
//   energy_state  from the accepted state alone: S_e, and the totals the steps count in the state
//                 (a bolt's plastic work, the dashpots' work): the meter takes the first row's off
//   energy_step   what the step since the meter's last call added, from the state before and
//                 after it (a contact's slip, the water pressure's work on the faces' motion, the
//                 strain energy a crack released)
// Each adds its terms to the sums it is handed (+=), term by term: the meter keeps one order of
// summation, so energy.csv keeps its bytes (the order of the list: mesh_bound.h `metered`).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/mesh.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

class Model;

/// J/m (per metre of thickness): terms of the energy balance.
struct EnergyTerms {
  double stored = 0;    ///< J/m, S_e: elastic energy held in springs (energy.csv springs)
  double work = 0;      ///< J/m, W_e: work done on the rock (load_work)
  double friction = 0;  ///< J/m, D_e: dissipated by friction and plastic slip (friction)
  double absorbed = 0;  ///< J/m, D_e: taken out through the model's boundary (absorbed)
  double fracture = 0;  ///< J/m, D_e: dissipated by cracking (fracture)
  /// J/m, Q_e: what the step released of a start out of balance by the effect's forces' jump
  /// between steps, which the step's motion takes (`damped`: a static step throws it away, a
  /// dynamic one damps it); the step's own, not a total
  double damped = 0;
};

/// energy.csv's optional columns an effect owns: they appear where it takes part.
enum EnergyColumns : unsigned {
  kNoEnergyColumn = 0,
  kAbsorbedColumn = 1u << 0,  ///< absorbed
  kFractureColumn = 1u << 1,  ///< fracture
};

/// What an effect reads to report its terms of an accepted state (energy_state).
struct EnergyState {
  const Model& model;  ///< the run's model on the state's mesh (scene, mesh, materials)
  const RunState& s;   ///< the accepted state
};

/// What an effect reads to report the step since the meter's last call (energy_step).
struct EnergyStep {
  const Model& model;  ///< the run's model on the state's mesh
  const RunState& s;   ///< the accepted state at the step's end
  /// [2·v] m, the loop vertices' displacements at the meter's last call, carried onto s's mesh
  /// (empty on the first call).
  const std::vector<double>& last_loop_u;
  /// The step changed the mesh (mesh_change.h): its start carried onto the new mesh (its
  /// loop_xy, loop_u, stress: state_transfer.h), else null.
  const RunState* changed_start;
  /// The scene's joints at the meter's last call (those after them the step's change added).
  std::size_t joints_before;
  /// J/m, on a step that changed the mesh: r·d, the work over the step of the force r its start,
  /// carried onto the new mesh, is out of balance by because of the change (the faces it opened:
  /// solver/fracture/crack_release.h), d the step's motion; 0 otherwise.
  double cut_work = 0;
};

class EffectEnergy {
 public:
  /// energy.csv's optional columns it owns (EnergyColumns), where it takes part.
  virtual unsigned energy_columns() const { return kNoEnergyColumn; }
  /// Adds to t its terms of the accepted state: t.stored what it holds now, the other fields its
  /// totals counted in the state (the meter takes those of its first call off).
  virtual void energy_state(const EnergyState& /*e*/, EnergyTerms& /*t*/) const {}
  /// Adds to t what the step since the meter's last call added: t.work into the step's work, the
  /// dissipation into the run's totals (t.stored is not read).
  virtual void energy_step(const EnergyStep& /*e*/, EnergyTerms& /*t*/) const {}
  /// Its part of summary.json from the run's energy totals `totals` (energy.csv's last row: the
  /// cracks' fracture.dissipated_j).
  virtual void summarise_energy(const EnergyTerms& /*totals*/, nlohmann::json& /*summary*/) const {}

 protected:
  EffectEnergy() = default;
  EffectEnergy(const EffectEnergy&) = default;
  EffectEnergy& operator=(const EffectEnergy&) = default;
  ~EffectEnergy() = default;
};

/// The element's body is excavated in state s: it holds no energy and nothing works on it.
inline bool element_removed(const Mesh& mesh, const RunState& s, std::int32_t element) {
  const std::int32_t body = mesh.element_body[static_cast<std::size_t>(element)];
  return static_cast<std::size_t>(body) < s.body_removed.size() && s.body_removed[static_cast<std::size_t>(body)];
}

}  // namespace nmm::solve
