// Tests of a run's variants (common/run_config.h): the merge patch of --config, the --set syntax,
// the refusal of geometry changes, and the one-line InputError of every kind of mistake. The
// function reads only Mesh::scene_text, so the mesh here is a scene and nothing else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "common/error.h"
#include "common/mesh.h"
#include "common/run_config.h"
#include "common/scene.h"
#include "tests/temp_dir.h"

namespace nmm::solve {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nmm::test::TempDir;

const char* const kScene = R"({
  // two bodies, one joint: enough of every part to vary
  "name": "variants",
  "gravity": [0, -9.81],
  "materials": { "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 } },
  "joint_sets": {
    "bedding": { "friction_deg": 20,
                 "normal": { "model": "constant", "kn": 5e11 },
                 "shear":  { "model": "constant", "ks": 2e11 } }
  },
  "bodies": [ { "material": "rock", "outer": [[0,0],[10,0],[10,5],[0,5]] } ],
  "joints": [ { "set": "bedding", "points": [[0,1],[10,1.5]] } ],
  "mesh": { "size": 0.5 },
  "fixed_points": [[0,0],[10,0]],
  "loads": [ { "point": [5,5], "force": [0,-1e6] } ],
  "measure_points": [[5,4]],
  "solver": { "time_step": 1e-3, "steps": 1000 }
})";

Mesh scene_mesh(const std::string& text = kScene) {
  Mesh mesh;
  mesh.scene_file = "variants.json";
  mesh.scene_text = text;
  return mesh;
}

RunScene run(const std::vector<std::string>& sets, const std::string& config = "") {
  return make_run_scene(scene_mesh(), "m.nmm", config, sets);
}

// Runs `f`, expects an InputError, and returns it for the caller to check.
InputError input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    // The contract: one line on stderr.
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", "", "");
}

TEST(RunConfig, NoVariantsGiveTheEmbeddedScene) {
  const RunScene r = run({});
  const SceneDef s = parse_scene(kScene, "x");
  EXPECT_EQ(r.effective, parse_json_text(kScene, "x"));
  EXPECT_EQ(r.scene.name, "variants");
  EXPECT_TRUE(r.scene.has_gravity);
  EXPECT_EQ(r.scene.gravity, s.gravity);
  EXPECT_EQ(r.scene.solver.time_step, 1e-3);
  EXPECT_EQ(r.scene.solver.steps, 1000);
  ASSERT_EQ(r.scene.loads.size(), 1u);
  EXPECT_EQ(r.scene.loads[0].force, (Vec2{0, -1e6}));
  EXPECT_EQ(r.scene.joints.size(), 1u);
}

TEST(RunConfig, BadEmbeddedSceneIsBlamedOnTheMeshFile) {
  const InputError e = input_error(
      [] { make_run_scene(scene_mesh(R"({"materials": {}})"), "m.nmm", "", {"name=x"}); });
  EXPECT_EQ(e.file(), "m.nmm (embedded scene)");
}

TEST(RunConfig, MergePatchChangesAndRemoves) {
  TempDir dir;
  const std::string config = dir.file("v.json", R"({
    // a merge patch: null removes, objects merge, arrays replace
    "gravity": null,
    "solver": { "time_step": 2e-4 },
    "joint_sets": { "bedding": { "friction_deg": 35 } },
    "loads": [ { "point": [5,5], "force": [1,2] }, { "point": [1,5], "force": [3,4] } ]
  })");
  const RunScene r = run({}, config);
  EXPECT_FALSE(r.scene.has_gravity);
  EXPECT_FALSE(r.effective.contains("gravity"));
  EXPECT_EQ(r.scene.solver.time_step, 2e-4);
  EXPECT_EQ(r.scene.solver.steps, 1000);  // merged, not replaced
  ASSERT_EQ(r.scene.joint_sets.size(), 1u);
  EXPECT_EQ(r.scene.joint_sets[0].friction_deg, 35);
  EXPECT_EQ(r.scene.joint_sets[0].normal.kn, 5e11);
  ASSERT_EQ(r.scene.loads.size(), 2u);
  EXPECT_EQ(r.scene.loads[1].force, (Vec2{3, 4}));
  EXPECT_EQ(r.effective["solver"]["time_step"], 2e-4);
}

TEST(RunConfig, SetNumberStringBareWordAndIndex) {
  const RunScene r =
      run({"solver.time_step=5e-4", "name=\"quoted\"", "plane=stress", "loads.0.force=[7, -8]",
           "loads.0.point.1=4.5", "solver.dynamic=false", "materials.rock.young=2e10"});
  EXPECT_EQ(r.scene.solver.time_step, 5e-4);
  EXPECT_EQ(r.scene.name, "quoted");
  EXPECT_EQ(r.scene.plane, PlaneKind::stress);  // bare word taken as a string
  EXPECT_EQ(r.scene.loads[0].force, (Vec2{7, -8}));
  EXPECT_EQ(r.scene.loads[0].point, (Vec2{5, 4.5}));
  EXPECT_FALSE(r.scene.solver.dynamic);
  EXPECT_EQ(r.scene.materials[0].young, 2e10);
  EXPECT_EQ(r.effective["plane"], "stress");
}

