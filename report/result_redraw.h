// result.svg of a finished run, redrawn from its folder (nmm-report): the frame of one output
// step (the last by default) read back with common/vtu_reader.h, the contacts of that step from
// contacts.csv, the measure points from history.csv, and the mesh and run scene from the files
// summary.json "inputs" names (the mesh file, --config, --set), or a mesh given explicitly.
//
// The frame holds every loop vertex as a point (point v is Mesh::loop_xy vertex v) with exact
// binary doubles, and the CSVs hold round-trip text, so the redrawn last frame is the picture
// nmm-solve --pictures drew from its state in memory, byte for byte.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/mesh.h"
#include "report/result_picture.h"
#include "common/scene.h"

namespace nmm::report {

struct RedrawOptions {
  std::int64_t frame_step = -1;  ///< step number of the frame (frames/frame_<step>.vtu); -1: last
  std::string mesh_path;         ///< "" : summary.json inputs.mesh
  std::string field;             ///< "" : summary.json inputs.picture_field, else displacement
  /// Drawn displacement factor; 0: summary.json inputs.exaggerate, else automatic.
  double exaggerate = 0;
  std::string title;             ///< first words of the title; "": the scene's name
};

/// What redraw_result drew.
struct RedrawInfo {
  std::int64_t step = 0;   ///< step of the frame drawn
  double time = 0;         ///< s
  std::size_t polygons = 0;  ///< manifold elements drawn
  std::size_t contacts = 0;  ///< closed contacts drawn
  bool contacts_known = true;
};

/// The mesh and run scene of a run folder: the mesh file summary.json "inputs.mesh" names (or
/// `mesh_path` when not empty) with the run's --config and --set applied. InputError naming
/// summary.json or the mesh file when they cannot be used.
struct RunInputs {
  std::string mesh_path;
  Mesh mesh;
  SceneDef scene;
  nlohmann::json summary;  ///< the run's summary.json, as read
};
RunInputs load_run_inputs(const std::string& dir, const std::string& mesh_path);

/// RUN/summary.json parsed; InputError naming it when it is missing or not JSON.
nlohmann::json read_run_summary(const std::string& dir);

/// (time s, step) of every frame listed in RUN/frames.pvd, in order. InputError if unreadable.
std::vector<std::pair<double, std::int64_t>> list_run_frames(const std::string& dir);

/// result.svg of the chosen frame, as text (nmm-fos draws a trial's mechanism with it); `info`
/// (when given) says what was drawn. Errors as redraw_result.
std::string redraw_result_svg(const std::string& dir, const RedrawOptions& options,
                              RedrawInfo* info = nullptr);

/// Writes DIR/result.svg for the chosen frame. InputError (file, where, what) when the folder,
/// the mesh or the frame cannot be used: a frame of another mesh, a step without a frame, ...
RedrawInfo redraw_result(const std::string& dir, const RedrawOptions& options);

}  // namespace nmm::report
