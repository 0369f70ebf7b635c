// The failing mechanism of nmm-fos (mechanism.svg): the last frame of the failing trial with the
// smallest factor, drawn by the solver's result picture (result_picture.h through
// result_redraw.h) — the same colour map, model frame (x, y in metres, axes and scale bar),
// units (|u| in mm), exaggeration and contact states as every result.svg, with the trial's
// factor in the title.
#pragma once

#include <string>

namespace nmm::studies {

/// Writes the picture of the last frame of the run in `run_dir` (an nmm-solve output folder)
/// to `svg_path` (atomically), the title starting with `title`. Throws RunError when the run
/// cannot be drawn (no readable frame, its mesh gone).
void write_mechanism_svg(const std::string& run_dir, const std::string& title,
                         const std::string& svg_path);

}  // namespace nmm::studies
