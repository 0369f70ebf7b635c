// Tests of scene parsing and validation (common/scene.h): the documented example and defaults,
// and one table entry per kind of mistake, each checked for its exact JSON path and message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/scene.h"
#include "common/time_table.h"

namespace nmm {
namespace {

using nlohmann::json;

// The scene of docs/interface.md, comments included.
const char* const kInterfaceExample = R"({
  "name": "sliding-block",
  "gravity": [0, -9.81],                      // m/s²; leave out for no gravity
  "plane": "strain",                          // or "stress"
  "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
  "joint_sets": {
    "bedding": {
      "friction_deg": 20, "cohesion": 0, "tensile_strength": 0,          // Pa
      "normal": { "model": "constant", "kn": 5e10 },                     // Pa/m: stress per closure
      //    or { "model": "bandis_barton", "kni": 1.5e10, "vm": 2.3e-4 } // Pa/m, m
      //    or { "model": "penalty", "kn": 5e11 }                        // DDA's point penalty, N/m per contact point
      "shear":  { "model": "constant", "ks": 2e10 }                      // Pa/m: stress per shear displacement
      //    or { "model": "hyperbolic", "ksi": 1e10, "rf": 0.9 }         // Pa/m, –
      //    or { "model": "penalty", "ks": 2e11 }                        // N/m per contact point
    }
  },
  "bodies": [ { "material": "rock",
                "outer": [[0,0],[10,0],[10,5],[0,5]],                    // polygon, any orientation
                "holes": [ [[4,2],[6,2],[6,3],[4,3]] ] } ],
  "joints": [ { "set": "bedding", "points": [[0,1],[10,1.5]] } ],      // polylines; may end inside a body
  "interface_set": "bedding",                 // joint set for contacts where separate bodies touch
  "mesh": { "size": 0.5 },                    // side of the equilateral mathematical triangles
  "fixed_points": [[0,0],[10,0]],
  "loads": [ { "point": [5,5], "force": [0,-1e6] } ],                // N per unit thickness
  "measure_points": [[5,4]],
  "solver": { "time_step": 1e-3, "steps": 1000, "dynamic": true,
              "max_displacement_ratio": 0.001, "output_every": 10 }
})";

TEST(Scene, InterfaceExampleParsesIntoEveryField) {
  const SceneDef s = parse_scene(kInterfaceExample, "example.json");
  EXPECT_EQ(s.name, "sliding-block");
  EXPECT_TRUE(s.has_gravity);
  EXPECT_EQ(s.gravity, (Vec2{0, -9.81}));
  EXPECT_EQ(s.plane, PlaneKind::strain);

  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "rock");
  EXPECT_EQ(s.materials[0].density, 2650);
  EXPECT_EQ(s.materials[0].young, 1e10);
  EXPECT_EQ(s.materials[0].poisson, 0.25);

  ASSERT_EQ(s.joint_sets.size(), 1u);
  const JointSetDef& js = s.joint_sets[0];
  EXPECT_EQ(js.name, "bedding");
  EXPECT_EQ(js.friction_deg, 20);
  EXPECT_EQ(js.cohesion, 0);
  EXPECT_EQ(js.tensile_strength, 0);
  EXPECT_EQ(js.normal.model, NormalModel::constant);
  EXPECT_EQ(js.normal.kn, 5e10);
  EXPECT_EQ(js.shear.model, ShearModel::constant);
  EXPECT_EQ(js.shear.ks, 2e10);

  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].material, 0);
  EXPECT_EQ(s.bodies[0].outer, (Ring{{0, 0}, {10, 0}, {10, 5}, {0, 5}}));
  ASSERT_EQ(s.bodies[0].holes.size(), 1u);
  EXPECT_EQ(s.bodies[0].holes[0], (Ring{{4, 2}, {6, 2}, {6, 3}, {4, 3}}));

  ASSERT_EQ(s.joints.size(), 1u);
  EXPECT_EQ(s.joints[0].set, 0);
  EXPECT_EQ(s.joints[0].points, (std::vector<Vec2>{{0, 1}, {10, 1.5}}));
  EXPECT_EQ(s.interface_set, 0);
  EXPECT_EQ(s.mesh_size, 0.5);

  EXPECT_EQ(s.fixed_points, (std::vector<Vec2>{{0, 0}, {10, 0}}));
  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].point, (Vec2{5, 5}));
  EXPECT_EQ(s.loads[0].force, (Vec2{0, -1e6}));
  EXPECT_EQ(s.measure_points, (std::vector<Vec2>{{5, 4}}));

  EXPECT_EQ(s.solver.time_step, 1e-3);
  EXPECT_EQ(s.solver.steps, 1000);
  EXPECT_TRUE(s.solver.dynamic);
  EXPECT_EQ(s.solver.max_displacement_ratio, 0.001);
  EXPECT_EQ(s.solver.output_every, 10);
  EXPECT_EQ(s.solver.sliver_cover_weight, 1e-3);  // the default

  EXPECT_DOUBLE_EQ(body_area(s.bodies[0]), 50.0 - 2.0);
}

TEST(Scene, MinimalSceneGetsTheDocumentedDefaults) {
  const SceneDef s = parse_scene(R"({
    "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0 } },
    "bodies": [ { "material": "rock", "outer": [[0,0],[1,0],[0,1]] } ],
    "mesh": { "size": 0.1 }
  })",
                                 "minimal.json");
  const SolverDef defaults;
  EXPECT_EQ(s.name, "");
  EXPECT_FALSE(s.has_gravity);
  EXPECT_EQ(s.gravity, (Vec2{0, 0}));
  EXPECT_EQ(s.plane, PlaneKind::strain);
  EXPECT_TRUE(s.joint_sets.empty());
  EXPECT_TRUE(s.bodies[0].holes.empty());
  EXPECT_TRUE(s.joints.empty());
  EXPECT_EQ(s.interface_set, -1);
  EXPECT_TRUE(s.fixed_points.empty());
  EXPECT_TRUE(s.loads.empty());
  EXPECT_TRUE(s.measure_points.empty());
  EXPECT_EQ(s.solver.time_step, 1e-3);
  EXPECT_EQ(s.solver.steps, 1000);
  EXPECT_TRUE(s.solver.dynamic);
  EXPECT_EQ(s.solver.max_displacement_ratio, 0.001);
  EXPECT_EQ(s.solver.output_every, 10);
  EXPECT_EQ(s.solver.time_step, defaults.time_step);
  EXPECT_EQ(s.solver.steps, defaults.steps);
}

