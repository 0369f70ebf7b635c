// Solver output files (output_writer.h, contract in docs/interface.md "Solver output in OUTDIR").
//
// Rules:
// - Every file is written whole through write_file_atomically (temporary name, rename), so a
//   reader never sees a half-written file under its final name, even when a run is killed.
//   Frames and frames.pvd skip the fsync (Durability::renamed): two fsyncs per file were most of
//   a frame's cost (docs/performance.md, "Output"); history, summary and checkpoint keep it.
//   history.csv and frames.pvd are therefore kept in memory and rewritten whole each time; both
//   are small next to the frames.
// - Numbers are written as the shortest text that reads back to the same double (std::to_chars):
//   full round-trip precision like %.17g, but "0.001" rather than "0.0010000000000000000208",
//   and independent of the C locale (printf would write "0,001" under a German locale and break
//   the CSV).
// - A frame is the manifold elements as polygons at their current position: the grid of
//   mesh_to_grid (one point per loop vertex, so per-vertex arrays indexed like Mesh::loop_xy are
//   point data as they are) with its coordinates replaced by the current ones. The connectivity
//   comes from the mesh as it was cut, so every frame has the same cells and ParaView can
//   animate them.
// - frames.pvd is a VTK Collection (the ParaView data format for time series) listing every frame
//   written so far with its time; writing the same step again replaces its entry. An effect's
//   grid of the frame (EffectOutput::frame_parts) is a file of its own, frames/<name>_<step>.vtu,
//   listed with the same time as part 1, 2, ...: ParaView's PVD reader makes each part a block
//   of one multiblock data set, so both animate together and keep their own arrays.
#include "solver/output/output_writer.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/vtk_writer.h"
#include "common/vtu_compressed.h"

namespace nmm::solve {

namespace {

namespace fs = std::filesystem;

void append_double(std::string& out, double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}

std::string join_path(const std::string& dir, const std::string& name) {
  return (fs::path(dir) / name).string();
}

/// Creates `path` (and its parents) as a folder, or throws naming `out_dir`.
void make_folder(const std::string& path, const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(path, ec);
  // create_directories reports no error when `path` exists as something else than a folder.
  if (ec || !fs::is_directory(path))
    throw InputError(out_dir, "",
                     "cannot create output folder " + path + ": " +
                         (ec ? ec.message() : std::string("a file of that name exists")));
}

/// Caller bugs, not user input: a field array of the wrong size would write a corrupt frame.
void check_size(const std::vector<double>* v, std::size_t expected, const char* name) {
  if (v == nullptr) throw std::logic_error(std::string("FrameFields::") + name + " is null");
  if (v->size() != expected)
    throw std::logic_error(std::string("FrameFields::") + name + " has " +
                           std::to_string(v->size()) + " values, expected " +
                           std::to_string(expected));
}


}  // namespace

std::string frame_file_name(std::int64_t step) { return frame_part_file_name(step, "frame"); }

std::string frame_part_file_name(std::int64_t step, const std::string& prefix) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "_%06lld.vtu", static_cast<long long>(step));
  return "frames/" + prefix + buf;
}

namespace {
/// frames/ holds this run's files only: "<letters>_<digits>.vtu", the names frame_file_name gives.
bool is_frame_file_name(const std::string& name) {
  const std::size_t u = name.find('_');
  if (u == std::string::npos || u == 0 || name.size() < u + 6 || name.compare(name.size() - 4, 4, ".vtu") != 0)
    return false;
  for (std::size_t i = 0; i < u; ++i)
    if (name[i] < 'a' || name[i] > 'z') return false;
  for (std::size_t i = u + 1; i + 4 < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  return true;
}
}  // namespace

OutputWriter::OutputWriter(const std::string& out_dir, FrameFormat format)
    : dir_(out_dir), format_(format) {
  make_folder(dir_, dir_);
  make_folder(join_path(dir_, "frames"), dir_);
  // A folder used before would mix the old run's frames with this one's (frames.pvd listing
  // some, ParaView's file-series reader all): remove what an earlier run wrote — only the files
  // nmm-solve itself names, nothing else in the folder.
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(join_path(dir_, "frames"), ec)) {
    const std::string name = entry.path().filename().string();
    if (is_frame_file_name(name)) fs::remove(entry.path(), ec);
  }
  // The effects' own files go when a run starts (run_driver.cpp: Effect::output_files).
  for (const char* name : {"frames.pvd", "history.csv", "summary.json", "result.svg", "result.png",
                           "history.svg", "run_history.svg", "load_travel.svg", "load_travel.png", "index.html",
                           "checkpoint.nmmstate", "energy.csv"})
    fs::remove(join_path(dir_, name), ec);
}

void OutputWriter::add_history(std::int64_t step, double time,
                               const std::vector<MeasureSample>& samples) {
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const MeasureSample& s = samples[i];
    history_ += std::to_string(step);
    history_ += ',';
    append_double(history_, time);
    history_ += ',';
    history_ += std::to_string(i);
    for (double v : {s.x, s.y, s.ux, s.uy}) {
      history_ += ',';
      append_double(history_, v);
    }
    history_ += '\n';
  }
}

