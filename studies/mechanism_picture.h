// The failing mechanism: the last frame of a solver run, drawn as the deformed manifold elements
// coloured by displacement magnitude (blue 0 → red max), with a colour bar. Reads the run's own
// frames.pvd / frames/*.vtu (ASCII, written by common/vtk_writer), so it needs no mesh file.
// Kept on its own over common/svg_writer so that the shared result-picture module can replace it.
#pragma once

#include <string>

namespace nmm::studies {

/// Writes the picture of the last frame of the run in `run_dir` to `svg_path` (atomically).
/// Throws RunError when the run has no readable frame.
void write_mechanism_svg(const std::string& run_dir, const std::string& title,
                         const std::string& svg_path);

}  // namespace nmm::studies