TEST(Scene, OtherModelsPlaneStressAndSortedIndices) {
  // Materials and joint sets are sorted by name; bodies and joints refer to them by index.
  const SceneDef s = parse_scene(R"({
    "plane": "stress",
    "materials": { "soil": { "density": 1800, "young": 5e7, "poisson": 0.3 },
                   "clay": { "density": 1700, "young": 2e7, "poisson": 0.45 } },
    "joint_sets": {
      "fault": { "friction_deg": 30, "cohesion": 1e5, "tensile_strength": 2e4,
                 "normal": { "model": "bandis_barton", "kni": 1.5e10, "vm": 2.3e-4 },
                 "shear": { "model": "hyperbolic", "ksi": 1e10, "rf": 0.9 } },
      "bedding": { "friction_deg": 0, "normal": { "model": "constant", "kn": 1 },
                   "shear": { "model": "constant", "ks": 1 } } },
    "bodies": [ { "material": "soil", "outer": [[0,0],[0,2],[2,2],[2,0]] },
                { "material": "clay", "outer": [[2,0],[4,0],[4,2],[2,2]] } ],
    "joints": [ { "set": "fault", "points": [[0,0.5],[1,1],[2,1.2]] } ],
    "interface_set": "fault",
    "mesh": { "size": 0.25 },
    "solver": { "steps": 10.0, "dynamic": false, "output_every": 1e0 }
  })",
                                 "models.json");
  EXPECT_EQ(s.plane, PlaneKind::stress);
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "clay");
  EXPECT_EQ(s.materials[1].name, "soil");
  EXPECT_EQ(s.bodies[0].material, 1);
  EXPECT_EQ(s.bodies[1].material, 0);
  ASSERT_EQ(s.joint_sets.size(), 2u);
  EXPECT_EQ(s.joint_sets[0].name, "bedding");
  const JointSetDef& fault = s.joint_sets[1];
  EXPECT_EQ(fault.name, "fault");
  EXPECT_EQ(fault.cohesion, 1e5);
  EXPECT_EQ(fault.tensile_strength, 2e4);
  EXPECT_EQ(fault.normal.model, NormalModel::bandis_barton);
  EXPECT_EQ(fault.normal.kni, 1.5e10);
  EXPECT_EQ(fault.normal.vm, 2.3e-4);
  EXPECT_EQ(fault.shear.model, ShearModel::hyperbolic);
  EXPECT_EQ(fault.shear.ksi, 1e10);
  EXPECT_EQ(fault.shear.rf, 0.9);
  EXPECT_EQ(s.joints[0].set, 1);
  EXPECT_EQ(s.interface_set, 1);
  EXPECT_EQ(s.solver.steps, 10);  // 10.0 is a whole number
  EXPECT_FALSE(s.solver.dynamic);
  EXPECT_EQ(s.solver.output_every, 1);
  EXPECT_EQ(s.joint_sets[0].cohesion, 0);  // default
}

TEST(Scene, LargeMeshSizeIsFine) {
  const SceneDef s = parse_scene(R"({
    "materials": { "rock": { "density": 1, "young": 1, "poisson": 0 } },
    "bodies": [ { "material": "rock", "outer": [[0,0],[1,0],[0,1]] } ],
    "mesh": { "size": 1e7 }
  })",
                                 "big.json");
  EXPECT_EQ(s.mesh_size, 1e7);
}

// "penalty" is DDA's point spring (N/m per contact point); "constant" the joint's stiffness (Pa/m).
TEST(Scene, PenaltyIsANormalAndShearModel) {
  const SceneDef s = parse_scene(R"({
    "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
    "joint_sets": { "dda": { "friction_deg": 30, "normal": { "model": "penalty", "kn": 2e11 },
                             "shear": { "model": "penalty", "ks": 8e10 } } },
    "bodies": [ { "material": "rock", "outer": [[0,0],[1,0],[0,1]] } ],
    "mesh": { "size": 0.5 }
  })",
                                 "penalty.json");
  EXPECT_EQ(s.joint_sets[0].normal.model, NormalModel::penalty);
  EXPECT_EQ(s.joint_sets[0].normal.kn, 2e11);
  EXPECT_EQ(s.joint_sets[0].shear.model, ShearModel::penalty);
  EXPECT_EQ(s.joint_sets[0].shear.ks, 8e10);
}

// Barton–Bandis shear, the closure's hysteresis and the water keys (docs/interface.md).
TEST(Scene, BartonBandisShearHysteresisAndWater) {
  const SceneDef s = parse_scene(R"({
    "gravity": [0, -9.81],
    "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
    "joint_sets": { "rough": { "friction_deg": 28,
        "normal": { "model": "bandis_barton", "kni": 1.5e10, "vm": 2e-4, "hysteresis": true },
        "shear": { "model": "barton_bandis", "ks": 1e11, "jrc": 8, "jcs": 6e7, "length": 2,
                   "strength_factor": 1.25 } } },
    "bodies": [ { "material": "rock", "outer": [[0,0],[4,0],[4,4],[0,4]] } ],
    "joints": [ { "set": "rough", "points": [[0,1],[4,2]] }, { "set": "rough", "points": [[2,0],[2,4]] } ],
    "mesh": { "size": 0.5 },
    "water": { "density": 1020, "phreatic": [[4, 3], [0, 2.5]],
               "joints": [ { "joint": 1, "fill_depth": 1.5 }, { "joint": 0, "pressure": [[0, 1e4], [3, 2e4]] } ] }
  })",
                                 "bb.json");
  const JointSetDef& j = s.joint_sets[0];
  EXPECT_TRUE(j.normal.hysteresis);
  EXPECT_EQ(j.shear.model, ShearModel::barton_bandis);
  EXPECT_EQ(j.shear.jrc, 8);
  EXPECT_EQ(j.shear.jcs, 6e7);
  EXPECT_EQ(j.shear.length, 2);
  EXPECT_EQ(j.shear.lab_length, 0);  // no scale correction
  EXPECT_EQ(j.shear.strength_factor, 1.25);
  ASSERT_TRUE(s.water.present);
  EXPECT_EQ(s.water.density, 1020);
  ASSERT_EQ(s.water.phreatic.size(), 2u);  // either direction across gravity
  ASSERT_EQ(s.water.joints.size(), 2u);
  EXPECT_EQ(s.water.joints[0].joint, 1);
  EXPECT_EQ(s.water.joints[0].fill_depth, 1.5);
  EXPECT_EQ(s.water.joints[1].fill_depth, -1);
  EXPECT_EQ(s.water.joints[1].at, (std::vector<double>{0, 3}));
  EXPECT_EQ(s.water.joints[1].pressure, (std::vector<double>{1e4, 2e4}));
  const SceneDef dry = parse_scene(R"({"materials": {"r": {"density": 1, "young": 1, "poisson": 0}},
    "bodies": [{"material": "r", "outer": [[0,0],[1,0],[0,1]]}], "mesh": {"size": 0.5}})", "dry.json");
  EXPECT_FALSE(dry.water.present);
}