TEST(RunConfig, SetCreatesMissingObjects) {
  // A new joint set, built one --set at a time (its objects do not exist beforehand).
  const RunScene r =
      run({"joint_sets.faults.friction_deg=30", "joint_sets.faults.normal.model=constant",
           "joint_sets.faults.normal.kn=1e9", "joint_sets.faults.shear.model=hyperbolic",
           "joint_sets.faults.shear.ksi=1e10", "joint_sets.faults.shear.rf=0.9",
           "interface_set=faults"});
  ASSERT_EQ(r.scene.joint_sets.size(), 2u);
  EXPECT_EQ(r.scene.joint_sets[1].name, "faults");
  EXPECT_EQ(r.scene.joint_sets[1].friction_deg, 30);
  EXPECT_EQ(r.scene.joint_sets[1].shear.model, ShearModel::hyperbolic);
  EXPECT_EQ(r.scene.joint_sets[1].shear.rf, 0.9);
  EXPECT_EQ(r.scene.interface_set, 1);
}

TEST(RunConfig, SetNullRemovesAKey) {
  const RunScene r = run({"gravity=null"});
  EXPECT_FALSE(r.scene.has_gravity);
  EXPECT_FALSE(r.effective.contains("gravity"));
}

TEST(RunConfig, ConfigThenSetsInOrder) {
  TempDir dir;
  const std::string config = dir.file("v.json", R"({"solver": {"time_step": 2e-4, "steps": 7}})");
  const RunScene r = run({"solver.time_step=1e-5", "solver.time_step=3e-5"}, config);
  EXPECT_EQ(r.scene.solver.time_step, 3e-5);
  EXPECT_EQ(r.scene.solver.steps, 7);
}

TEST(RunConfig, UnchangedGeometryIsAccepted) {
  TempDir dir;
  // Restated with 10.0 for 10: equal as JSON values, so not a change.
  const std::string config =
      dir.file("v.json", R"({"mesh": {"size": 0.50}, "bodies": [ { "material": "rock",
                   "outer": [[0,0],[10.0,0],[10,5],[0,5]] } ]})");
  EXPECT_NO_THROW(run({"mesh.size=0.5"}, config));
}

TEST(RunConfig, GeometryIsRefusedFromConfig) {
  TempDir dir;
  const struct {
    const char* patch;
    const char* where;
  } cases[] = {
      {R"({"bodies": [ { "material": "rock", "outer": [[0,0],[11,0],[10,5],[0,5]] } ]})",
       "/bodies"},
      {R"({"joints": null})", "/joints"},
      {R"({"mesh": {"size": 0.25}})", "/mesh"},
  };
  for (const auto& c : cases) {
    const std::string config = dir.file("geometry.json", c.patch);
    const InputError e = input_error([&] { run({}, config); });
    EXPECT_EQ(e.file(), config) << c.patch;
    EXPECT_EQ(e.where(), c.where) << c.patch;
    EXPECT_NE(e.message().find("geometry cannot change"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find("preprocess the scene again"), std::string::npos) << e.what();
  }
}

TEST(RunConfig, GeometryIsRefusedFromSet) {
  const struct {
    const char* set;
    const char* where;
  } cases[] = {
      {"bodies.0.outer.1.0=11", "/bodies"},
      {"bodies.0.holes=[[[4,2],[6,2],[6,3]]]", "/bodies"},
      {"joints.0.points.1=[10,2]", "/joints"},
      {"joints=null", "/joints"},
      {"mesh.size=0.25", "/mesh"},
  };
  for (const auto& c : cases) {
    const InputError e = input_error([&] { run({"solver.steps=3", c.set}); });
    EXPECT_EQ(e.file(), "--set") << c.set;
    EXPECT_EQ(e.where(), c.where) << c.set;
    EXPECT_NE(e.message().find("geometry cannot change"), std::string::npos) << e.what();
  }
}

// Generated joint sets (docs/joint-networks.md): the embedded scene keeps the generate block as
// generated_from; changing either on the solver would be accepted and ignored, so it is refused
// with the command that does rebuild the network.
TEST(RunConfig, GenerateKeysAreRefusedAndNameThePreprocessor) {
  std::string text = kScene;
  const std::string shear = R"("shear":  { "model": "constant", "ks": 2e11 } })";
  const auto at = text.find(shear);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, shear.size(),
               R"("shear":  { "model": "constant", "ks": 2e11 },
                 "generated_from": { "orientation": { "mean_deg": 10 }, "p21": 0.1,
                                     "length": 3, "seed": 1 } })");
  const Mesh mesh = scene_mesh(text);
  EXPECT_NO_THROW(make_run_scene(mesh, "m.nmm", "", {"joint_sets.bedding.friction_deg=25"}));
  const struct {
    const char* set;
    const char* where;
  } cases[] = {
      {"joint_sets.bedding.generate.seed=3", "/joint_sets/bedding/generate"},
      {"joint_sets.bedding.generated_from.seed=3", "/joint_sets/bedding/generated_from"},
      {"joint_sets.bedding.generated_from=null", "/joint_sets/bedding/generated_from"},
      {"joint_sets.new.generate.seed=3", "/joint_sets/new/generate"},
  };
  for (const auto& c : cases) {
    const InputError e = input_error([&] { make_run_scene(mesh, "m.nmm", "", {c.set}); });
    EXPECT_EQ(e.file(), "--set") << c.set;
    EXPECT_EQ(e.where(), c.where) << c.set;
    EXPECT_NE(e.message().find("nmm-preprocess --set"), std::string::npos) << e.what();
  }
  TempDir dir;
  const std::string config =
      dir.file("seed.json", R"({"joint_sets": {"bedding": {"generated_from": {"seed": 4}}}})");
  const InputError e = input_error([&] { make_run_scene(mesh, "m.nmm", config, {}); });
  EXPECT_EQ(e.file(), config);
  EXPECT_EQ(e.where(), "/joint_sets/bedding/generated_from");
}

