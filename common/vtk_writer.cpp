// VTK writers. Formats: "VTK File Formats" (Kitware, VTK User's Guide 11th ed., ch. 19), the
// XML UnstructuredGrid (version 0.1, ASCII) and the legacy "DataFile Version 3.0" layout, which
// every VTK since 4.x, ParaView and meshio read.
#include "common/vtk_writer.h"

#include "common/atomic_file.h"
#include "common/xml_text.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "common/error.h"

namespace nmm {

namespace {

// Shortest text that reads back to the same double: the files are also used to compare runs.
void append_double(std::string& out, double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}

void append_int(std::string& out, long long v) {
  char buf[24];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}


// Legacy files are whitespace-separated tokens: a name must be one non-empty token.
std::string legacy_name(const std::string& s) {
  std::string out = s.empty() ? std::string("unnamed") : s;
  for (char& c : out)
    if (static_cast<unsigned char>(c) <= ' ') c = '_';
  return out;
}

// Values as lines of up to `per_line` numbers: keeps the ASCII files readable in an editor.
void append_values(std::string& out, const GridArray& a, const std::string& indent,
                   std::size_t per_line) {
  const std::size_t n = a.value_count();
  for (std::size_t i = 0; i < n; ++i) {
    if (i % per_line == 0) out += indent;
    if (a.type == GridArray::Type::Float64)
      append_double(out, a.f64[i]);
    else
      append_int(out, a.i32[i]);
    out += (i + 1) % per_line == 0 || i + 1 == n ? '\n' : ' ';
  }
}

void add_array(std::vector<GridArray>& arrays, const std::string& name, int components,
               std::vector<double> f64, std::vector<std::int32_t> i32, GridArray::Type type) {
  GridArray a;
  a.name = name;
  a.type = type;
  a.components = components;
  a.f64 = std::move(f64);
  a.i32 = std::move(i32);
  arrays.push_back(std::move(a));
}

void check_arrays(const std::vector<GridArray>& arrays, std::size_t tuples, const char* where) {
  for (const GridArray& a : arrays) {
    if (a.components < 1)
      throw std::logic_error(std::string("PolygonGrid ") + where + " array '" + a.name +
                             "': components < 1");
    if (a.value_count() != tuples * static_cast<std::size_t>(a.components))
      throw std::logic_error(std::string("PolygonGrid ") + where + " array '" + a.name + "' has " +
                             std::to_string(a.value_count()) + " values, expected " +
                             std::to_string(tuples) + " x " + std::to_string(a.components));
  }
}

void append_xml_arrays(std::string& out, const std::vector<GridArray>& arrays, const char* tag) {
  if (arrays.empty()) return;
  out += "      <";
  out += tag;
  out += ">\n";
  for (const GridArray& a : arrays) {
    out += "        <DataArray type=\"";
    out += a.type == GridArray::Type::Float64 ? "Float64" : "Int32";
    out += "\" Name=\"" + xml_escape(a.name) + "\" NumberOfComponents=\"";
    append_int(out, a.components);
    out += "\" format=\"ascii\">\n";
    append_values(out, a, "          ", static_cast<std::size_t>(a.components) * 4);
    out += "        </DataArray>\n";
  }
  out += "      </";
  out += tag;
  out += ">\n";
}

void append_legacy_arrays(std::string& out, const std::vector<GridArray>& arrays) {
  // All arrays go into one FIELD: VTK's legacy reader keeps only the first SCALARS / VECTORS
  // attribute of a section unless told to read them all (ReadAllScalarsOn), but always reads
  // every FIELD array, and a FIELD takes any number of components. ParaView shows them alike.
  out += "FIELD FieldData ";
  append_int(out, static_cast<long long>(arrays.size()));
  out += '\n';
  for (const GridArray& a : arrays) {
    out += legacy_name(a.name) + " ";
    append_int(out, a.components);
    out += ' ';
    append_int(out,
               static_cast<long long>(a.value_count() / static_cast<std::size_t>(a.components)));
    out += a.type == GridArray::Type::Float64 ? " double\n" : " int\n";
    append_values(out, a, "", static_cast<std::size_t>(a.components) * 4);
  }
}

}  // namespace

std::int32_t PolygonGrid::add_point(double x, double y) {
  points.push_back(x);
  points.push_back(y);
  points.push_back(0.0);
  return static_cast<std::int32_t>(point_count() - 1);
}

void PolygonGrid::add_cell(const std::vector<std::int32_t>& loop) {
  if (offsets.empty()) offsets.push_back(0);
  connectivity.insert(connectivity.end(), loop.begin(), loop.end());
  offsets.push_back(static_cast<std::int32_t>(connectivity.size()));
}

void PolygonGrid::add_point_array(const std::string& name, int components,
                                  std::vector<double> values) {
  add_array(point_data, name, components, std::move(values), {}, GridArray::Type::Float64);
}
void PolygonGrid::add_point_array(const std::string& name, int components,
                                  std::vector<std::int32_t> values) {
  add_array(point_data, name, components, {}, std::move(values), GridArray::Type::Int32);
}
void PolygonGrid::add_cell_array(const std::string& name, int components,
                                 std::vector<double> values) {
  add_array(cell_data, name, components, std::move(values), {}, GridArray::Type::Float64);
}
void PolygonGrid::add_cell_array(const std::string& name, int components,
                                 std::vector<std::int32_t> values) {
  add_array(cell_data, name, components, {}, std::move(values), GridArray::Type::Int32);
}

void check_grid(const PolygonGrid& g) {
  if (g.points.size() % 3 != 0) throw std::logic_error("PolygonGrid: points not a multiple of 3");
  if (g.offsets.empty() || g.offsets.front() != 0)
    throw std::logic_error("PolygonGrid: offsets must start with 0");
  for (std::size_t c = 0; c + 1 < g.offsets.size(); ++c)
    if (g.offsets[c + 1] < g.offsets[c]) throw std::logic_error("PolygonGrid: offsets decrease");
  if (static_cast<std::size_t>(g.offsets.back()) != g.connectivity.size())
    throw std::logic_error("PolygonGrid: last offset != connectivity length");
  if (g.cell_type != PolygonGrid::kPolygon && g.cell_type != PolygonGrid::kLine)
    throw std::logic_error("PolygonGrid: cell type neither polygon nor line");
  if (g.cell_type == PolygonGrid::kLine)
    for (std::size_t c = 0; c + 1 < g.offsets.size(); ++c)
      if (g.offsets[c + 1] - g.offsets[c] != 2) throw std::logic_error("PolygonGrid: a line cell without two points");
  for (std::int32_t p : g.connectivity)
    if (p < 0 || static_cast<std::size_t>(p) >= g.point_count())
      throw std::logic_error("PolygonGrid: point index out of range");
  check_arrays(g.point_data, g.point_count(), "point");
  check_arrays(g.cell_data, g.cell_count(), "cell");
}

std::string vtu_text(const PolygonGrid& g) {
  check_grid(g);
  std::string out;
  out.reserve(64 * (g.points.size() + g.connectivity.size()) + 1024);
  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <Piece NumberOfPoints=\"";
  append_int(out, static_cast<long long>(g.point_count()));
  out += "\" NumberOfCells=\"";
  append_int(out, static_cast<long long>(g.cell_count()));
  out += "\">\n";
  append_xml_arrays(out, g.point_data, "PointData");
  append_xml_arrays(out, g.cell_data, "CellData");

  GridArray pts;
  pts.components = 3;
  pts.f64 = g.points;
  out += "      <Points>\n";
  out +=
      "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
      "format=\"ascii\">\n";
  append_values(out, pts, "          ", 3);
  out += "        </DataArray>\n";
  out += "      </Points>\n";

  // VTK's offsets are the end of each cell (no leading 0), unlike our CSR.
  GridArray conn, offs, types;
  conn.type = offs.type = types.type = GridArray::Type::Int32;
  conn.i32 = g.connectivity;
  offs.i32.assign(g.offsets.begin() + 1, g.offsets.end());
  types.i32.assign(g.cell_count(), g.cell_type);
  out += "      <Cells>\n";
  out += "        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  append_values(out, conn, "          ", 12);
  out += "        </DataArray>\n";
  out += "        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  append_values(out, offs, "          ", 12);
  out += "        </DataArray>\n";
  out += "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  append_values(out, types, "          ", 24);
  out += "        </DataArray>\n";
  out += "      </Cells>\n";
  out += "    </Piece>\n";
  out += "  </UnstructuredGrid>\n";
  out += "</VTKFile>\n";
  return out;
}

std::string legacy_vtk_text(const PolygonGrid& g, const std::string& title) {
  check_grid(g);
  std::string out;
  out.reserve(64 * (g.points.size() + g.connectivity.size()) + 1024);
  out += "# vtk DataFile Version 3.0\n";
  // The title line is at most 256 characters and must be one line.
  std::string t = title.substr(0, 255);
  for (char& c : t)
    if (c == '\n' || c == '\r') c = ' ';
  out += t + "\n";
  out += "ASCII\nDATASET UNSTRUCTURED_GRID\n";
  out += "POINTS ";
  append_int(out, static_cast<long long>(g.point_count()));
  out += " double\n";
  for (std::size_t p = 0; p < g.point_count(); ++p) {
    append_double(out, g.points[3 * p]);
    out += ' ';
    append_double(out, g.points[3 * p + 1]);
    out += ' ';
    append_double(out, g.points[3 * p + 2]);
    out += '\n';
  }
  // CELLS n size: size counts every integer in the section, the leading vertex counts included.
  out += "CELLS ";
  append_int(out, static_cast<long long>(g.cell_count()));
  out += ' ';
  append_int(out, static_cast<long long>(g.cell_count() + g.connectivity.size()));
  out += '\n';
  for (std::size_t c = 0; c < g.cell_count(); ++c) {
    append_int(out, g.offsets[c + 1] - g.offsets[c]);
    for (std::int32_t i = g.offsets[c]; i < g.offsets[c + 1]; ++i) {
      out += ' ';
      append_int(out, g.connectivity[static_cast<std::size_t>(i)]);
    }
    out += '\n';
  }
  out += "CELL_TYPES ";
  append_int(out, static_cast<long long>(g.cell_count()));
  out += '\n';
  for (std::size_t c = 0; c < g.cell_count(); ++c) {
    append_int(out, g.cell_type);
    out += '\n';
  }
  if (!g.cell_data.empty()) {
    out += "CELL_DATA ";
    append_int(out, static_cast<long long>(g.cell_count()));
    out += '\n';
    append_legacy_arrays(out, g.cell_data);
  }
  if (!g.point_data.empty()) {
    out += "POINT_DATA ";
    append_int(out, static_cast<long long>(g.point_count()));
    out += '\n';
    append_legacy_arrays(out, g.point_data);
  }
  return out;
}

void write_vtu(const PolygonGrid& grid, const std::string& path, Durability durability) {
  write_file_atomically(path, vtu_text(grid), durability);
}

void write_legacy_vtk(const PolygonGrid& grid, const std::string& path, const std::string& title) {
  write_file_atomically(path, legacy_vtk_text(grid, title));
}

bool is_vtu_path(const std::string& path) {
  const std::string ext = ".vtu";
  return path.size() >= ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
}

void write_vtk_by_extension(const PolygonGrid& grid, const std::string& path,
                            const std::string& title) {
  if (is_vtu_path(path))
    write_vtu(grid, path);
  else
    write_legacy_vtk(grid, path, title);
}

PolygonGrid mesh_to_grid(const Mesh& mesh) {
  PolygonGrid g;
  const std::size_t ne = mesh.element_count();
  const std::size_t nv = mesh.loop_vertex_count();
  g.points.reserve(3 * nv);
  for (std::size_t v = 0; v < nv; ++v) g.add_point(mesh.loop_xy[2 * v], mesh.loop_xy[2 * v + 1]);
  // Point v is loop vertex v, so per-vertex data computed along the loops (the solver's
  // displacement) is point data as it is. A cell skips a vertex lying within kMergeShare of
  // its element's size from the previous kept one: such near-duplicates (edges of 1e-9 m where
  // a boundary passes next to a mesh node) make VTK's ear-cutting triangulation drop the whole
  // polygon, leaving holes in the rendering. The `area` array keeps the exact loop area.
  constexpr double kMergeShare = 1e-5;
  g.connectivity.reserve(nv);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto b = static_cast<std::size_t>(mesh.element_loop_offset[e]);
    const auto end = static_cast<std::size_t>(mesh.element_loop_offset[e + 1]);
    const double* p = mesh.loop_xy.data();
    double x0 = p[2 * b], x1 = x0, y0 = p[2 * b + 1], y1 = y0;
    for (std::size_t v = b; v < end; ++v) {
      x0 = std::min(x0, p[2 * v]), x1 = std::max(x1, p[2 * v]);
      y0 = std::min(y0, p[2 * v + 1]), y1 = std::max(y1, p[2 * v + 1]);
    }
    const double tol = kMergeShare * std::hypot(x1 - x0, y1 - y0);
    auto near = [&](std::size_t a, std::size_t c) {
      return std::hypot(p[2 * a] - p[2 * c], p[2 * a + 1] - p[2 * c + 1]) <= tol;
    };
    std::vector<std::int32_t> kept;
    for (std::size_t v = b; v < end; ++v)
      if (kept.empty() || !near(static_cast<std::size_t>(kept.back()), v))
        kept.push_back(static_cast<std::int32_t>(v));
    while (kept.size() > 1 &&
           near(static_cast<std::size_t>(kept.back()), static_cast<std::size_t>(kept.front())))
      kept.pop_back();
    if (kept.size() < 3) {  // a sliver: keep it whole rather than lose the cell
      kept.clear();
      for (std::size_t v = b; v < end; ++v) kept.push_back(static_cast<std::int32_t>(v));
    }
    g.add_cell(kept);
  }

  std::vector<std::int32_t> id(ne);
  std::vector<double> area(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    id[e] = static_cast<std::int32_t>(e);
    area[e] = element_area(mesh, e);
  }
  g.add_cell_array("element", 1, std::move(id));
  g.add_cell_array("triangle", 1, mesh.element_triangle);
  g.add_cell_array("block", 1, mesh.element_block);
  g.add_cell_array("body", 1, mesh.element_body);
  g.add_cell_array("area", 1, std::move(area));
  g.add_cell_array("covers", 3, mesh.element_covers);
  return g;
}


}  // namespace nmm