// ---- bad scenes ---------------------------------------------------------------------------------

// A valid scene that the table below breaks, one mistake at a time, with a JSON merge patch.
const char* const kBase = R"({
  "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 },
                 "soil": { "density": 1800, "young": 5e7, "poisson": 0.3 } },
  "joint_sets": {
    "bedding": { "friction_deg": 20, "normal": { "model": "constant", "kn": 5e11 },
                 "shear": { "model": "constant", "ks": 2e11 } },
    "fault": { "friction_deg": 30, "normal": { "model": "bandis_barton", "kni": 1.5e10, "vm": 2.3e-4 },
               "shear": { "model": "hyperbolic", "ksi": 1e10, "rf": 0.9 } } },
  "bodies": [ { "material": "rock", "outer": [[0,0],[10,0],[10,5],[0,5]],
                "holes": [ [[4,2],[6,2],[6,3],[4,3]] ] } ],
  "joints": [ { "set": "bedding", "points": [[0,1],[10,1.5]] },
              { "set": "fault", "points": [[1,0],[2,2],[3,5]] } ],
  "mesh": { "size": 0.5 }
})";

struct BadCase {
  const char* patch;   ///< JSON merge patch applied to kBase, or the whole text if `raw`
  const char* where;   ///< exact JSON path (or "line L, column C")
  const char* phrase;  ///< part of the message
  bool raw = false;
};

// Names the case in gtest's failure output (instead of a byte dump).
void PrintTo(const BadCase& c, std::ostream* os) {
  *os << '"' << c.where << "\" / " << c.phrase;
}

std::string scene_text(const BadCase& c) {
  if (c.raw) return c.patch;
  json doc = json::parse(kBase);
  doc.merge_patch(json::parse(c.patch));
  return doc.dump();
}

