// A crack cut by hand into a stressed run, as the fracture effect cuts one (Fracture::apply): run
// the scene to `run_time`, add one crack segment to its joints (the scene's crack_set), re-cut the
// mesh incrementally (pre::recut) and carry the state over (solve::transfer_state). The fracture
// tests compare the state before and after the cut (fields, strain energy, crack vertices).
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "common/mesh.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"
#include "preprocess/recut.h"
#include "solver/fracture/state_transfer.h"
#include "solver/stepping/fracture_effect.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::test {

struct CutCrack {
  SceneDef scene, cracked;  // the scene, and the scene with the crack segment among its joints
  Mesh before_mesh, now;    // the mesh as the run had it, and as re-cut
  pre::RecutMap map;        // now → before_mesh
  solve::RunState before, after;  // the run's state at run_time, and carried onto `now`
  Outcome outcome;          // of the run to run_time
  bool cracked_in_run = false;  // the run cracked by itself before the cut
};

/// `dofs`: a cover's unknowns (2 at cover order 0; 2·monomial_count(n) at order n).
inline CutCrack cut_crack(const SceneDef& scene, const std::string& name, double run_time,
                          const std::array<Vec2, 2>& segment, int dofs) {
  CutCrack c;
  c.scene = scene;
  c.before_mesh = pre::build_mesh(c.scene, name);
  solve::TimeStepper st(c.before_mesh, c.scene, name);
  c.outcome = st.run_until(run_time, [](std::int64_t) {});
  c.cracked_in_run = !solve::fracture_of(st.view()).segments().empty();
  c.before = st.view().state;
  c.cracked = c.scene;
  const std::size_t first = c.cracked.joints.size();
  c.cracked.joints.push_back({c.cracked.fracture.crack_set, {segment[0], segment[1]}});
  c.now = pre::recut(c.before_mesh, c.cracked, first, name, c.map);
  c.after = c.before;
  solve::transfer_state(c.before_mesh, c.now, c.map, dofs, c.after);
  return c;
}

}  // namespace nmm::test
