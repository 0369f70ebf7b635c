// The checkpoint sections of the effects that carry state (effect_output.h checkpoint_sections:
// ABSORB, BOLTS, FLOW; docs/checkpoint-format.md), written and read by the effects since issue 49
// moved them out of run_state.cpp. A checkpoint must keep its bytes across that move, so that
// checkpoints written before it restart as they did, and state hashes do not move:
//   - the run state's sections and the effects', in MeshBound::checkpointed's order, are byte for
//     byte the layout run_state.cpp wrote (encoded here independently, field by field, from the
//     format's table: legacy_sections);
//   - such a checkpoint reads back, through state_from_sections and each effect's
//     restore_sections, to the state it was written from, every field equal;
//   - the state hash over them is the SHA-256 of every section but DIAG, tags and bytes in order;
//   - a state without bolts, absorbing reaction or flow writes none of the sections;
//   - a damaged section is one InputError naming the file and the section.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/checkpoint_file.h"
#include "common/error.h"
#include "common/mesh_file.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "solver/discretisation/state_bytes.h"
#include "solver/stepping/mesh_bound.h"
#include "solver/stepping/initial_state.h"

namespace nmm {
namespace {

using solve::BoltState;
using solve::ByteWriter;
using solve::RunState;
using solve::TrackedPoint;

// A 2 m × 1 m block, h = 0.5 m: a mesh to hold the sections' element indices.
SceneDef block_scene() {
  nlohmann::json d;
  d["materials"]["rock"] = {{"density", 2500}, {"young", 1e10}, {"poisson", 0.25}};
  d["bodies"] = {{{"material", "rock"}, {"outer", {{0, 0}, {2, 0}, {2, 1}, {0, 1}}}}};
  d["mesh"]["size"] = 0.5;
  d["fixed_points"] = {{0.1, 0.1}, {1.9, 0.1}};
  return scene_from_json(d, "block");
}

// A state carrying all three: an anchored bolt and a grouted cable, an absorbing reaction, flow.
RunState carrying_state(const solve::MeshBound& b) {
  RunState s = solve::initial_state(b.model, b.space);
  s.step = 40;
  BoltState anchored;
  anchored.type = 0;
  anchored.ax = 0.2, anchored.ay = 0.3, anchored.bx = 1.7, anchored.by = 0.6;
  anchored.installed_step = 10;
  anchored.broken = 1;
  anchored.max_axial = 2.5e5;
  anchored.nodes = {{0, 0.2, 0.3, 0.2001, 0.2999}, {1, 1.7, 0.6, 1.7002, 0.6001}};
  anchored.axial = {1.25e5};
  BoltState grouted;
  grouted.type = 1;
  grouted.ax = 0.1, grouted.ay = 0.5, grouted.bx = 1.9, grouted.by = 0.5;
  grouted.installed_step = 40;
  grouted.yielded = 1;
  grouted.max_axial = 3e5;
  grouted.plastic_work = 12.5;
  grouted.nodes = {{0, 0.1, 0.5, 0.1, 0.5}, {1, 1.0, 0.5, 1.0001, 0.5}, {2, 1.9, 0.5, 1.9002, 0.5}};
  grouted.axial = {1e5, 2e5};
  grouted.slip = {1e-4, -2e-5, 3e-6};
  grouted.bond = {-5e4, 1e3, 4e4};
  s.bolts = {anchored, grouted};
  s.absorbing_key = {1, 2, 0, 0, 2, 0};
  s.absorbing_reaction.assign(s.cover_u.size(), 0.0);
  s.absorbing_reaction[1] = -1.5e4;
  s.absorbed_work = 3.25;
  s.absorbing_load_work = 7.5;
  s.flow_pressure = {1e5, 2e5, 1.5e5};
  s.flow_aperture = {1e-4, 2e-4, 1.5e-4, 1e-4};
  s.flow_outflow_rate = {-2e-6};
  s.flow_injected = 1e-3, s.flow_outflow = 4e-4, s.flow_stored = 6e-4, s.flow_load_work = 0.75,
  s.flow_exchanged = 1.4e-3;
  return s;
}

// The sections as run_state.cpp wrote them before issue 49, from the table of
// docs/checkpoint-format.md: ABSORB, BOLTS, FLOW after CARRY, each only when it holds something.
CheckpointSections legacy_sections(const RunState& s, const Mesh& mesh) {
  CheckpointSections out = solve::state_to_sections(s, "", mesh);
  if (!s.absorbing_key.empty()) {
    ByteWriter w;
    w.put_vector(s.absorbing_key);
    w.put_vector(s.absorbing_reaction);
    w.put(s.absorbed_work);
    w.put(s.absorbing_load_work);
    out.emplace_back("ABSORB", w.take());
  }
  if (!s.bolts.empty()) {
    ByteWriter w;
    w.put<std::uint32_t>(1);
    w.put<std::uint64_t>(s.bolts.size());
    for (const BoltState& b : s.bolts) {
      w.put(b.type);
      for (double v : {b.ax, b.ay, b.bx, b.by}) w.put(v);
      w.put(b.installed_step);
      w.put(b.broken);
      w.put(b.yielded);
      w.put(b.max_axial);
      w.put(b.plastic_work);
      w.put<std::uint64_t>(b.nodes.size());
      for (const TrackedPoint& p : b.nodes) {
        w.put(p.element);
        for (double v : {p.x0, p.y0, p.x, p.y}) w.put(v);
      }
      w.put_vector(b.axial);
      w.put_vector(b.slip);
      w.put_vector(b.bond);
    }
    out.emplace_back("BOLTS", w.take());
  }
  if (!s.flow_pressure.empty()) {
    ByteWriter w;
    w.put_vector(s.flow_pressure);
    w.put_vector(s.flow_aperture);
    w.put_vector(s.flow_outflow_rate);
    for (double v : {s.flow_injected, s.flow_outflow, s.flow_stored, s.flow_load_work, s.flow_exchanged}) w.put(v);
    out.emplace_back("FLOW", w.take());
  }
  return out;
}

// The sections the effects write now: the run state's, then MeshBound::checkpointed's.
CheckpointSections effect_sections(const solve::MeshBound& b, const RunState& s, const Mesh& mesh) {
  CheckpointSections out = solve::state_to_sections(s, "", mesh);
  for (const solve::Effect* e : b.checkpointed) e->checkpoint_sections(s, mesh, out);
  return out;
}

}  // namespace

TEST(EffectSections, TheEffectsWriteTheBytesTheRunStateWrote) {
  const SceneDef scene = block_scene();
  const Mesh mesh = pre::build_mesh(scene, "block");
  const solve::MeshBound b(mesh, scene, "block");
  const RunState s = carrying_state(b);
  const CheckpointSections legacy = legacy_sections(s, mesh);
  ASSERT_EQ(legacy.size(), 16u);  // META … DIAG (13), ABSORB, BOLTS, FLOW
  const CheckpointSections now = effect_sections(b, s, mesh);
  ASSERT_EQ(now.size(), legacy.size());
  for (std::size_t i = 0; i < now.size(); ++i) {
    EXPECT_EQ(now[i].first, legacy[i].first) << "section " << i;
    EXPECT_TRUE(now[i].second == legacy[i].second) << "section " << now[i].first << " changed its bytes";
  }
  EXPECT_TRUE(checkpoint_to_bytes(now) == checkpoint_to_bytes(legacy));
  // The hash: every section but DIAG, tag, NUL and bytes, in order.
  std::string all;
  for (const auto& [tag, data] : legacy)
    if (tag != "DIAG") all += tag + std::string(1, '\0') + data;
  EXPECT_EQ(solve::state_hash(now), to_hex(sha256(all)));
  // Without bolts, reaction or flow: the run state's sections alone.
  RunState bare = s;
  bare.bolts.clear();
  bare.absorbing_key.clear();
  bare.absorbing_reaction.clear();
  bare.flow_pressure.clear();
  EXPECT_EQ(effect_sections(b, bare, mesh).size(), 13u);
}

TEST(EffectSections, ACheckpointOfTheOldLayoutReadsBackWhole) {
  const SceneDef scene = block_scene();
  const Mesh mesh = pre::build_mesh(scene, "block");
  const solve::MeshBound b(mesh, scene, "block");
  const RunState s = carrying_state(b);
  // Through the container, as a file written before the move is read.
  const CheckpointSections read = checkpoint_from_bytes(checkpoint_to_bytes(legacy_sections(s, mesh)), "old.nmmstate");
  std::string history;
  RunState r = solve::state_from_sections(read, mesh, "old.nmmstate", history, b.space.dofs_per_cover(), b.space.terms());
  EXPECT_TRUE(r.bolts.empty() && r.absorbing_key.empty() && r.flow_pressure.empty());  // the effects' to read
  for (const solve::Effect* e : b.effects) e->restore_sections(read, mesh, "old.nmmstate", r);
  ASSERT_EQ(r.bolts.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const BoltState &x = s.bolts[i], &y = r.bolts[i];
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(x.installed_step, y.installed_step);
    EXPECT_EQ(x.broken, y.broken);
    EXPECT_EQ(x.yielded, y.yielded);
    EXPECT_EQ(x.max_axial, y.max_axial);
    EXPECT_EQ(x.plastic_work, y.plastic_work);
    EXPECT_EQ(x.axial, y.axial);
    EXPECT_EQ(x.slip, y.slip);
    EXPECT_EQ(x.bond, y.bond);
    ASSERT_EQ(x.nodes.size(), y.nodes.size());
    for (std::size_t k = 0; k < x.nodes.size(); ++k)
      EXPECT_TRUE(x.nodes[k].element == y.nodes[k].element && x.nodes[k].x == y.nodes[k].x && x.nodes[k].y0 == y.nodes[k].y0);
  }
  EXPECT_EQ(r.absorbing_key, s.absorbing_key);
  EXPECT_EQ(r.absorbing_reaction, s.absorbing_reaction);
  EXPECT_EQ(r.absorbed_work, s.absorbed_work);
  EXPECT_EQ(r.absorbing_load_work, s.absorbing_load_work);
  EXPECT_EQ(r.flow_pressure, s.flow_pressure);
  EXPECT_EQ(r.flow_aperture, s.flow_aperture);
  EXPECT_EQ(r.flow_outflow_rate, s.flow_outflow_rate);
  EXPECT_EQ(r.flow_exchanged, s.flow_exchanged);
  // And written again, the same bytes.
  EXPECT_TRUE(checkpoint_to_bytes(effect_sections(b, r, mesh)) == checkpoint_to_bytes(legacy_sections(s, mesh)));
}

TEST(EffectSections, ADamagedSectionIsOneErrorNamingIt) {
  const SceneDef scene = block_scene();
  const Mesh mesh = pre::build_mesh(scene, "block");
  const solve::MeshBound b(mesh, scene, "block");
  RunState s = carrying_state(b);
  s.absorbing_reaction[0] = std::numeric_limits<double>::infinity();
  s.bolts[0].nodes[0].element = 10000;  // past the mesh's elements
  const CheckpointSections bad = legacy_sections(s, mesh);
  std::string history;
  RunState r = solve::state_from_sections(bad, mesh, "bad.nmmstate", history, b.space.dofs_per_cover(), b.space.terms());
  const std::pair<const char*, const solve::Effect*> damaged[] = {{"ABSORB", &b.absorbing}, {"BOLTS", &b.bolts}};
  for (const auto& [tag, effect] : damaged) {
    try {
      effect->restore_sections(bad, mesh, "bad.nmmstate", r);
      ADD_FAILURE() << tag << ": no error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("bad.nmmstate"), std::string::npos) << what;
      EXPECT_NE(what.find(std::string("section ") + tag), std::string::npos) << what;
    }
  }
}

}  // namespace nmm