const BadCase kBadCases[] = {
    // JSON syntax: line and column of the offending character, comments count as lines.
    {"{\n  \"mesh\": {\"size\": 0.5,}\n}", "line 2, column 24", "invalid JSON", true},
    {"// a comment\n/* and\n another */\n{ \"name\": \"x\" ", "line 4, column 15",
     "unexpected end of input", true},
    {"", "line 1, column 1", "invalid JSON", true},
    {"[1, 2]", "top level", "expected an object, got an array", true},
    {R"({"materials": {"rock": {"density": null, "young": 1, "poisson": 0}}})",
     "/materials/rock/density", "expected a number, got null", true},
    // 1e400 does not fit a double: nlohmann refuses it while parsing, with no position; the
    // error still names the value's path, and its line and column.
    {"{\"materials\": {\"rock\": {\"density\": 1,\n  \"young\": 1e400}}}", "/materials/rock/young",
     "number 1e400 is too large for a double (at line 2, column 12)", true},
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[-1e400,0],[10,5]]}]})",
     "/bodies/0/outer/1/0", "number -1e400 is too large", true},
    {R"({"gravity": [0, 1e400]})", "/gravity/1", "number 1e400 is too large", true},
    // Unknown keys, at several levels.
    {R"({"meshh": {"size": 1}})", "/meshh",
     "unknown key \"meshh\" (allowed: absorbing, base_acceleration, bodies, bolts, excavate, fixed_points, "
     "flow, fracture, gravity, insitu_stress, interface_set, joint_sets, joints, loads, materials, measure_points, mesh, "
     "name, plane, solver, supports, tractions, water)"},
    {R"({"joint_sets": {"bedding": {"fricton_deg": 20}}})", "/joint_sets/bedding/fricton_deg",
     "unknown key \"fricton_deg\" (allowed: cohesion, friction_deg, generate, generated_from, "
     "normal, residual_cohesion, shear, tensile_strength)"},
    {R"({"materials": {"rock": {"E": 1}}})", "/materials/rock/E", "unknown key \"E\""},
    {R"({"solver": {"timestep": 1}})", "/solver/timestep", "unknown key \"timestep\""},
    {R"({"mesh": {"size": 0.5, "type": "quad"}})", "/mesh/type",
     "unknown key \"type\" (allowed: size, split_gap_ends)"},
    {R"({"mesh": {"size": 0.5, "split_gap_ends": "yes"}})", "/mesh/split_gap_ends",
     "expected true or false, got a string"},
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[1,0],[0,1]], "hole": []}]})",
     "/bodies/0/hole", "unknown key \"hole\" (allowed: holes, material, outer)"},
    {R"({"loads": [{"point": [1,1], "force": [0,1], "moment": 3}]})", "/loads/0/moment",
     "unknown key \"moment\""},
    // Both models' parameters may stand side by side (runs switch models); typos still fail.
    {R"({"joint_sets": {"bedding": {"normal": {"kn_i": 1e10}}}})", "/joint_sets/bedding/normal/kn_i",
     "unknown key \"kn_i\" (allowed: hysteresis, jcs, jrc, kn, kni, model, reload, ucs, vm)"},
    {R"({"joint_sets": {"fault": {"shear": {"rff": 0.9}}}})", "/joint_sets/fault/shear/rff",
     "unknown key \"rff\" (allowed: jcs, jrc, ks, ksi, lab_length, length, model, rf, strength_factor)"},
    {R"({"joint_sets": {"bedding": {"normal": {"model": "linear"}}}})",
     "/joint_sets/bedding/normal/model",
     "unknown normal model \"linear\" (known: constant, bandis_barton, penalty)"},
    {R"({"joint_sets": {"bedding": {"shear": {"model": "mohr"}}}})",
     "/joint_sets/bedding/shear/model",
     "unknown shear model \"mohr\" (known: constant, hyperbolic, penalty, barton_bandis)"},
    // Barton–Bandis shear: JRC in [0, 20], JCS > 0, the joint length for δp, the spring ks.
    {R"({"joint_sets": {"fault": {"shear": {"model": "barton_bandis", "ks": 1e10, "jrc": 25, "jcs": 1e8, "length": 1}}}})",
     "/joint_sets/fault/shear/jrc", "must be in [0, 20] (got 25)"},
    {R"({"joint_sets": {"fault": {"shear": {"model": "barton_bandis", "ks": 1e10, "jrc": 10, "jcs": 1e8}}}})",
     "/joint_sets/fault/shear", "missing required key \"length\""},
    {R"({"joint_sets": {"fault": {"shear": {"model": "barton_bandis", "ks": 1e10, "jrc": 10, "jcs": 0, "length": 1}}}})",
     "/joint_sets/fault/shear/jcs", "must be in (0, 1e+11] (got 0)"},
    {R"({"joint_sets": {"fault": {"normal": {"hysteresis": "yes"}}}})", "/joint_sets/fault/normal/hysteresis",
     "expected true or false, got a string"},
    // Water: hydrostatic pressure needs gravity; one water level per position; joints by index.
    {R"({"water": {"phreatic": [[0, 4], [10, 3]]}})", "/water/phreatic",
     "a phreatic surface needs gravity"},
    {R"({"gravity": [0, -9.81], "water": {"phreatic": [[0, 4], [5, 3], [4, 2]]}})", "/water/phreatic/2",
     "the phreatic surface turns back across gravity here"},
    {R"({"gravity": [0, -9.81], "water": {"joints": [{"joint": 2, "pressure": 1e5}]}})", "/water/joints/0/joint",
     "no joint 2 (the scene has 2)"},
    {R"({"gravity": [0, -9.81], "water": {"joints": [{"joint": 0, "pressure": 1e5, "fill_depth": 1}]}})",
     "/water/joints/0", "give either \"pressure\""},
    {R"({"gravity": [0, -9.81], "water": {"joints": [{"joint": 0, "pressure": -1}]}})",
     "/water/joints/0/pressure", "must be in [0, 1e+11] (got -1)"},
    {R"({"gravity": [0, -9.81], "water": {"joints": [{"joint": 0, "pressure": [[0, 1e5], [0, 2e5]]}]}})",
     "/water/joints/0/pressure/1/0", "distances must increase strictly"},
    {R"({"gravity": [0, -9.81], "water": {"joints": [{"joint": 1, "fill_depth": 1}, {"joint": 1, "pressure": 0}]}})",
     "/water/joints/1/joint", "joint 1 is given water twice"},
    {R"({"water": {"joints": [{"joint": 1, "fill_depth": 1}]}})", "/water/joints/0/fill_depth",
     "fill_depth needs gravity"},
    {R"({"gravity": [0, -9.81], "water": {"density": 0}})", "/water/density", "must be in (0, 1e+05] (got 0)"},
    {R"({"gravity": [0, -9.81], "water": {"phreatc": []}})", "/water/phreatc",
     "unknown key \"phreatc\" (allowed: density, joints, phreatic)"},
    // DDA's point penalty: a stiffness, in (0, 1e17] N/m, and the shear needs ks.
    {R"({"joint_sets": {"bedding": {"normal": {"model": "penalty", "kn": -1}}}})",
     "/joint_sets/bedding/normal/kn", "must be in (0, 1e+17] (got -1)"},
    {R"({"joint_sets": {"bedding": {"shear": {"model": "penalty", "ks": null}}}})",
     "/joint_sets/bedding/shear", "missing required key \"ks\""},
    {R"({"joint_sets": {"bedding": {"normal": {"model": null}}}})", "/joint_sets/bedding/normal",
     "missing required key \"model\""},
    // Names that must refer to something defined.
    {R"({"joints": [{"set": "beding", "points": [[0,1],[1,1]]}]})", "/joints/0/set",
     "unknown joint set \"beding\" (known: bedding, fault)"},
    {R"({"joint_sets": null})", "/joints/0/set",
     "unknown joint set \"bedding\" (no joint_sets are defined)"},
    {R"({"interface_set": "faults"})", "/interface_set",
     "unknown joint set \"faults\" (known: bedding, fault)"},
    {R"({"bodies": [{"material": "granite", "outer": [[0,0],[1,0],[0,1]]}]})", "/bodies/0/material",
     "unknown material \"granite\" (known: rock, soil)"},
    {R"({"plane": "strian"})", "/plane", "unknown plane \"strian\" (known: strain, stress)"},
    // Types.
    {R"({"materials": {"rock": {"young": "1e10"}}})", "/materials/rock/young",
     "expected a number, got a string"},
    {R"({"name": 5})", "/name", "expected a string, got a number"},
    {R"({"joints": {"a": 1}})", "/joints", "expected an array, got an object"},
    {R"({"materials": [1]})", "/materials", "expected an object, got an array"},
    {R"({"solver": {"dynamic": "yes"}})", "/solver/dynamic",
     "expected true or false, got a string"},
    {R"({"solver": {"steps": "10"}})", "/solver/steps", "expected an integer, got a string"},
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[1,0],[0,1]], "holes": {}}]})",
     "/bodies/0/holes", "expected an array, got an object"},
    // Required keys and non-empty collections.
    {R"({"bodies": [{"material": "rock"}]})", "/bodies/0", "missing required key \"outer\""},
    {R"({"mesh": null})", "top level", "missing required key \"mesh\""},
    {R"({"joint_sets": {"bedding": {"friction_deg": null}}})", "/joint_sets/bedding",
     "missing required key \"friction_deg\""},
    {R"({"loads": [{"point": [1,1]}]})", "/loads/0", "missing required key \"force\""},
    {R"({"joint_sets": {"bedding": {"friction_deg": 30, "normal": {"model": "bandis_barton",
        "kni": 1e10, "vm": 1e-4, "hysteresis": false, "reload": {"kni": 3e10, "vm": 5e-5}},
        "shear": {"model": "constant", "ks": 1e10}}}})",
     "/joint_sets/bedding/normal/hysteresis", "the reloading cycle (reload) needs the hysteresis: true or leave it out"},
    {R"({"supports": [{"points": [[0,0],[1,0]], "fix": "y", "velocity": [0.1, 0]}]})",
     "/supports/0/velocity", "a support moves only in the directions it holds (fix)"},
    {R"({"supports": [{"points": [[0,0],[1,0]], "fix": "y", "table": [[0, 1], [1, -1]]}]})",
     "/supports/0/table", "a velocity table needs the support's velocity"},
    {R"({"materials": null})", "top level", "missing required key \"materials\""},
    {R"({"bodies": []})", "/bodies", "at least one body is required"},
    {R"({"materials": {"rock": null, "soil": null}})", "/materials",
     "at least one material is required"},
    // Points.
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[1,0,0],[0,1]]}]})", "/bodies/0/outer/1",
     "expected a point [x, y], got an array of 3 values"},
    {R"({"fixed_points": ["origin"]})", "/fixed_points/0", "expected a point [x, y], got a string"},
    {R"({"fixed_points": [[0, "1"]]})", "/fixed_points/0/1", "expected a number, got a string"},
    {R"({"measure_points": [[2e7, 0]]})", "/measure_points/0/0",
     "must be in [-1e+07, 1e+07] (got 2e+07)"},
    {R"({"gravity": [-9.81]})", "/gravity", "expected [gx, gy], got an array of 1 value"},
    {R"({"loads": [{"point": [1,1], "force": [0, "down"]}]})", "/loads/0/force/1",
     "expected a number, got a string"},
    // Rings and polylines.
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[1,0]]}]})", "/bodies/0/outer",
     "a polygon needs at least 3 points, got 2"},
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[1,0],[1,0],[0,1]]}]})",
     "/bodies/0/outer/2", "zero-length segment: point 2 repeats point 1"},
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[1,0],[0,1],[0,0]]}]})",
     "/bodies/0/outer/3", "the last point repeats the first"},
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[1,1],[3,3],[2,2]]}]})", "/bodies/0/outer",
     "zero-area polygon"},
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[0.1,0.1],[0.3,0.3]]}]})",
     "/bodies/0/outer", "zero-area polygon"},  // collinear in decimal, not quite in binary
    {R"({"bodies": [{"material": "rock", "outer": [[0,0],[9,0],[9,9]],
                     "holes": [[[1,1],[2,1],[3,1]]]}]})",
     "/bodies/0/holes/0", "zero-area polygon"},
    {R"({"joints": [{"set": "bedding", "points": [[0,1]]}]})", "/joints/0/points",
     "a joint needs at least 2 points, got 1"},
    {R"({"joints": [{"set": "bedding", "points": [[0,1],[1,2],[1,2]]}]})", "/joints/0/points/2",
     "zero-length segment: point 2 repeats point 1"},
    // Mesh size.
    {R"({"mesh": {"size": 0}})", "/mesh/size", "must be > 0 (got 0)"},
    {R"({"mesh": {"size": 0.001}})", "/mesh/size",
     "mesh size 0.001 m would make about 1.2e+08 triangles over the bodies' bounding box "
     "(limit 5e+06); use a larger size"},
    {R"({"mesh": {"size": 1e-300}})", "/mesh/size", "would make more than 1e+308 triangles"},
    // Physical ranges.
    {R"({"materials": {"rock": {"density": -5}}})", "/materials/rock/density",
     "must be in (0, 1e+05] (got -5)"},
    {R"({"materials": {"soil": {"young": 0}}})", "/materials/soil/young", "must be in (0, 1e+13] (got 0)"},
    {R"({"materials": {"rock": {"poisson": 0.5}}})", "/materials/rock/poisson",
     "must be in [0, 0.5) (got 0.5)"},
    {R"({"materials": {"rock": {"poisson": -0.1}}})", "/materials/rock/poisson",
     "must be in [0, 0.5) (got -0.1)"},
    {R"({"joint_sets": {"bedding": {"friction_deg": 90}}})", "/joint_sets/bedding/friction_deg",
     "must be in [0, 90) (got 90)"},
    {R"({"joint_sets": {"bedding": {"cohesion": -1}}})", "/joint_sets/bedding/cohesion",
     "must be in [0, 1e+11] (got -1)"},
    {R"({"joint_sets": {"fault": {"tensile_strength": -2e3}}})",
     "/joint_sets/fault/tensile_strength", "must be in [0, 1e+11] (got -2000)"},
    // Intact rock that breaks (docs/fracture.md).
    {R"({"materials": {"rock": {"strength": {"tensile": -1e6, "cohesion": 1e6, "friction_deg": 30}}}})",
     "/materials/rock/strength/tensile", "must be in (0, 1e+11] (got -1e+06)"},
    {R"({"materials": {"rock": {"strength": {"tensile": 1e6, "cohesion": -5, "friction_deg": 30}}}})",
     "/materials/rock/strength/cohesion", "must be in [0, 1e+11] (got -5)"},
    {R"({"materials": {"rock": {"strength": {"tensile": 1e6, "cohesion": 1e6}}}})",
     "/materials/rock/strength", "missing required key \"friction_deg\""},
    {R"({"materials": {"rock": {"strength": {"tensile": 1e6, "cohesion": 1e6, "friction_deg": 30, "gf": 1}}}})",
     "/materials/rock/strength/gf", "unknown key \"gf\" (allowed: cohesion, fracture_energy, friction_deg, tensile, toughness)"},
    {R"({"materials": {"rock": {"strength": {"tensile": 1e6, "cohesion": 1e6, "friction_deg": 30, "fracture_energy": -60}}}})",
     "/materials/rock/strength/fracture_energy", "must be in [0, 1e+09] (got -60)"},
    {R"({"materials": {"rock": {"strength": {"tensile": 1e6, "cohesion": 1e6, "friction_deg": 30, "toughness": 0}}}})",
     "/materials/rock/strength/toughness", "must be in (0, 1e+10] (got 0)"},
    {R"({"fracture": {"crack_set": "bedding", "tip_step": -0.1}})", "/fracture/tip_step",
     "must be in (0, 1e+06] (got -0.1)"},
    {R"({"fracture": {"crack_set": "fresh"}})", "/fracture/crack_set",
     "unknown joint set \"fresh\" (known: bedding, fault)"},
    {R"({"joint_sets": {"bedding": {"cohesion": 1e4, "residual_cohesion": 2e4}}})",
     "/joint_sets/bedding/residual_cohesion", "must be in [0, 10000] (got 20000)"},
    {R"({"joint_sets": {"bedding": {"normal": {"kn": 0}}}})", "/joint_sets/bedding/normal/kn",
     "must be in (0, 1e+17] (got 0)"},
    {R"({"joint_sets": {"bedding": {"shear": {"ks": -1e9}}}})", "/joint_sets/bedding/shear/ks",
     "must be in (0, 1e+17] (got -1e+09)"},
    {R"({"joint_sets": {"fault": {"normal": {"kni": 0}}}})", "/joint_sets/fault/normal/kni",
     "must be in (0, 1e+17]"},
    {R"({"joint_sets": {"fault": {"normal": {"vm": -1e-4}}}})", "/joint_sets/fault/normal/vm",
     "must be in (0, 1] (got -1e-04)"},
    {R"({"joint_sets": {"fault": {"shear": {"ksi": 0}}}})", "/joint_sets/fault/shear/ksi",
     "must be in (0, 1e+17]"},
    {R"({"joint_sets": {"fault": {"shear": {"rf": 1.5}}}})", "/joint_sets/fault/shear/rf",
     "must be in (0, 1] (got 1.5)"},
    {R"({"joint_sets": {"fault": {"shear": {"rf": 0}}}})", "/joint_sets/fault/shear/rf",
     "must be in (0, 1] (got 0)"},
    {R"({"solver": {"time_step": 0}})", "/solver/time_step", "must be in [1e-12, 1e+06] (got 0)"},
    {R"({"solver": {"time_step": 1e308}})", "/solver/time_step", "must be in [1e-12, 1e+06] (got 1e+308)"},
    {R"({"materials": {"rock": {"density": 1e308}}})", "/materials/rock/density",
     "must be in (0, 1e+05] (got 1e+308)"},
    {R"({"gravity": [0, -1e308]})", "/gravity/1", "must be in [-1e+05, 1e+05] (got -1e+308)"},
    {R"({"solver": {"steps": -1}})", "/solver/steps", "must be >= 0 (got -1)"},
    {R"({"solver": {"steps": 10.5}})", "/solver/steps", "must be a whole number (got 10.5)"},
    {R"({"solver": {"steps": 1e30}})", "/solver/steps", "integer too large"},
    {R"({"solver": {"output_every": 0}})", "/solver/output_every", "must be >= 1 (got 0)"},
    {R"({"solver": {"history_every": 0}})", "/solver/history_every", "must be >= 1 (got 0)"},
    {R"({"solver": {"stop_at_ratio": 0}})", "/solver/stop_at_ratio", "must be in (0, 1) (got 0)"},
    {R"({"solver": {"stop_at_ratio": 1}})", "/solver/stop_at_ratio", "must be in (0, 1) (got 1)"},
    {R"({"solver": {"contact_tolerance": 0}})", "/solver/contact_tolerance", "must be in [1e-12, 0.01] (got 0)"},
    {R"({"solver": {"contact_tolerance": 0.1}})", "/solver/contact_tolerance", "must be in [1e-12, 0.01] (got 0.1)"},
    {R"({"solver": {"max_displacement_ratio": 1}})", "/solver/max_displacement_ratio",
     "must be in (0, 1) (got 1)"},
    // At 1/3 an element could have all three covers tied (its weights sum to 1).
    {R"({"solver": {"sliver_cover_weight": 0.34}})", "/solver/sliver_cover_weight",
     "must be in [0, 0.3) (got 0.34)"},
    // Bolts (docs/reinforcement.md): a type, two points, the keys of that type only.
    {R"({"bolts": [{"points": [[1,1],[2,2]], "stiffness": 1e7}]})", "/bolts/0", "missing required key \"type\""},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "rockbolt"}]})", "/bolts/0/type",
     "unknown bolt type \"rockbolt\" (known: anchored, grouted)"},
    {R"({"bolts": [{"points": [[1,1],[2,2],[3,3]], "type": "anchored", "stiffness": 1e7}]})", "/bolts/0/points",
     "a bolt is straight: exactly 2 points"},
    {R"({"bolts": [{"points": [[1,1],[1,1]], "type": "anchored", "stiffness": 1e7}]})", "/bolts/0/points/1",
     "zero-length segment"},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "anchored", "stiffness": 1e7, "ea": 1e7}]})", "/bolts/0/ea",
     "unknown key \"ea\" (allowed for type \"anchored\": points, pretension, spacing, stiffness, strength, type)"},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "grouted", "ea": 1e7, "bond_stiffness": 1e8, "stiffness": 1}]})",
     "/bolts/0/stiffness", "unknown key \"stiffness\" (allowed for type \"grouted\": bond_stiffness, bond_strength, ea, points, segments, spacing, type, yield)"},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "anchored"}]})", "/bolts/0", "missing required key \"stiffness\""},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "anchored", "stiffness": 0}]})", "/bolts/0/stiffness",
     "must be in (0, 1e+17] (got 0)"},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "anchored", "stiffness": 1e7, "pretension": 3e5, "strength": 2e5}]})",
     "/bolts/0/pretension", "must be below the bolt's strength (2e+05 N)"},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "anchored", "stiffness": 1e7, "spacing": 0}]})", "/bolts/0/spacing",
     "must be in (0, 1000] (got 0)"},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "grouted", "ea": 1e7}]})", "/bolts/0",
     "missing required key \"bond_stiffness\""},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "grouted", "ea": 1e7, "bond_stiffness": 1e8, "yield": -1}]})",
     "/bolts/0/yield", "must be in (0, 1e+15] (got -1)"},
    {R"({"bolts": [{"points": [[1,1],[2,2]], "type": "grouted", "ea": 1e7, "bond_stiffness": 1e8, "segments": 0}]})",
     "/bolts/0/segments", "must be >= 1 (got 0)"},
    {R"({"bolts": {"points": [[1,1],[2,2]]}})", "/bolts", "expected an array, got an object"},
    // Absorbing boundaries: a polyline, an input velocity of time tables.
    {R"({"absorbing": [{"points": [[0,0]]}]})", "/absorbing/0/points", "an absorbing boundary needs at least 2 points"},
    {R"({"absorbing": [{"points": [[0,0],[10,0]], "input_velocity": {}}]})", "/absorbing/0/input_velocity",
     "an input velocity needs \"x\" and/or \"y\""},
    {R"({"absorbing": [{"points": [[0,0],[10,0]], "input_velocity": {"z": [[0, 1]]}}]})",
     "/absorbing/0/input_velocity/z", "unknown key \"z\" (allowed: x, y)"},
    {R"({"absorbing": [{"points": [[0,0],[10,0]], "input_velocity": {"x": [[0, 1], [0, 2]]}}]})",
     "/absorbing/0/input_velocity/x/1/0", "times must increase strictly"},
    {R"({"absorbing": [{"points": [[0,0],[10,0]], "damping": 1}]})", "/absorbing/0/damping",
     "unknown key \"damping\" (allowed: input_velocity, points)"},
    // Fluid flow along the joints (docs/flow.md).
    {R"({"flow": {"fluid": {"viscosity": 0}}})", "/flow/fluid/viscosity", "must be in (0, 1e+12] (got 0)"},
    {R"({"flow": {"aperture": {"residual": 1e-3, "max": 1e-4}}})", "/flow/aperture/max",
     "the cap 1e-04 m is below the residual aperture 0.001 m"},
    {R"({"flow": {"boundaries": [{"points": [[0,0],[10,0]], "pressure": [[0, 1], [0, 2]]}]}})",
     "/flow/boundaries/0/pressure/1/0", "times must increase strictly"},
    {R"({"flow": {"injections": [{"point": [1, 1]}]}})", "/flow/injections/0", "missing required key \"rate\""},
    {R"({"flow": {"steady": 1}})", "/flow/steady", "expected true or false"},
    {R"({"flow": {"pressure": 1}})", "/flow/pressure", "unknown key \"pressure\""},
    {R"({"water": {"density": 1000}, "flow": {}})", "/flow", "\"flow\" and \"water\" both set"},
    // Keys with '/' or '~' are escaped in the path (RFC 6901).
    {R"({"joint_sets": {"a/b~c": {"friction_deg": -1, "normal": {"model": "constant", "kn": 1},
                                  "shear": {"model": "constant", "ks": 1}}}})",
     "/joint_sets/a~1b~0c/friction_deg", "must be in [0, 90) (got -1)"},
};

