// Scene definition: everything a scene file (JSON with comments) says, parsed and validated once
// into plain definition structs. Contract: docs/interface.md ("Scene file").
//
// Units are SI throughout: m, kg, s, N, Pa; 2D with unit thickness. Forces are N per metre of
// thickness. Materials and joint sets are referred to by index into the sorted-by-name vectors
// below (the JSON objects are ordered by key, so the indices are deterministic).
//
// parse_scene() checks structure, types and physical ranges (everything that needs no geometry
// kernel). The geometric checks that need exact predicates (self-intersecting polygons, holes
// outside their body, overlapping bodies) live in preprocess/scene_geometry.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "common/joint_generation.h"
#include "common/vec2.h"

namespace nmm {


/// A time history: a value that follows a table of (time, value) rows, linearly interpolated and
/// held at its first / last value outside the table (common/time_table.h evaluates it).
struct TimeTable {
  std::vector<double> time;   ///< s, strictly increasing
  std::vector<double> value;  ///< – (a factor) or m/s² (base acceleration), one per time
  bool empty() const { return time.empty(); }
};

enum class PlaneKind { strain, stress };
/// What `"dynamic": false` solves: DDA's static analysis (each step from rest, the inertia term
/// kept in the step's matrix, so blocks held only by contacts are well posed and settle) or the
/// pure equilibrium K d = F of a body held by fixed points (docs/solver.md, "Static analysis").
enum class StaticMode { dda, equilibrium };

/// The strength of intact rock (a material's "strength"): where it breaks (docs/fracture.md).
struct StrengthDef {
  bool present = false;         ///< the material can break (a scene "fracture" block is needed too)
  double tensile = 0;           ///< Pa, > 0: the tension cut-off, σ1 ≥ tensile (tension positive)
  double cohesion = 0;          ///< Pa, ≥ 0: Mohr–Coulomb's c
  double friction_deg = 0;      ///< degrees, in [0, 90): Mohr–Coulomb's φ
  double fracture_energy = 0;   ///< J/m², 0: a new crack's cohesive softening (> 0 refused: not built yet)
};

struct MaterialDef {
  std::string name;
  double density = 0;  ///< kg/m³, > 0
  double young = 0;    ///< Pa, > 0
  double poisson = 0;  ///< –, in [0, 0.5)
  StrengthDef strength;  ///< absent: the material never breaks
};

/// Fracturing of intact rock (scene key "fracture"; docs/fracture.md): on when present and some
/// material has a strength.
struct FractureDef {
  bool present = false;
  int crack_set = -1;  ///< joint set whose law the faces of new cracks use
};

/// constant: kn in Pa/m (joint stress per unit closure, integrated over each contact's tributary
/// length); bandis_barton: the closure curve (Pa/m, m); penalty: DDA's point spring, kn in N/m
/// per contact point (so the joint's stiffness grows with the number of contact points).
enum class NormalModel { constant, bandis_barton, penalty };
struct NormalLawDef {
  NormalModel model = NormalModel::constant;
  double kn = 0;   ///< Pa/m (constant model) or N/m per contact point (penalty)
  double kni = 0;  ///< Pa/m, initial normal stiffness (Bandis–Barton)
  double vm = 0;   ///< m, maximum closure (Bandis–Barton)
  bool hysteresis = false;  ///< Bandis–Barton: unload and reload along the tangent at the largest closure
  /// Bandis–Barton cycles ("reload"): below the largest closure the joint unloads and reloads on
  /// the reloading cycle's hyperbola, initial stiffness reload_kni (Pa/m) and maximum closure
  /// reload_vm (m), from the permanent closure (0: not given; then `hysteresis` is the tangent)
  double reload_kni = 0;
  double reload_vm = 0;
  // Given instead of kni and vm, these derive them (Barton–Bandis empirical relations):
  double jrc = 0;       ///< –, joint roughness coefficient (0 if not given)
  double jcs = 0;       ///< Pa, joint wall compressive strength
  double ucs = 0;       ///< Pa, uniaxial compressive strength of the intact rock (σc)
  double aperture = 0;  ///< m, initial aperture a_j derived from them
};

/// constant: ks in Pa/m (shear stress per unit shear displacement); hyperbolic: the curve (Pa/m,
/// –); penalty: DDA's point spring, ks in N/m per contact point; barton_bandis: Barton's peak
/// strength, mobilised roughness and dilation (solver/contact/barton_bandis.h) on an elastic spring ks
/// in Pa/m, the joint set's friction_deg being the residual friction angle φr.
enum class ShearModel { constant, hyperbolic, penalty, barton_bandis };
struct ShearLawDef {
  ShearModel model = ShearModel::constant;
  double ks = 0;   ///< Pa/m (constant and barton_bandis) or N/m per contact point (penalty)
  double ksi = 0;  ///< Pa/m, initial shear stiffness (hyperbolic)
  double rf = 0;   ///< –, failure ratio in (0, 1] (hyperbolic)
  // Barton–Bandis shear (field scale after the scale corrections when lab_length is given):
  double jrc = 0;         ///< –, joint roughness coefficient JRC_n at the joint length
  double jcs = 0;         ///< Pa, joint wall compressive strength JCS_n at the joint length
  double length = 0;      ///< m, joint (block) length L_n: peak displacement δp = L_n/500·(JRC_n/L_n)^0.33
  double lab_length = 0;  ///< m, L_0 of the sample JRC and JCS were measured on (0: no scale correction)
  double strength_factor = 1;  ///< –, the frictional strength is divided by it (strength reduction, nmm-fos)
};

struct JointSetDef {
  std::string name;
  double friction_deg = 0;      ///< degrees, in [0, 90)
  double cohesion = 0;          ///< Pa, >= 0
  double tensile_strength = 0;  ///< Pa, >= 0
  double residual_cohesion = 0;  ///< Pa, in [0, cohesion]: kept by a contact once it broke (reached its peak at an accepted step) or opened
  NormalLawDef normal;
  ShearLawDef shear;
  bool generated = false;       ///< a `generate` block is present
  JointGenerationDef generate;  ///< its definition (common/joint_generation.h)
  /// The set's joints were generated by nmm-preprocess and are listed in /joints; its former
  /// `generate` block is kept as `generated_from` (metadata only: nothing is generated again;
  /// nmm-inspect --network compares requested and measured statistics with it). Definition in
  /// `generate`, `generated` stays false.
  bool expanded = false;
};

struct BodyDef {
  int material = -1;        ///< index into SceneDef::materials
  Ring outer;               ///< outer boundary, m
  std::vector<Ring> holes;  ///< holes strictly inside `outer`, m
};

struct JointDef {
  int set = -1;              ///< index into SceneDef::joint_sets
  std::vector<Vec2> points;  ///< polyline, >= 2 points, no zero-length segment, m
};

struct LoadDef {
  Vec2 point;  ///< m, where the force acts
  Vec2 force;  ///< N per unit thickness
};

/// Supports along the body boundary under a polyline: the covers of the ME edges lying on it are
/// held by penalty springs in x, y or both (solver/discretisation/boundary_conditions.h).
struct SupportDef {
  std::vector<Vec2> points;  ///< polyline, >= 2 points, m
  bool fix_x = false;        ///< held in x
  bool fix_y = false;        ///< held in y
  /// m/s, the held position moves at this velocity from t = 0 (UDEC's `boundary xvelocity`):
  /// held at u = velocity·t in its held directions; zero in a free direction. 0: held in place
  Vec2 velocity;
  /// –, a factor on the velocity over time (UDEC's velocity history): held at
  /// u = velocity·∫0^t f dt' (support_travel()); empty: f = 1
  TimeTable table;
};

/// Traction on the body boundary under a polyline (solver/discretisation/boundary_conditions.h).
struct TractionDef {
  std::vector<Vec2> points;  ///< polyline, >= 2 points, m
  double normal = 0;         ///< Pa, along the outward normal (< 0 pushes into the body)
  double shear = 0;          ///< Pa, along the polyline's direction
  bool from_insitu = false;  ///< the traction is σ_insitu(x)·n instead (matches the in-situ stress)
  TimeTable table;           ///< factor on the traction over time; empty: 1
};

/// What a bolt is (docs/reinforcement.md): DDA's point-anchored bolt, an axial spring between
/// its two ends; or UDEC's fully grouted cable, axial segments tied along their length to the
/// rock by a grout shear spring.
enum class BoltType { anchored, grouted };

/// A straight rock bolt or cable from `a` to `b` (solver/reinforcement/). Forces and stiffnesses
/// are per bolt; in the plane-strain model each acts per metre of thickness divided by `spacing`.
/// A strength or yield force that is not given is none (infinity: never breaks, never yields).
struct BoltDef {
  Vec2 a, b;                         ///< m, its first and second point, both inside bodies
  BoltType type = BoltType::anchored;
  double spacing = 1;                ///< m between bolts out of the plane
  // anchored
  double stiffness = 0;              ///< N/m per bolt, of the axial spring
  double pretension = 0;             ///< N per bolt, its axial force when installed (tension > 0)
  double strength = 0;               ///< N per bolt: |axial force| at which it breaks (force 0 after)
  // grouted
  double ea = 0;                     ///< N per bolt, axial rigidity E·A of the steel
  double yield = 0;                  ///< N per bolt, axial yield force (tension and compression)
  double bond_stiffness = 0;         ///< N/m per m of bolt (Pa): grout shear stiffness
  double bond_strength = 0;          ///< N per m of bolt: grout shear strength
  int segments = 0;                  ///< axial segments; 0: the default (solver/reinforcement/bolt_layout.h)
};

/// Lysmer–Kuhlemeyer dashpots on the body boundary under a polyline
/// (solver/discretisation/absorbing_boundary.h); with an input velocity the boundary is compliant
/// and lets that incoming wave in.
struct AbsorbingDef {
  std::vector<Vec2> points;  ///< polyline, >= 2 points, m
  TimeTable input_x;         ///< m/s, the incoming wave's particle velocity in x over time; empty: none
  TimeTable input_y;         ///< m/s, in y
};

/// Initial stress σ(x, y) = σ0 + (y_ref − y)·gradient, Pa, tension positive.
struct InsituStressDef {
  bool present = false;
  double sxx = 0, syy = 0, sxy = 0;     ///< Pa, σ0 at y = y_ref
  double y_ref = 0;                     ///< m
  double gxx = 0, gyy = 0, gxy = 0;     ///< Pa per m of depth below y_ref
};

struct SolverDef {
  double time_step = 1e-3;                ///< s, > 0
  std::int64_t steps = 1000;              ///< number of time steps, >= 0
  bool dynamic = true;                    ///< false: static analysis (every step from rest)
  StaticMode static_mode = StaticMode::dda;  ///< what a static run solves (see StaticMode)
  double dynamic_factor = 1.0;            ///< –, in [0, 1]: v0 of the next step = factor · v1
  double newmark_beta = 0.6;              ///< –, in [0.5, 1]: 0.5 is Shi's scheme exactly
  double fixed_point_stiffness = 0;       ///< N/m per unit thickness; 0: 100 × largest E·1 m
  double max_displacement_ratio = 0.001;  ///< –, g2 in Shi's step control, in (0, 1)
  std::int64_t output_every = 10;         ///< steps between outputs (frames), >= 1
  /// steps between history.csv rows, >= 1; 0 (absent): output_every. Rows cost no frame.
  std::int64_t history_every = 0;
  /// –, in (0, 1): stop the run once the maximum unbalanced force ratio falls below it (and, in a
  /// dynamic run, no cover moves faster than the rest velocity): UDEC's `solve ratio`
  /// (solver/stepping/equilibrium_indicator.cpp); 0 (absent): run all steps
  double stop_at_ratio = 0;
  /// –, in [0, 0.3): a physical cover whose weight stays below this everywhere on its support (a
  /// sliver left where a joint passes next to the edge of its star) shares the unknowns of the
  /// neighbour cover it overlaps most; 0 never ties (solver/discretisation/cover_unknowns.cpp)
  double sliver_cover_weight = 1e-3;
  /// steps between checkpoints written during the run (0: only after the last step)
  std::int64_t checkpoint_every = 0;
  /// N/m² (N/m per m of boundary, unit thickness); 0: 100 × largest E / mesh size
  double support_stiffness = 0;
  /// steps over which the in-situ traction on a face freed by excavation is released (1: at once)
  std::int64_t excavation_steps = 1;
  /// –, degree n of the cover functions (seed eq. 1): 0 constant (2 unknowns per physical
  /// cover), 1 linear (6), 2 quadratic (12); a choice of the run, not of the mesh
  /// (docs/higher-order-covers.md)
  int cover_order = 0;
  /// –, τ in [1e-12, 1e-2]: the contact solve accepts a step when no unknown is out of balance by
  /// more than this fraction of the largest contact force, friction strengths follow the
  /// normal forces to within the same force, and (with a softening joint law) the displacement
  /// that would remove the rest is within 3e-4·τ·w0 (docs/contact.md "Tolerance and error")
  double contact_tolerance = 1e-3;
};

/// Water in the joints: a pressure p (Pa) on both faces of every joint (and on every body
/// boundary) below the phreatic surface, or from a per-joint entry (solver/discretisation/joint_water.h).
struct JointWaterDef {
  int joint = -1;               ///< index into SceneDef::joints
  std::vector<double> at;       ///< m, distance along the joint from its first point (table rows)
  std::vector<double> pressure; ///< Pa, ≥ 0, one per row of `at` (one row: uniform)
  double fill_depth = -1;       ///< m, ≥ 0: filled from its lowest point to this height (hydrostatic); −1: the table
};
struct WaterDef {
  bool present = false;            ///< "water" given
  double density = 1000;           ///< kg/m³, ρw (γw = ρw·|g|)
  std::vector<Vec2> phreatic;      ///< m, water table polyline (empty: none), single-valued across gravity
  std::vector<JointWaterDef> joints;  ///< per-joint pressures, replacing the phreatic surface on those joints
};

struct SceneDef {
  std::string name;                     ///< free text, "" if absent
  bool has_gravity = false;             ///< "gravity" present
  Vec2 gravity;                         ///< m/s²
  PlaneKind plane = PlaneKind::strain;  ///< plane strain (default) or plane stress
  std::vector<MaterialDef> materials;   ///< sorted by name
  std::vector<JointSetDef> joint_sets;  ///< sorted by name
  std::vector<BodyDef> bodies;
  std::vector<JointDef> joints;
  int interface_set = -1;  ///< joint set for touching bodies, -1 if absent
  double mesh_size = 0;    ///< m, side of the equilateral mathematical triangles
  std::vector<Vec2> fixed_points;    ///< m
  std::vector<LoadDef> loads;
  std::vector<TimeTable> load_tables;  ///< [load] factor on its force over time (empty: 1); may be shorter than loads
  std::vector<Vec2> measure_points;  ///< m
  std::vector<SupportDef> supports;
  std::vector<TractionDef> tractions;
  InsituStressDef insitu_stress;
  std::vector<int> excavate;         ///< bodies removed at the start of this run
  TimeTable base_acceleration_x;     ///< m/s², ground acceleration in x over time; empty: none
  TimeTable base_acceleration_y;     ///< m/s², in y
  WaterDef water;                    ///< water pressure in the joints (absent: dry)
  FractureDef fracture;              ///< intact rock that breaks (absent: it never does)
  std::vector<BoltDef> bolts;        ///< rock bolts and cables, numbered from 0 in this order
  std::vector<AbsorbingDef> absorbing;  ///< absorbing (viscous) boundaries
  SolverDef solver;
};

/// Limits that keep a scene within what the tools can represent and finish. The physical ones
/// lie orders of magnitude beyond any rock (or steel, or diamond) so that they refuse only
/// typing accidents, and they bound every product the solver forms: the largest matrix entry,
/// 2·ρ·A/Δt² ≤ 1e5 · 4e14 / 1e-24 = 4e43, and its square stay finite (docs/preprocess.md, "Limits").
constexpr double kMaxCoordinate = 1e7;         ///< m, |x| and |y| of any point
constexpr double kMaxMeshTriangles = 5e6;      ///< triangles over the bodies' bounding box
constexpr double kMaxDensity = 1e5;            ///< kg/m³ (osmium: 2.26e4)
constexpr double kMaxModulus = 1e13;           ///< Pa, Young's modulus (diamond: 1.2e12)
constexpr double kMaxStrength = 1e11;          ///< Pa, cohesion, tensile strength, JCS, UCS
constexpr double kMaxSpringStiffness = 1e17;   ///< N/m (point springs) or Pa/m (joint laws)
constexpr double kMaxClosure = 1;              ///< m, maximum joint closure Vm
constexpr double kMaxAcceleration = 1e5;       ///< m/s², each gravity component (1e4 g)
constexpr double kMaxForce = 1e15;             ///< N per unit thickness, each load component
constexpr double kMinTimeStep = 1e-12;         ///< s
constexpr double kMaxTimeStep = 1e6;           ///< s
constexpr double kMaxGeneratedJoints = 1e6;    ///< expected joints of one generated set

/// Parses scene text (JSON, // and /* */ comments allowed) and validates it.
/// Throws InputError(file, JSON path, message) on the first problem found.
SceneDef parse_scene(const std::string& text, const std::string& file);

/// Parses JSON text with comments allowed; InputError with "line L, column C" on a syntax error.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);

/// Validates an already parsed JSON document as a scene (used after merge patches).
SceneDef scene_from_json(const nlohmann::json& doc, const std::string& file);

/// What a JSON value is, for "expected X, got Y" messages: "an object", "a number",
/// "a string ("10")" (short strings quoted: the quotes are often the mistake), ...
std::string describe_json_value(const nlohmann::json& v);

/// Signed area of a ring (shoelace), m². Positive for counter-clockwise.
double ring_signed_area(const Ring& ring);

/// Area of a body: outer minus holes, m².
double body_area(const BodyDef& body);

}  // namespace nmm
