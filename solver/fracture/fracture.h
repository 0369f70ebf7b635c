// Intact rock that breaks (docs/fracture.md): which elements an accepted step breaks, the crack
// segments that break them, and the cracks' tips carried from step to step.
//
// The rule, after each accepted solution of a step (the new faces are contacts of the fracture
// block's crack_set):
//   1. every crack tip grows: the element ahead of it, if its stress breaks it (rock_strength.h),
//      is crossed from the tip along its crack direction (turned to continue the crack) to where
//      the line leaves it, and so on through the next element, until an element holds or the
//      crack reaches a body boundary or a joint; tips lie on element edges;
//   2. if no tip grew, at most one new crack starts: in the element most beyond its strength
//      (largest ratio, then lowest index) that is armed, a segment through the element (its
//      centroid) along its crack direction, both of whose ends then grow as in 1;
//   3. the step is solved again from its start on the cracked mesh (time_stepper.cpp attempt),
//      and 1–3 repeat until its solution breaks nothing more. A crack thus grows and relieves
//      the stress at the load of the step that broke the rock, whatever the step's length.
// An element a crack crosses is disarmed — its pieces keep the stress it had when it broke, which
// the next steps relax — until its stress falls back inside the strength; a disarmed element may
// still be crossed by a growing tip. Tips start at the ends of the scene's joints that lie inside
// a body, so a crack grows on from a joint as from a crack.
//   4. a disarmed element still beyond its strength whose crack has not parted it (a piece
//      across its crack shares one of its covers, crack_parting.h) is re-armed: it competes with
//      the new cracks of 2 by its ratio, and where it wins, its own crack's active tips grow on
//      instead of a new crack starting in it;
//   5. a new crack of 2 whose element lies straight ahead of an active tip, within three
//      elements, is that tip's: the tip grows to it instead of a second crack starting in line
//      with the first;
//   in 4 and 5 a tensile crack's tip crosses elements that hold only as a rock bridge between
//   joints (tip_drive.h): straight on through at most three of them, each pulled open across the
//   line by its own stress, to a joint or a crack face — the tip's crack or what it reaches tied
//   to a scene joint — or, from a crack tied to a joint, to an element that breaks; never to a
//   body boundary. A shear crack crosses none, and a scene without joints none at all.
// Cracks are cut in the mesh as cut (the reference configuration); their directions come from
// the current stress, turned into that configuration by each element's own affine map
// (element_geometry.h).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "common/vec2.h"
#include "preprocess/recut.h"
#include "solver/discretisation/run_state.h"
#include "solver/fracture/crack_parting.h"
#include "solver/fracture/element_grid.h"
#include "solver/fracture/rock_strength.h"

namespace nmm::solve {

/// One segment of crack, cut into the mesh as one joint of the crack set.
struct CrackSegment {
  Vec2 a, b;            ///< m, its ends as cut (reference configuration)
  Vec2 a_now, b_now;    ///< m, where its ends were when it formed (current configuration)
  CrackMode mode = CrackMode::tensile;
  std::int32_t crack = -1;  ///< which crack it belongs to (0, 1, ... in order of starting)
  std::int64_t step = 0;    ///< the accepted step whose state broke the rock
  double time = 0;          ///< s, that step's end
};

class Fracture {
 public:
  Fracture() = default;
  /// Active when the scene has a fracture block and some material a strength.
  explicit Fracture(const SceneDef& scene);
  bool active() const { return active_; }

  /// After an accepted step: the segments its state breaks (the rule above), on `mesh` with the
  /// state's stresses and cover nodes; `removed` [me] 1: excavated (never breaks). A quiet step
  /// costs one screen per element (StrengthScreen: a square root, no trigonometry) and, where
  /// tips are active, a lookup ahead of each in the mesh's element grid (built once per mesh).
  /// `may_start` [me] (empty: every element): where a new crack may start (rule 2; the rules
  /// of rock that softens, cohesive_starts.h); growth by rules 1, 4, 5 is not narrowed by it.
  std::vector<CrackSegment> find(const Mesh& mesh, const SceneDef& scene, const RunState& s,
                                 const std::vector<std::uint8_t>& removed,
                                 const std::vector<std::uint8_t>& may_start = {});
  /// The segments `find` returned were cut into `mesh` (`map`: from it to the mesh they were
  /// found on): they join the record, the elements they crossed are disarmed, and the blocks
  /// they cut off that are smaller than kDebrisArea·h², or of one element and smaller than
  /// kSliverArea·h², become debris.
  void cut(const std::vector<CrackSegment>& segments, const Mesh& mesh, const pre::RecutMap& map);