class BadScene : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScene, ThrowsInputErrorWithPathAndMessage) {
  const BadCase& c = GetParam();
  const std::string text = scene_text(c);
  try {
    parse_scene(text, "bad.json");
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_EQ(e.where(), c.where) << what;
    const std::string prefix =
        std::string("bad.json: ") + (*c.where ? std::string(c.where) + ": " : "");
    EXPECT_EQ(what.rfind(prefix, 0), 0u) << what;
    EXPECT_NE(what.find(c.phrase), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    if (std::getenv("NMM_PRINT_ERRORS")) std::printf("%s\n", what.c_str());
  }
}

INSTANTIATE_TEST_SUITE_P(Table, BadScene, ::testing::ValuesIn(kBadCases));

TEST(BadSceneTable, HasAtLeastThirtyCases) {
  EXPECT_GE(std::size(kBadCases), 30u);
}

TEST(BadSceneTable, BaseSceneIsValid) {
  const SceneDef s = parse_scene(kBase, "base.json");
  EXPECT_EQ(s.joints.size(), 2u);
  EXPECT_EQ(s.joints[1].set, 1);
}

// Bolts and absorbing boundaries as the contract writes them (docs/interface.md): every key
// read, the optional strengths absent as none (infinite), the defaults.
TEST(Scene, BoltsAndAbsorbingBoundariesParse) {
  const SceneDef s = parse_scene(R"({
    "materials": {"rock": {"density": 2650, "young": 1e10, "poisson": 0.25}},
    "bodies": [{"material": "rock", "outer": [[0,0],[10,0],[10,10],[0,10]]}], "mesh": {"size": 1},
    "bolts": [
      { "points": [[1, 1], [3, 1]], "type": "anchored", "stiffness": 5e7,
        "pretension": 0, "strength": 2e5, "spacing": 1.0 },
      { "points": [[1, 2], [4, 2]], "type": "grouted", "ea": 1.8e7, "yield": 2.5e5,
        "bond_stiffness": 1.1e8, "bond_strength": 1.75e5, "spacing": 1.5, "segments": 12 },
      { "points": [[1, 3], [4, 3]], "type": "anchored", "stiffness": 1e6, "pretension": 5e4 },
      { "points": [[1, 4], [4, 4]], "type": "grouted", "ea": 1e7, "bond_stiffness": 1e8 } ],
    "absorbing": [ { "points": [[0, 0], [10, 0]], "input_velocity": { "x": [[0, 0], [0.1, 1]] } },
                   { "points": [[0, 0], [0, 10]] } ] })",
                                 "bolts.json");
  ASSERT_EQ(s.bolts.size(), 4u);
  EXPECT_EQ(s.bolts[0].type, BoltType::anchored);
  EXPECT_EQ(s.bolts[0].a, (Vec2{1, 1}));
  EXPECT_EQ(s.bolts[0].b, (Vec2{3, 1}));
  EXPECT_EQ(s.bolts[0].stiffness, 5e7);
  EXPECT_EQ(s.bolts[0].strength, 2e5);
  EXPECT_EQ(s.bolts[1].type, BoltType::grouted);
  EXPECT_EQ(s.bolts[1].ea, 1.8e7);
  EXPECT_EQ(s.bolts[1].yield, 2.5e5);
  EXPECT_EQ(s.bolts[1].bond_stiffness, 1.1e8);
  EXPECT_EQ(s.bolts[1].bond_strength, 1.75e5);
  EXPECT_EQ(s.bolts[1].spacing, 1.5);
  EXPECT_EQ(s.bolts[1].segments, 12);
  EXPECT_EQ(s.bolts[2].pretension, 5e4);
  EXPECT_TRUE(std::isinf(s.bolts[2].strength));  // never breaks
  EXPECT_EQ(s.bolts[2].spacing, 1.0);
  EXPECT_TRUE(std::isinf(s.bolts[3].yield));
  EXPECT_TRUE(std::isinf(s.bolts[3].bond_strength));
  EXPECT_EQ(s.bolts[3].segments, 0);  // the default, chosen by the solver
  ASSERT_EQ(s.absorbing.size(), 2u);
  EXPECT_EQ(s.absorbing[0].points.size(), 2u);
  EXPECT_EQ(s.absorbing[0].input_x.time.size(), 2u);
  EXPECT_TRUE(s.absorbing[0].input_y.empty());
  EXPECT_TRUE(s.absorbing[1].input_x.empty());
}

