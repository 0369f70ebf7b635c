// The run state: everything a run carries from one step to the next, as a plain struct, so that
// it can be written to a checkpoint and a run continued from it bitwise exactly
// (docs/interface.md "Rock-engineering set-ups and restart"; file layout: docs/checkpoint-format.md).
//
// Rule: anything the next step reads and an earlier step wrote lives here (or in the contact
// history, saved by contact_history.h). What a TimeStepper derives from the mesh and the scene
// (element groups, material matrices, element frames) does not.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/checkpoint_file.h"
#include "common/mesh.h"
#include "solver/discretisation/state_bytes.h"

namespace nmm::solve {

/// A point carried by the deforming body (fixed point, load point, measure point).
struct TrackedPoint {
  std::int32_t element = -1;  ///< element it lies in
  double x0 = 0, y0 = 0;      ///< m, where it started
  double x = 0, y = 0;        ///< m, where it is now
  /// m, its displacement since the start.
  std::array<double, 2> displacement() const { return {x - x0, y - y0}; }
};

/// s, RunState::dt before the first step: longer than any time_step, so step control starts at
/// time_step (StepControl takes the smaller). Finite, not infinity, because Δt is saved in the
/// checkpoint's META section and hashed into state hashes: a checkpoint written before the first
/// step keeps the bytes it has always had.
constexpr double kDtBeforeFirstStep = 1e300;
/// A rock bolt's or cable's state carried from step to step (solver/reinforcement/bolt_step.h;
/// docs/reinforcement.md). Forces are per bolt; the model feels them divided by its spacing.
struct BoltState {
  std::uint8_t type = 0;        ///< 0 anchored, 1 grouted (BoltType)
  /// m, the scene's points it was installed for: a restart continues a bolt whose type and
  /// points are still the scene's, and installs any other afresh (bolt_layout.h)
  double ax = 0, ay = 0, bx = 0, by = 0;
  std::int64_t installed_step = 0;  ///< the step it was installed at (0, or a restart's)
  std::uint8_t broken = 0;      ///< anchored: its axial force reached its strength (0 since)
  std::uint8_t yielded = 0;     ///< grouted: a segment's axial force reached the yield force
  double max_axial = 0;         ///< N per bolt, the largest |axial force| so far
  double plastic_work = 0;      ///< J/m, work of grout slip and steel yield so far (per m of model)
  /// The rock points the bolt is tied to, carried by the rock: anchored its two ends, grouted
  /// its n + 1 segment points (element, installed and current position)
  std::vector<TrackedPoint> nodes;
  std::vector<double> axial;    ///< [segments] N per bolt, axial force, tension positive (anchored: 1)
  std::vector<double> slip;     ///< [nodes] m, the cable's displacement along its axis relative to the rock (grouted)
  std::vector<double> bond;     ///< [nodes] N per bolt, the grout's force on the cable at each node (grouted)
};

struct RunState {
  std::int64_t step = 0;  ///< steps completed since step 0 of the first run
  double time = 0;        ///< s, simulated time
  double dt = kDtBeforeFirstStep;  ///< s, the step length step control has arrived at
  std::vector<double> cover_xy;  ///< [2·pc] m, current position of each cover's node
  /// Per cover, its cover-function coefficients (m per cover = 2, 6, 12 at order 0, 1, 2;
  /// cover_space.h): [m·pc]
  std::vector<double> cover_u;   ///< [m·pc] m, displacement since the start
  std::vector<double> velocity;  ///< [m·pc] m/s, v0 of the next step
  std::vector<double> accel;     ///< [m·pc] m/s², a0 of the next step
  bool accel_known = false;      ///< a0 comes from a step (else the next step takes β = ½)
  /// [3·T·me] Pa, σxx σyy τxy (tension positive): per element T = (n+1)(n+2)/2 coefficients of
  /// the stress polynomial in its scaled frame coordinates (n = 0: the element's stress)
  std::vector<double> stress;
  std::vector<double> loop_xy;   ///< [2·v] m, current loop vertices
  std::vector<double> loop_u;    ///< [2·v] m, displacement since the start
  std::vector<TrackedPoint> fixed, loads, measure;
  /// element pairs the system matrix pattern holds (contact_effect.cpp update_pattern; kept so
  /// that a restarted run factorises the same pattern, hence the same round-off, as the
  /// straight run)
  std::vector<std::pair<std::int32_t, std::int32_t>> pattern_pairs;
  /// [3·block] N/m, N/m, N·m/m: the net out-of-balance force (x, y) and moment the last step left
  /// on each block, applied in the next step (block_momentum.h); empty: none (static runs, steps
  /// in balance at their start)
  std::vector<double> block_force;
  /// [bolt] the scene's rock bolts and cables (solver/reinforcement/); empty: none
  std::vector<BoltState> bolts;
  /// Absorbing boundaries (absorbing_boundary.h): the polylines the carried reaction was taken
  /// for (absorbing_key(); empty: none taken), and the reaction, [cover unknowns] N/m
  std::vector<double> absorbing_key;
  std::vector<double> absorbing_reaction;
  double absorbed_work = 0;        ///< J/m since step 0 of the first run: taken out by the dashpots
  double absorbing_load_work = 0;  ///< J/m, likewise: done by the input traction and the carried reaction
  /// Fluid flow along the joints (solver/flow/; empty: none), on the flow network's nodes and
  /// segments (flow_network.h), as the last accepted step left them
  std::vector<double> flow_pressure;   ///< [node] Pa
  std::vector<double> flow_aperture;   ///< [2·segment] m, hydraulic aperture at each segment end
  /// [node] m³ per m, the vapour each node holds: its volume less its fluid's (the fluid lag,
  /// flow_balance.h); empty without `cavitation_pressure`
  std::vector<double> flow_void;
  std::vector<double> flow_outflow_rate;  ///< [boundary] m³/s per m leaving through each `boundaries` entry
  double flow_injected = 0;   ///< m³ per m since step 0 of the first run, injected
  double flow_outflow = 0;    ///< m³ per m likewise, left through the boundaries (net)
  double flow_stored = 0;     ///< m³ per m likewise, the change of the volume the network holds
  double flow_load_work = 0;  ///< J/m likewise, done by the pressure on the joint faces
  double flow_exchanged = 0;  ///< m³ per m likewise, injected and through the boundaries in either direction
  double flow_filled = 0;     ///< m³ per m likewise, put into new cracks at the pressure carried to them (flow_transfer.h)
  std::vector<std::uint8_t> body_removed;      ///< [body] 1: excavated
  std::vector<std::int64_t> body_removed_at;   ///< [body] step at which it was excavated, or -1
  // Diagnostics over all runs (summary.json), not physics:
  std::uint64_t iterations = 0;          ///< open–close iterations (solves)
  std::uint64_t cuts = 0;                ///< time-step cuts
  std::uint64_t friction_unsettled = 0;  ///< steps taken with friction forces still moving
  std::uint64_t max_capped = 0;          ///< most contacts held below Vm after one step
  double max_penetration = 0;            ///< m
  double max_step_displacement = 0;      ///< m
};

/// The checkpoint sections of a state, its contact history (contact_history.h) and the mesh it
/// belongs to (identified by counts and the SHA-256 of its embedded scene): the run state's own,
/// META to DIAG and CARRY. The effects write the sections of the state they carry after them
/// (effect_output.h checkpoint_sections; the whole checkpoint: solver/stepping/restart.h).
CheckpointSections state_to_sections(const RunState& s, const std::string& contact_history,
                                     const Mesh& mesh);

/// Reads the run state's own sections back, checking every size and index against `mesh`; a
/// checkpoint of another mesh, or damaged data, is an InputError naming `name` and the section.
/// Sections of the effects are left to them (effect_output.h restore_sections).
/// dofs_per_cover and stress_terms (polynomial stress coefficients per element) are the run's
/// (cover_space.h); a checkpoint of another cover order is an InputError. `factor_source`
/// receives the optional FACTOR section (system_matrix.h factor_source()).
RunState state_from_sections(const CheckpointSections& sections, const Mesh& mesh,
                             const std::string& name, std::string& contact_history,
                             int dofs_per_cover = 2, int stress_terms = 1,
                             std::string* factor_source = nullptr);

/// SHA-256 (hex) of a state's sections: every one but DIAG (diagnostics) and FACTOR (the solver's
/// working matrix), tag and bytes in order. Two runs whose hashes are equal are bitwise in the
/// same state.
std::string state_hash(const CheckpointSections& sections);
/// The same of the run state's own sections (state_to_sections).
std::string state_hash(const RunState& s, const std::string& contact_history, const Mesh& mesh);

/// Tracked points in a section (POINTS, a bolt's nodes): u64 n, n × (i32 element, f64 x0, y0,
/// x, y); read back with each element checked against `elements` and each value finite.
void put_points(ByteWriter& w, const std::vector<TrackedPoint>& pts);
std::vector<TrackedPoint> get_points(ByteReader& r, std::size_t elements);

}  // namespace nmm::solve
