// Solver output in OUTDIR (docs/interface.md): history.csv, summary.json, frames.pvd with
// frames/*.vtu. Every file appears under its final name only when complete (written to a
// temporary name, then renamed), including when a run stops early.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/mesh.h"
#include "common/vtk_writer.h"

namespace nmm::solve {

/// One measure point at one output step.
struct MeasureSample {
  double x, y;    ///< m, current position
  double ux, uy;  ///< m, displacement since the start
};

/// One contact at one output step (contacts.csv).
struct ContactSample {
  double x, y;             ///< m, the contact vertex
  int state;               ///< 0 open, 1 locked, 2 sliding
  int law;                 ///< joint set index (or the default interface's, last)
  double closure;          ///< m, −gap (> 0: the faces overlap by this much), the normal spring's:
                           ///< net of a Barton–Bandis joint's dilation (faces apart by dilation − closure)
  double shear;            ///< m, elastic shear of the shear spring
  double normal_force;     ///< N, compression
  double shear_force;      ///< N
  double kn, ks;           ///< N/m, tangent stiffnesses (0 where the spring is off)
  double length;           ///< m, tributary joint length
  int vertex;              ///< loop vertex P of the contact (Mesh::loop_xy index)
  int edge;                ///< first loop vertex of the edge P faces (edge → next vertex)
  double pressure = 0;     ///< Pa, water pressure in the joint at the contact (joint_water.h)
  double jrc_mob = 0;      ///< –, mobilised JRC (Barton–Bandis shear; 0 for the other laws)
  double dilation = 0;     ///< m, the joint's opening from shearing (Barton–Bandis; else 0)
};

/// One point of a bolt at one output step (bolts.csv; solver/reinforcement/bolt_readout.h).
struct BoltSample {
  int bolt;            ///< the scene's bolt, from 0
  double s;            ///< m, along the bolt from its first point
  double axial_force;  ///< N per bolt, tension positive
  double bond_force;   ///< N per m of bolt, the grout's force (0 for an anchored bolt)
  double x, y;         ///< m, current position
  double ux, uy;       ///< m, displacement since the mesh was cut
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
  /// `topology`: which mesh of the run this is (RunView::topology: cracks re-cut it); the cells
  /// are built again when it changes.
  void write_frame(std::int64_t step, double time, const Mesh& mesh, const FrameFields& fields,
                   std::size_t topology = 0);

  /// Keep the contacts of every n-th output step only (n >= 1; the last one is always kept):
  /// contacts.csv is the largest text output of a long run (nmm-solve --contacts-every).
  void set_contacts_every(int n) { contacts_every_ = n < 1 ? 1 : n; }

  /// Write contacts.csv.gz (the same CSV, gzip-compressed: gzip_text.h) instead of contacts.csv
  /// (nmm-solve --contacts-gzip).
  void set_contacts_gzip(bool on) { contacts_gzip_ = on; }

  /// Appends one output step's contacts to contacts.csv (in memory until flush_history()).
  void add_contacts(std::int64_t step, double time, const std::vector<ContactSample>& contacts);

  /// Appends one output step's bolt points to bolts.csv (in memory until flush_history()).
  void add_bolts(std::int64_t step, double time, const std::vector<BoltSample>& points);

  /// Writes history.csv (header "step,time,point,x,y,ux,uy") with every row so far, bolts.csv
  /// ("step,time,bolt,s,axial_force,bond_force,x,y,ux,uy") if any bolt rows were added, and
  /// contacts.csv ("step,time,contact,x,y,state,set,closure,shear,normal_force,shear_force,kn,ks,
  /// length,vertex,edge,normal_stress,shear_stress,pressure,effective_normal_stress,jrc_mob,
  /// dilation": forces in N, stiffnesses N/m, the tributary length in m, the joint stresses N/L,
  /// T/L in Pa — N/L being the effective normal stress, repeated by name — the water pressure in
  /// Pa, the mobilised JRC and the dilation in m) if any contact rows were added.
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
  std::string contacts_;  // contacts.csv rows so far
  std::string bolts_;     // bolts.csv rows so far
  std::string pending_contacts_;  // the last skipped output step's rows (sampling)
  int contacts_every_ = 1;
  bool contacts_gzip_ = false;
  std::int64_t contact_calls_ = 0;
  std::vector<std::pair<double, std::string>> frames_;  // time, relative file name
  nlohmann::json inputs_;  // summary.json "inputs" (null: none)
  // The frame grid: mesh_to_grid of the mesh as cut, with the identifier cell arrays only; every
  // frame overwrites its points and adds its fields (the connectivity never changes).
  const Mesh* grid_mesh_ = nullptr;
  std::size_t grid_topology_ = 0;  // of grid_mesh_ (a new mesh may take the old one's address)
  PolygonGrid grid_;
  std::size_t grid_cell_arrays_ = 0;  // element, block, body
};

}  // namespace nmm::solve