// Fracturing goes with bolts, absorbing boundaries (a re-cut ties the bolts again and lays
// the dashpots on the re-cut edges: docs/fracture.md) and cover order ≥ 1.
TEST(Scene, FractureWithBoltsAndAbsorbingBoundariesParses) {
  const SceneDef s = parse_scene(R"({
    "materials": {"rock": {"density": 2650, "young": 1e10, "poisson": 0.25,
                           "strength": {"tensile": 1e6, "cohesion": 4e6, "friction_deg": 35}}},
    "joint_sets": {"crack": {"friction_deg": 30, "normal": {"model": "constant", "kn": 1e11},
                             "shear": {"model": "constant", "ks": 4e10}}},
    "bodies": [{"material": "rock", "outer": [[0,0],[10,0],[10,10],[0,10]]}], "mesh": {"size": 1},
    "fracture": {"crack_set": "crack"},
    "bolts": [{ "points": [[1, 1], [3, 1]], "type": "anchored", "stiffness": 5e7 }],
    "absorbing": [{ "points": [[0, 0], [10, 0]] }] })",
                                 "fracture_bolts.json");
  EXPECT_TRUE(s.fracture.present);
  EXPECT_EQ(s.bolts.size(), 1u);
  EXPECT_EQ(s.absorbing.size(), 1u);
}