void OutputWriter::write_frame(std::int64_t step, double time, const Mesh& mesh,
                               const FrameFields& fields, std::size_t topology,
                               const std::vector<FramePart>& parts) {
  const std::size_t nv = mesh.loop_vertex_count();
  const std::size_t ne = mesh.element_count();
  check_size(fields.loop_xy, 2 * nv, "loop_xy");
  check_size(fields.loop_u, 2 * nv, "loop_u");
  check_size(fields.stress, 3 * ne, "stress");
  if (fields.extra_cell != nullptr) check_size(fields.extra_cell, ne, "extra_cell");
  if (fields.vertex_stress != nullptr) check_size(fields.vertex_stress, 3 * nv, "vertex_stress");

  if (grid_mesh_ != &mesh || grid_topology_ != topology) {
    // Once per mesh of the run: the cells change only where an effect changed it (near-duplicate
    // vertices dropped by mesh_to_grid).
    grid_ = mesh_to_grid(mesh);
    grid_mesh_ = &mesh;
    grid_topology_ = topology;
    // mesh_to_grid keeps one point per loop vertex (it drops near-duplicates from the cells
    // only), so point v is loop vertex v; a different layout would silently misplace every value.
    if (grid_.point_count() != nv)
      throw std::logic_error("mesh_to_grid no longer has one point per loop vertex");
    // Keep the identifiers; drop what describes the cut mesh rather than a state (the area of
    // the undeformed loop, the triangle and covers are for nmm-inspect).
    std::vector<GridArray> kept;
    for (GridArray& a : grid_.cell_data)
      if (a.name == "element" || a.name == "block" || a.name == "body") kept.push_back(std::move(a));
    grid_.cell_data = std::move(kept);
    grid_cell_arrays_ = grid_.cell_data.size();
  }
  PolygonGrid& grid = grid_;
  const std::vector<double>& xy = *fields.loop_xy;
  const std::vector<double>& u = *fields.loop_u;
  std::vector<double> displacement(3 * nv);
  for (std::size_t v = 0; v < nv; ++v) {
    grid.points[3 * v] = xy[2 * v];
    grid.points[3 * v + 1] = xy[2 * v + 1];
    displacement[3 * v] = u[2 * v];
    displacement[3 * v + 1] = u[2 * v + 1];
    // ParaView's "Warp By Vector" wants 3-component vectors; z stays 0 in 2D.
  }
  grid.point_data.clear();
  grid.add_point_array("displacement", 3, std::move(displacement));
  if (fields.vertex_stress != nullptr) grid.add_point_array("vertex_stress", 3, *fields.vertex_stress);

  grid.cell_data.resize(grid_cell_arrays_);  // the last frame's fields go
  grid.add_cell_array("stress", 3, *fields.stress);
  if (fields.extra_cell != nullptr)
    grid.add_cell_array(
        fields.extra_cell_name.empty() ? std::string("extra") : fields.extra_cell_name, 1,
        *fields.extra_cell);

  const std::string file = frame_file_name(step);
  // Frames and frames.pvd: the rename without fsync (atomic_file.h, Durability::renamed).
  if (format_ == FrameFormat::text)
    write_vtu(grid, join_path(dir_, file), Durability::renamed);
  else
    write_vtu_compressed(grid, join_path(dir_, file), Durability::renamed);

  auto list = [&](const std::string& name, int part) {
    for (ListedFrame& frame : frames_)
      if (frame.file == name) {
        frame.time = time;
        return;
      }
    frames_.push_back({time, name, part});
  };
  list(file, 0);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::string part_file = frame_part_file_name(step, parts[k].name);
    if (format_ == FrameFormat::text)
      write_vtu(parts[k].grid, join_path(dir_, part_file), Durability::renamed);
    else
      write_vtu_compressed(parts[k].grid, join_path(dir_, part_file), Durability::renamed);
    list(part_file, static_cast<int>(k) + 1);
  }

  std::string pvd =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const ListedFrame& f : frames_) {
    pvd += "    <DataSet timestep=\"";
    append_double(pvd, f.time);
    // The file names are ours (letters, digits), so they need no XML escaping.
    pvd += "\" group=\"\" part=\"" + std::to_string(f.part) + "\" file=\"" + f.file + "\"/>\n";
  }
  pvd += "  </Collection>\n</VTKFile>\n";
  write_file_atomically(join_path(dir_, "frames.pvd"), pvd, Durability::renamed);
}

void OutputWriter::remove_files(const std::vector<std::string>& names) {
  std::error_code ec;
  for (const std::string& name : names) fs::remove(join_path(dir_, name), ec);
}

void OutputWriter::flush_history() {
  write_file_atomically(join_path(dir_, "history.csv"), "step,time,point,x,y,ux,uy\n" + history_);
  tables_.write(dir_);
}

void OutputWriter::write_summary(const nlohmann::json& summary_in) {
  nlohmann::json summary = summary_in;
  if (!inputs_.is_null()) summary["inputs"] = inputs_;
  // Replace invalid UTF-8 (a reason built from a file name, say) rather than throw: the summary
  // is what a failed run leaves behind, so writing it must not fail for that.
  write_file_atomically(
      join_path(dir_, "summary.json"),
      summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

}  // namespace nmm::solve
