// The cracks of a run and their tips as NumPy arrays (nmm.Solver.cracks(), .crack_tips();
// docs/python.md "Cracks and crack tips"): what cracks.csv and crack_tips.csv hold, read from the
// run's state while it steps (solver/stepping/fracture_effect.h, solver/fracture/crack_tip_readout.h).
#pragma once

#include "python/binding.h"
#include "solver/fracture/crack_tips.h"
#include "solver/stepping/run_view.h"

namespace nmm::python {

/// Every crack segment of the run so far, in the order they formed, as cracks.csv's columns:
/// x0, y0, x1, y1 (m, where its ends were when it formed), mode (0 tensile, 1 shear), crack (the
/// crack it belongs to), step, time (s) — a dict of arrays, each of one row per segment.
py::dict crack_segments(const solve::RunView& run);

/// The tips inside a body now (the scene's joints' and the cracks'), as crack_tips.csv's
/// columns: tip (its number, kept as its crack grows, `finder` numbering them over its calls),
/// x, y (m, where it is now), k1, k2 (Pa·√m), angle_deg (the maximum tangential stress direction,
/// deg counter-clockwise from +x), direction (the same as a unit vector, (n, 2)), radius (m, the
/// interaction integral's domain).
py::dict crack_tips(const solve::RunView& run, solve::CrackTipFinder& finder);

}  // namespace nmm::python