// A support's velocity table: held at velocity·∫0^t f, the integral exact on the linear rows
// and f held outside them.
TEST(Scene, SupportVelocityTableIntegratesItsFactor) {
  const SceneDef s = parse_scene(R"({
    "materials": {"rock": {"density": 2650, "young": 1e10, "poisson": 0.25}},
    "bodies": [{"material": "rock", "outer": [[0,0],[1,0],[1,1],[0,1]]}], "mesh": {"size": 0.5},
    "supports": [{"points": [[0,0],[0,1]], "fix": "x", "velocity": [0.002, 0],
                  "table": [[0.5, 1], [1, 1], [1.5, -1]]}]})",
                                 "table.json");
  const TimeTable& t = s.supports[0].table;
  ASSERT_EQ(t.time.size(), 3u);
  EXPECT_DOUBLE_EQ(table_integral(t, 0.25), 0.25);  // f = 1 held before the first row
  EXPECT_DOUBLE_EQ(table_integral(t, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(table_integral(t, 1.25), 1.125);  // f from 1 to 0 over 0.25 s
  EXPECT_DOUBLE_EQ(table_integral(t, 1.5), 1.0);                 // the ramp 1 → −1 nets 0
  EXPECT_DOUBLE_EQ(table_integral(t, 2.5), 0.0);                 // then back at −1
  EXPECT_DOUBLE_EQ(table_integral(TimeTable{}, 3.0), 3.0);       // no table: velocity·t
}

TEST(Scene, SyntaxErrorPositionMatchesNlohmann) {
  // Our "line L, column C" must agree with the position nlohmann itself reports.
  const std::string text = "{\n  \"a\": [1, 2,\n  3 4]\n}";
  try {
    parse_json_text(text, "x.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "line 3, column 5");
    EXPECT_EQ(std::string(e.what()).find("[json.exception"), std::string::npos) << e.what();
  }
  try {
    const json ignored = json::parse(text);
    FAIL();
  } catch (const json::parse_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 3, column 5"), std::string::npos) << e.what();
  }
}

TEST(Scene, CommentsAreAccepted) {
  const json doc =
      parse_json_text("/* lead */ { // line\n \"a\": /* inline */ 1 }\n// trail\n", "c.json");
  EXPECT_EQ(doc.at("a"), 1);
}

TEST(Scene, SceneFromJsonRejectsNaN) {
  // Merge patches build documents in memory, where NaN can appear (JSON text cannot hold it).
  json doc = json::parse(kBase);
  doc["mesh"]["size"] = std::numeric_limits<double>::quiet_NaN();
  try {
    scene_from_json(doc, "patched.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/mesh/size");
    EXPECT_NE(std::string(e.what()).find("must be a finite number (got nan)"), std::string::npos)
        << e.what();
  }
}

TEST(Scene, RingAreaAndBodyArea) {
  const Ring ccw{{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  const Ring cw{{0, 0}, {0, 3}, {4, 3}, {4, 0}};
  EXPECT_DOUBLE_EQ(ring_signed_area(ccw), 12.0);
  EXPECT_DOUBLE_EQ(ring_signed_area(cw), -12.0);
  EXPECT_DOUBLE_EQ(ring_signed_area(Ring{{1e6, 1e6}, {1e6 + 1, 1e6}, {1e6, 1e6 + 1}}), 0.5);
  EXPECT_EQ(ring_signed_area(Ring{}), 0.0);
  BodyDef body;
  body.outer = cw;  // orientation does not matter for either ring
  body.holes = {Ring{{1, 1}, {2, 1}, {2, 2}, {1, 2}}, Ring{{3, 1}, {3, 2}, {2.5, 2}}};
  EXPECT_DOUBLE_EQ(body_area(body), 12.0 - 1.0 - 0.25);
}

}  // namespace
}  // namespace nmm