TEST(RunConfig, BadConfigFile) {
  TempDir dir;
  const std::string bad_json = dir.file("bad.json", "{\n  \"solver\": { \"steps\": 5, }\n}\n");
  InputError e = input_error([&] { run({}, bad_json); });
  EXPECT_EQ(e.file(), bad_json);
  EXPECT_EQ(e.where().rfind("line 2, column ", 0), 0u) << e.what();
  EXPECT_NE(e.message().find("invalid JSON"), std::string::npos) << e.what();

  const std::string array = dir.file("array.json", "[1, 2]");
  e = input_error([&] { run({}, array); });
  EXPECT_EQ(e.file(), array);
  EXPECT_EQ(e.where(), "top level");

  const std::string missing = (fs::temp_directory_path() / "nmm-no-such-variant.json").string();
  e = input_error([&] { run({}, missing); });
  EXPECT_EQ(e.file(), missing);
}

TEST(RunConfig, VariantMakingTheSceneInvalidNamesTheValue) {
  InputError e = input_error([] { run({"solver.time_step=-1"}); });
  EXPECT_EQ(e.where(), "/solver/time_step");
  EXPECT_NE(e.file().find("m.nmm"), std::string::npos) << e.what();
  EXPECT_NE(e.file().find("--set"), std::string::npos) << e.what();

  TempDir dir;
  const std::string config = dir.file("v.json", R"({"materials": {"rock": {"poisson": 0.5}}})");
  e = input_error([&] { run({}, config); });
  EXPECT_EQ(e.where(), "/materials/rock/poisson");
  EXPECT_NE(e.file().find("--config " + config), std::string::npos) << e.what();

  // A misspelt key is an unknown key, not a silently ignored one.
  e = input_error([] { run({"solver.timestep=1e-4"}); });
  EXPECT_EQ(e.where(), "/solver/timestep");
}

TEST(RunConfig, MalformedSets) {
  const char* const cases[] = {
      "solver.time_step",         // no '='
      "=1",                       // empty path
      "solver..time_step=1",      // empty key
      ".solver=1",                // empty key
      "solver.=1",                // empty key
      "loads.first.force=[1,2]",  // not an index into an array
      "loads.1.force=[1,2]",      // index out of range
      "loads.-1.force=[1,2]",     // not an index
      "name.first=x",             // into a string
      "solver.steps.x=1",         // into a number
      "loads.0.force.0.x=1",      // into a number inside an array
      "solver.time_step=1e400",   // too large for a double
      "loads.0.force=[1,2",       // meant as JSON, broken
      "name=\"unterminated",      // meant as JSON, broken
  };
  for (const char* set : cases) {
    const InputError e = input_error([&] { run({set}); });
    EXPECT_EQ(e.file(), "--set") << set;
    EXPECT_EQ(e.where(), set) << e.what();
    EXPECT_FALSE(e.message().empty()) << set;
  }
  const InputError e = input_error([] { run({"loads.3.force=[1,2]"}); });
  EXPECT_EQ(e.message(), "index 3 is out of range: /loads has 1 element");
}

}  // namespace
}  // namespace nmm::solve
