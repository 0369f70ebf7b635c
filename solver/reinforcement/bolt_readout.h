// What the outputs read of a bolt (bolts.csv, summary.json "bolts", result.svg): at each of its
// points, the distance along it, the axial force there, the grout's force per metre and where
// the point is. Forces per bolt (docs/interface.md "Rock bolts and cables").
//
// Axial force at a point: a segment carries one force, so inside a cable a point shows the mean
// of its two segments (the force at the point, to second order in the segment length), and an
// end point half of its segment's (the cable's force falls to 0 at a free end over the half
// segment its grout stands for). An anchored bolt is one spring between its anchors: both ends
// show its force. Bond force per metre: the grout's force on the cable at the point, along the
// bolt from its first point to its second, over its tributary length — positive where the rock
// holds the cable back against a pull at its first point (a head pulled out of its hole).
#pragma once

#include <vector>

#include "common/scene.h"
#include "solver/discretisation/run_state.h"

namespace nmm::solve {

struct BoltReading {
  double s = 0;           ///< m, along the bolt from its first point (as installed)
  double axial = 0;       ///< N per bolt, tension positive
  double bond = 0;        ///< N per m of bolt, the grout's force on the cable along the bolt (0: anchored)
  double x = 0, y = 0;    ///< m, where the point is now
  double ux = 0, uy = 0;  ///< m, its displacement since the mesh was cut (as a frame's)
};

/// The bolt's points, first to last.
std::vector<BoltReading> bolt_readout(const BoltDef& def, const BoltState& b);

}  // namespace nmm::solve
