// Reads a solver run's frames back: frames.pvd (times and files) and one frames/*.vtu (ASCII,
// as common/vtk_writer writes it: Points, point "displacement", cell "block", connectivity,
// offsets). Used by the failing-mechanism picture and by the block-velocity verdict.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace nmm::studies {

struct Frame {
  std::vector<double> points;        ///< [3·point] m, current positions
  std::vector<double> displacement;  ///< [3·point] m, since the start
  std::vector<int> connectivity;     ///< point indices of each cell's loop
  std::vector<int> offsets;          ///< [cell] end of each cell in connectivity (VTK's offsets)
  std::vector<int> block;            ///< [cell] block of each cell (empty if the frame has none)
};

/// (time s, path) of every frame listed in RUN/frames.pvd, in time order. RunError if unreadable.
std::vector<std::pair<double, std::string>> list_frames(const std::string& run_dir);

/// One frame. RunError naming the file when it cannot be read.
Frame read_frame(const std::string& vtu_path);

/// Mean displacement (ux, uy) of each block's cell vertices, m: [2·block], blocks 0..max.
std::vector<double> block_mean_displacement(const Frame& f);

}  // namespace nmm::studies