  /// [me] 1: debris — an element of a block the cracks cut off smaller than kDebrisArea·h². It
  /// leaves the model like an excavated body (excavation.h): no stiffness, mass, load or
  /// contact, its covers held. A splinter a thousandth of an element in area, held by stiff
  /// crack contacts at a mass four orders below its neighbours', is squeezed out at speed where
  /// cracks converge and stops the run on penetration; its mass is negligible. A fragment of
  /// 4e-3·h² loose between crack faces was pushed 7 mm a step at any Δt (a biaxial specimen past
  /// its peak): a block under a hundredth of an element is debris.
  const std::vector<std::uint8_t>& debris() const { return debris_; }
  static constexpr double kDebrisArea = 1e-2;
  /// A cohesive tip that would cross less than kCornerClip·h of an element straight on keeps its
  /// direction there (a corner clip: the element's stress is the rock's off the crack's line).
  static constexpr double kCornerClip = 0.1;
  /// ×h², below which a new block of a single element is debris too: a sliver the cracks cut
  /// off one element, whose three covers reach no other element, has no stiffness path to the
  /// rock beside it and only its contacts hold it. One of 5.76e-5 m² (1.5e-2·h²) under a
  /// biaxial specimen's platen moved 2.05–2.56 mm a step at every Δt down to the floor, and
  /// stopped the run (docs/fracture.md "Small pieces").
  static constexpr double kSliverArea = 5e-2;
  /// ×h², the least support a physical cover of a run that can crack keeps unknowns of its own
  /// with (cover_unknowns.cpp): a corner the cracks cut off at a node, less than a hundredth of
  /// an element, moves with a neighbour cover. Flaps of 1.5e-3·h² on a loaded boundary were
  /// pushed 2.4 mm in a step at any Δt by the traction on their edge (a biaxial specimen), and
  /// 3.6e-3·h² ones moved in dynamic steps (a uniaxial one).
  static constexpr double kLeastCoverSupport = 1e-2;
  int debris_blocks() const { return debris_blocks_; }
  double debris_area() const { return debris_area_; }  ///< m²

  /// Every segment cut so far, in order: the run's crack joints follow the scene's joints in it.
  const std::vector<CrackSegment>& segments() const { return segments_; }
  int crack_count() const { return cracks_; }
  /// The segments of the cracks that still have an active tip (cohesive_starts.h rule 6).
  std::vector<CrackSegment> growing_segments() const;
  /// Steps taken again because their solution broke the rock (this invocation: diagnostics).
  long resolves() const { return resolves_; }
  void count_resolve() { ++resolves_; }

  /// The checkpoint's FRACTURE section (tips, armed elements, segments), and back; `mesh`: the
  /// cracked mesh the section belongs to.
  std::string save() const;
  void load(const std::string& bytes, const Mesh& mesh, const std::string& name);

 private:
  struct Tip {
    Vec2 at;            // m, as cut
    Vec2 dir;           // unit, the direction it grows in (as cut)
    std::int32_t crack = -1;
    bool active = true;
  };
  void start_tips(const Mesh& mesh, const SceneDef& scene);

  bool active_ = false;
  bool tips_started_ = false;
  std::vector<Tip> tips_;
  std::vector<std::uint8_t> armed_;        // [me] 1: may start a crack
  std::vector<std::uint8_t> crossed_;      // [me of the mesh find() saw] crossed in that step
  std::vector<std::uint8_t> debris_;       // [me]
  // Kept between calls so that a quiet step allocates nothing: the elements by cell of the mesh
  // as cut (built when a tip first looks ahead, dropped when the mesh is cut again), and each
  // element's strength ratio from the last find (−∞: cannot break; below 1 where the screen
  // says it holds) with rock_failure's full check for those the screen passed on.
  std::shared_ptr<const ElementGrid> grid_;
  std::shared_ptr<const TriangleElements> parted_;  // of the mesh find() saw, built when a disarmed element is beyond its strength
  std::vector<double> ratio_;              // [me] –
  std::vector<RockFailure> failure_;       // [me] valid where the last find's ratio_ came from rock_failure
  std::vector<std::int32_t> over_;         // elements of the last find at or beyond their strength, ascending
  std::vector<CrackSegment> segments_;
  int cracks_ = 0;
  int debris_blocks_ = 0;
  double debris_area_ = 0;                 // m²
  long resolves_ = 0;
};

}  // namespace nmm::solve
