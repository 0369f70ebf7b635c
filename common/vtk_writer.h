// VTK output of polygon cells for ParaView: XML UnstructuredGrid (.vtu, ASCII) and legacy .vtk.
//
// One PolygonGrid serves both the inspector (the mesh as it was cut) and the solver's frames
// (displacement as 3-component point data, stress as cell data), so the writers know nothing
// about NMM: they take points, CSR polygon loops and named arrays.
//
// Cells are VTK_POLYGON (type 7). Manifold element loops are weakly simple (slits along joints
// ending inside an element, zero-width bridges to holes); VTK accepts them as polygons, and its
// ear-cutting triangulation still renders them correctly in the common cases.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/mesh.h"

namespace nmm {

/// A named data array attached to points or cells: `components` values per tuple.
struct GridArray {
  enum class Type { Float64, Int32 };
  std::string name;  ///< shown in ParaView; spaces become '_' in legacy files
  Type type = Type::Float64;
  int components = 1;             ///< values per point / cell, >= 1
  std::vector<double> f64;        ///< [components·tuple] when type == Float64
  std::vector<std::int32_t> i32;  ///< [components·tuple] when type == Int32

  std::size_t value_count() const { return type == Type::Float64 ? f64.size() : i32.size(); }
};

/// Polygon cells over a point set, with named point and cell data. `cell_type` kLine makes every
/// cell a line between two points instead (the flow network of a frame: flow_effect.h).
struct PolygonGrid {
  static constexpr std::uint8_t kPolygon = 7;  ///< VTK_POLYGON
  static constexpr std::uint8_t kLine = 3;     ///< VTK_LINE: every cell has exactly two points
  std::uint8_t cell_type = kPolygon;       ///< the VTK cell type of every cell
  std::vector<double> points;              ///< [3·point] x, y, z, m (z = 0 in 2D)
  std::vector<std::int32_t> offsets{0};    ///< [cell+1] CSR into connectivity, offsets[0] = 0
  std::vector<std::int32_t> connectivity;  ///< point indices of each cell's loop, CCW
  std::vector<GridArray> point_data;       ///< each with point_count() tuples
  std::vector<GridArray> cell_data;        ///< each with cell_count() tuples

  std::size_t point_count() const { return points.size() / 3; }
  std::size_t cell_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }

  /// Appends a point (x, y, 0) and returns its index.
  std::int32_t add_point(double x, double y);
  /// Appends a cell whose loop is the given point indices.
  void add_cell(const std::vector<std::int32_t>& loop);

  /// Appends a data array; `values` must hold components × (point or cell count) values.
  void add_point_array(const std::string& name, int components, std::vector<double> values);
  void add_point_array(const std::string& name, int components, std::vector<std::int32_t> values);
  void add_cell_array(const std::string& name, int components, std::vector<double> values);
  void add_cell_array(const std::string& name, int components, std::vector<std::int32_t> values);
};

/// Throws std::logic_error if the grid is inconsistent (CSR offsets, point indices, array
/// sizes). A bad grid is a bug in the caller, not bad user input.
void check_grid(const PolygonGrid& grid);

/// The file contents, for tests and for callers that write elsewhere.
std::string vtu_text(const PolygonGrid& grid);
std::string legacy_vtk_text(const PolygonGrid& grid, const std::string& title);

/// Write atomically (see write_file_atomically). InputError naming `path` on failure.
void write_vtu(const PolygonGrid& grid, const std::string& path,
               Durability durability = Durability::synced);
void write_legacy_vtk(const PolygonGrid& grid, const std::string& path,
                      const std::string& title = "nmm");
/// True if `path` ends in ".vtu": such files get the XML format, all others the legacy one.
bool is_vtu_path(const std::string& path);
/// .vtu (XML) if is_vtu_path(path), legacy .vtk otherwise.
void write_vtk_by_extension(const PolygonGrid& grid, const std::string& path,
                            const std::string& title = "nmm");

/// The manifold elements as polygon cells. Point v is loop vertex v (points are not shared
/// between elements: NMM displacement jumps across joints, so per-element points let the solver
/// write the discontinuous field exactly, as point data indexed like Mesh::loop_xy). A cell
/// leaves out loop vertices that nearly coincide with their predecessor (within 1e-5 of the
/// element's size), which VTK's polygon triangulation cannot handle.
/// Cell data: element, triangle, block, body (Int32), area (Float64, m², of the exact loop),
/// covers (Int32, 3 components, the physical cover of each triangle node in its node order).
PolygonGrid mesh_to_grid(const Mesh& mesh);


}  // namespace nmm
