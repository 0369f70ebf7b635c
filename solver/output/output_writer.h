// Solver output in OUTDIR (docs/interface.md): history.csv, summary.json, frames.pvd with
// frames/*.vtu, and the CSV files the run's parts write a block of rows to at each output step
// (tables(): the effects' CSV files; solver/discretisation/output_tables.h).
// Every file appears under its final name only when complete (written to a temporary name, then
// renamed), including when a run stops early.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/mesh.h"
#include "common/vtk_writer.h"
#include "solver/discretisation/effect_output.h"
#include "solver/discretisation/output_tables.h"

namespace nmm::solve {

/// One measure point at one output step.
struct MeasureSample {
  double x, y;    ///< m, current position
  double ux, uy;  ///< m, displacement since the start
};

/// What a frame shows: the element loops in their current position.
struct FrameFields {
  const std::vector<double>* loop_xy;      ///< [2·v] m, current loop vertex positions
  const std::vector<double>* loop_u;       ///< [2·v] m, displacement since the start
  const std::vector<double>* stress;       ///< [3·me] Pa, σxx, σyy, σxy per element
  const std::vector<double>* extra_cell = nullptr;  ///< optional per-element scalar, see name
  /// Name of extra_cell in the .vtu. The `{}` lets `FrameFields{&xy, &u, &stress}` leave both
  /// extra members out without -Wmissing-field-initializers (GCC warns for a member without one).
  std::string extra_cell_name{};
  /// [3·v] Pa, σxx σyy σxy of each loop vertex's element at that vertex (cover order ≥ 1: the
  /// stress varies inside an element; every element owns its loop vertices, so the field shows
  /// its jumps between elements); null: not written (point array "vertex_stress")
  const std::vector<double>* vertex_stress = nullptr;
};

/// The frame of a step, relative to the output folder: "frames/frame_000010.vtu" (zero-padded
/// so that a plain listing sorts the frames in order).
std::string frame_file_name(std::int64_t step);
/// An effect's part of that frame: "frames/<prefix>_000010.vtu".
std::string frame_part_file_name(std::int64_t step, const std::string& prefix);

/// How frames are written: binary zlib-compressed appended data (vtu_compressed.h, the default:
/// a tenth of the size or less) or ASCII text (nmm-solve --text-frames).
enum class FrameFormat { compressed, text };

class OutputWriter {
 public:
  /// Creates out_dir and out_dir/frames if needed; InputError(out_dir, "", why) if it cannot.
  /// Removes what an earlier run wrote there (frames, history, summary, pictures).
  explicit OutputWriter(const std::string& out_dir, FrameFormat format = FrameFormat::compressed);

  /// Appends the rows of one output step (one per measure point) to history.csv (in memory until
  /// flush_history()).
  void add_history(std::int64_t step, double time, const std::vector<MeasureSample>& samples);

  /// Writes frames/frame_<step>.vtu (ME polygons, point data "displacement" (3 components),
  /// cell data "stress" (σxx, σyy, σxy as 3 components), "block", "body") and rewrites
  /// frames.pvd listing every frame so far with its time.
  /// `topology`: which mesh of the run this is (RunView::topology: an effect changed it); the cells
  /// are built again when it changes. `parts`: the effects' grids of the frame (EffectOutput::frame_parts),
  /// each written as frames/<name>_<step>.vtu and listed in frames.pvd with the frame's
  /// time as part 1, 2, ... (the elements are part 0).
  void write_frame(std::int64_t step, double time, const Mesh& mesh, const FrameFields& fields,
                   std::size_t topology = 0, const std::vector<FramePart>& parts = {});

  /// Keep the contacts of every n-th output step only (n >= 1; the last one is always kept):
  /// contacts.csv is the largest text output of a long run (nmm-solve --contacts-every).
  void set_contacts_every(int n) { tables_.set_every("contacts.csv", n); }

  /// Write contacts.csv.gz (the same CSV, gzip-compressed: gzip_text.h) instead of contacts.csv
  /// (nmm-solve --contacts-gzip).
  void set_contacts_gzip(bool on) { tables_.set_gzip("contacts.csv", on); }

  /// The CSV files of the output steps (in memory until flush_history()): the run's parts add
  /// their rows (solver/discretisation/output_tables.h).
  OutputTables& tables() { return tables_; }

  /// Removes files an earlier run wrote into the folder (names in it), so that they never mix
  /// with this run's; a file that is not there is no error.
  void remove_files(const std::vector<std::string>& names);

  /// Writes history.csv (header "step,time,point,x,y,ux,uy") with every row so far, and every
  /// table that has rows (tables()).
  void flush_history();

  /// Writes summary.json (pretty-printed), with the run's inputs (set_run_inputs) as "inputs".
  void write_summary(const nlohmann::json& summary);

  /// What the run was made from (mesh file, --config, --set, --restart, picture field), kept in
  /// summary.json "inputs" so that nmm-report can load the mesh and scene to redraw a frame.
  void set_run_inputs(nlohmann::json inputs) { inputs_ = std::move(inputs); }

  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
  FrameFormat format_;
  std::string history_;   // CSV rows so far
  OutputTables tables_;   // the output steps' other CSV files
  struct ListedFrame {
    double time;       // s
    std::string file;  // relative file name
    int part;          // 0: the elements, 1, 2, ...: the effects' parts
  };
  std::vector<ListedFrame> frames_;  // frames.pvd's entries
  nlohmann::json inputs_;  // summary.json "inputs" (null: none)
  // The frame grid: mesh_to_grid of the mesh as cut, with the identifier cell arrays only; every
  // frame overwrites its points and adds its fields (the connectivity never changes).
  const Mesh* grid_mesh_ = nullptr;
  std::size_t grid_topology_ = 0;  // of grid_mesh_ (a new mesh may take the old one's address)
  PolygonGrid grid_;
  std::size_t grid_cell_arrays_ = 0;  // element, block, body
};

}  // namespace nmm::solve
