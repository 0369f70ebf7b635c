// Tests of the solver's output files (solver/output/output_writer.h) on a hand-made two-element mesh:
// the exact text of history.csv and frames.pvd, the arrays of the .vtu frames, summary.json, that
// no temporary file is left behind, and that ParaView's readers' stand-in (meshio) reads the
// frames back with the values written.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "common/error.h"
#include "common/mesh.h"
#include "common/gzip_text.h"
#include "solver/output/output_writer.h"
#include "common/vtu_compressed.h"
#include "common/vtu_reader.h"
#include "tests/temp_dir.h"

namespace nmm::solve {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nmm::test::TempDir;

// Element 0: the unit square (4 loop vertices); element 1: a triangle to its right (3 vertices),
// in another block and body so the identifiers are told apart.
Mesh two_element_mesh() {
  Mesh m;
  m.mesh_size = 1;
  m.node_xy = {0, 0, 1, 0, 0, 1, 1, 1, 2, 0};
  m.triangle_nodes = {0, 1, 2, 1, 4, 3};
  m.cover_node = {0, 1, 2, 1, 3, 4};
  m.cover_body = {0, 0, 0, 1, 1, 1};
  m.element_triangle = {0, 1};
  m.element_body = {0, 1};
  m.element_block = {0, 1};
  m.element_covers = {0, 1, 2, 3, 4, 5};
  m.element_loop_offset = {0, 4, 7};
  m.loop_xy = {0, 0, 1, 0, 1, 1, 0, 1, /**/ 1, 0, 2, 0, 1, 1};
  m.loop_edge_origin.assign(7, kEdgeBoundary);
  m.loop_edge_joint.assign(7, -1);
  m.block_body = {0, 1};
  return m;
}

// The fields of output number `k`: displacement grows with k, so each frame is distinct.
struct Fields {
  std::vector<double> xy, u, stress, extra;
  FrameFields view(bool with_extra) const {
    FrameFields f{&xy, &u, &stress};
    if (with_extra) {
      f.extra_cell = &extra;
      f.extra_cell_name = "contact_state";
    }
    return f;
  }
};
Fields fields_at(const Mesh& m, int k) {
  Fields f;
  for (std::size_t v = 0; v < m.loop_vertex_count(); ++v) {
    // The same expressions as in the meshio check below, so the doubles compare exactly.
    const double ux = 0.001 * k * static_cast<double>(v + 1);
    const double uy = -0.002 * k * static_cast<double>(v + 1);
    f.u.insert(f.u.end(), {ux, uy});
    f.xy.insert(f.xy.end(), {m.loop_xy[2 * v] + ux, m.loop_xy[2 * v + 1] + uy});
  }
  f.stress = {1e6 * k, -2e6 * k, 0.5e6 * k, 3e6 * k, 4e6 * k, -5e6 * k};
  f.extra = {0, 1};
  return f;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// Every file under `dir` (relative paths), to check what a run leaves behind.
std::vector<std::string> all_files(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file()) out.push_back(fs::relative(entry.path(), dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

// Writes what a short run writes: frames at steps 10 and 20, two history rows per step, a summary.
void write_run(const fs::path& out, const Mesh& mesh, FrameFormat format = FrameFormat::text) {
  OutputWriter w(out.string(), format);  // text by default, so the tests can read the numbers
  const Fields f1 = fields_at(mesh, 1), f2 = fields_at(mesh, 2);
  w.add_history(10, 0.01, {{1, 2, 0.1, 0.2}, {3, 4, 0.1 + 0.2, -1e-300}});
  w.write_frame(10, 0.01, mesh, f1.view(false));
  w.flush_history();
  w.add_history(20, 0.02, {{1.5, 2.5, 0.5, 0.5}, {3, 4, 0, 0}});
  w.write_frame(20, 0.02, mesh, f2.view(true));
  w.flush_history();
  w.write_summary({{"status", "ok"}, {"steps_completed", 20}, {"effects", {"elasticity"}}});
}

TEST(OutputWriter, WritesEveryFileWholeAndNoTemporaries) {
  TempDir dir;
  const fs::path out = dir.path() / "run" / "nested";  // created, parents included
  const Mesh mesh = two_element_mesh();
  write_run(out, mesh);

  EXPECT_EQ(all_files(out),
            (std::vector<std::string>{"frames.pvd", "frames/frame_000010.vtu",
                                      "frames/frame_000020.vtu", "history.csv", "summary.json"}));

  EXPECT_EQ(read_file(out / "history.csv"),
            "step,time,point,x,y,ux,uy\n"
            "10,0.01,0,1,2,0.1,0.2\n"
            "10,0.01,1,3,4,0.30000000000000004,-1e-300\n"
            "20,0.02,0,1.5,2.5,0.5,0.5\n"
            "20,0.02,1,3,4,0,0\n");

  EXPECT_EQ(read_file(out / "frames.pvd"),
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0.01\" group=\"\" part=\"0\" "
            "file=\"frames/frame_000010.vtu\"/>\n"
            "    <DataSet timestep=\"0.02\" group=\"\" part=\"0\" "
            "file=\"frames/frame_000020.vtu\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");

  const std::string summary = read_file(out / "summary.json");
  EXPECT_EQ(json::parse(summary),
            (json{{"status", "ok"}, {"steps_completed", 20}, {"effects", {"elasticity"}}}));
  EXPECT_TRUE(contains(summary, "{\n  \"effects\": [\n    \"elasticity\"\n  ],\n")) << summary;
}

TEST(OutputWriter, FrameHoldsCurrentPositionsAndTheArrays) {
  TempDir dir;
  const Mesh mesh = two_element_mesh();
  write_run(dir.path(), mesh);

  const std::string first = read_file(dir.path() / "frames/frame_000010.vtu");
  EXPECT_TRUE(contains(first, "NumberOfPoints=\"7\" NumberOfCells=\"2\"")) << first;
  EXPECT_TRUE(contains(first, "Name=\"displacement\" NumberOfComponents=\"3\"")) << first;
  EXPECT_TRUE(contains(first, "Name=\"stress\" NumberOfComponents=\"3\"")) << first;
  EXPECT_TRUE(contains(first, "Name=\"block\"")) << first;
  EXPECT_TRUE(contains(first, "Name=\"body\"")) << first;
  EXPECT_FALSE(contains(first, "contact_state")) << "no extra array was given";
  // Vertex 1 of element 0 is (1, 0) moved by (0.002, -0.004).
  EXPECT_TRUE(contains(first, "1.002 -0.004 0")) << first;
  EXPECT_TRUE(contains(first, "1e+06 -2e+06 5e+05 3e+06 4e+06 -5e+06")) << first;

  const std::string second = read_file(dir.path() / "frames/frame_000020.vtu");
  EXPECT_TRUE(contains(second, "Name=\"contact_state\" NumberOfComponents=\"1\"")) << second;
  EXPECT_TRUE(contains(second, "1.004 -0.008 0")) << second;
}

TEST(OutputWriter, SameStepAgainReplacesItsFrame) {
  TempDir dir;
  const Mesh mesh = two_element_mesh();
  OutputWriter w(dir.path().string());
  const Fields f = fields_at(mesh, 1);
  w.write_frame(5, 0.5, mesh, f.view(false));
  w.write_frame(5, 0.25, mesh, f.view(false));
  const std::string pvd = read_file(dir.path() / "frames.pvd");
  EXPECT_TRUE(contains(pvd,
                       "timestep=\"0.25\" group=\"\" part=\"0\" "
                       "file=\"frames/frame_000005.vtu\""))
      << pvd;
  EXPECT_FALSE(contains(pvd, "timestep=\"0.5\"")) << pvd;
  // An empty history still has its header.
  w.flush_history();
  EXPECT_EQ(read_file(dir.path() / "history.csv"), "step,time,point,x,y,ux,uy\n");
}

TEST(OutputWriter, WrongFieldSizesAreCallerBugs) {
  TempDir dir;
  const Mesh mesh = two_element_mesh();
  OutputWriter w(dir.path().string());
  Fields f = fields_at(mesh, 1);
  f.stress.pop_back();
  EXPECT_THROW(w.write_frame(1, 0.1, mesh, f.view(false)), std::logic_error);
  f = fields_at(mesh, 1);
  f.extra.push_back(2);
  EXPECT_THROW(w.write_frame(1, 0.1, mesh, f.view(true)), std::logic_error);
  EXPECT_FALSE(fs::exists(dir.path() / "frames/frame_000001.vtu"));
  EXPECT_FALSE(fs::exists(dir.path() / "frames.pvd"));
}

TEST(OutputWriter, UnusableOutputFolderIsAnInputError) {
  TempDir dir;
  const fs::path file = dir.path() / "a_file";
  std::ofstream(file) << "x";
  try {
    OutputWriter w(file.string());
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file.string());
  }
  try {
    OutputWriter w((file / "below").string());
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (file / "below").string());
  }
}

// A Python with meshio: `python3` first; else the system one (a python3 found first on PATH, a
// pyenv one say, may not see the distribution's python3-meshio package).
std::string python_with_meshio() {
  for (const char* python : {"python3", "/usr/bin/python3"}) {
    const std::string probe = std::string(python) + " -c 'import meshio' >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) return python;
  }
  return "";
}

// The check meshio makes, with the expected values computed as in fields_at().
const char* const kMeshioCheck = R"(
import os, sys
import xml.etree.ElementTree as ET
import meshio
import numpy as np

out = sys.argv[1]
root = ET.parse(os.path.join(out, "frames.pvd")).getroot()
assert root.get("type") == "Collection", root.get("type")
sets = root.find("Collection").findall("DataSet")
assert [float(d.get("timestep")) for d in sets] == [0.01, 0.02], sets
loop_xy = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [1, 0], [2, 0], [1, 1]], dtype=float)
for k, d in zip([1, 2], sets):
    m = meshio.read(os.path.join(out, d.get("file")))
    assert len(m.points) == 7, len(m.points)
    assert sum(len(block.data) for block in m.cells) == 2, m.cells
    u = m.point_data["displacement"]
    assert u.shape == (7, 3), u.shape
    n = np.arange(1, 8, dtype=float)
    ux = np.array([0.001 * k * v for v in n])
    uy = np.array([-0.002 * k * v for v in n])
    assert np.array_equal(u[:, 0], ux), u
    assert np.array_equal(u[:, 1], uy), u
    assert np.array_equal(u[:, 2], np.zeros(7)), u
    assert np.array_equal(m.points[:, 0], loop_xy[:, 0] + ux), m.points
    assert np.array_equal(m.points[:, 1], loop_xy[:, 1] + uy), m.points
    stress = np.concatenate([np.reshape(s, (-1, 3)) for s in m.cell_data["stress"]])
    expected = np.array([[1e6 * k, -2e6 * k, 0.5e6 * k], [3e6 * k, 4e6 * k, -5e6 * k]])
    assert np.array_equal(stress, expected), stress
print("meshio check ok")
)";

TEST(OutputWriter, MeshioReadsTheFramesBack) {
  const std::string python = python_with_meshio();
  if (python.empty()) GTEST_SKIP() << "no python3 with meshio";
  for (FrameFormat format : {FrameFormat::text, FrameFormat::compressed}) {
    TempDir dir;
    write_run(dir.path() / "out", two_element_mesh(), format);
    const fs::path script = dir.path() / "check.py";
    std::ofstream(script) << kMeshioCheck;
    const std::string command =
        python + " '" + script.string() + "' '" + (dir.path() / "out").string() + "'";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
  }
}


// The default frame is binary and zlib-compressed (vtu_compressed.h): decode the appended data
// of "Points" and "stress" as ParaView would and compare with the values written.
TEST(OutputWriter, CompressedFrameDecodesToTheValuesWritten) {
  TempDir dir;
  const Mesh mesh = two_element_mesh();
  {
    OutputWriter w(dir.path().string());
    const Fields f = fields_at(mesh, 1);
    w.write_frame(10, 0.01, mesh, f.view(false));
  }
  const std::string vtu = read_file(dir.path() / "frames/frame_000010.vtu");
  ASSERT_TRUE(contains(vtu, "compressor=\"vtkZLibDataCompressor\"")) << vtu.substr(0, 300);
  const std::size_t underscore = vtu.find('_', vtu.find("<AppendedData encoding=\"raw\">"));
  ASSERT_NE(underscore, std::string::npos);
  auto decode = [&](const std::string& name) {
    const std::size_t at = vtu.find("Name=\"" + name + "\"");
    const std::size_t off = vtu.find("offset=\"", at) + 8;
    std::size_t pos = underscore + 1 + std::stoull(vtu.substr(off, vtu.find('"', off) - off));
    auto u64 = [&](std::size_t i) {
      std::uint64_t v;
      std::memcpy(&v, vtu.data() + pos + 8 * i, 8);
      return v;
    };
    const std::uint64_t nblocks = u64(0);
    std::vector<double> out;
    std::size_t data = pos + 8 * (3 + nblocks);
    for (std::uint64_t b = 0; b < nblocks; ++b) {
      std::vector<unsigned char> raw(u64(1));
      uLongf len = raw.size();
      EXPECT_EQ(uncompress(raw.data(), &len, reinterpret_cast<const Bytef*>(vtu.data() + data),
                           u64(3 + b)), Z_OK);
      data += u64(3 + b);
      for (std::size_t i = 0; i + 8 <= len; i += 8) {
        double v;
        std::memcpy(&v, raw.data() + i, 8);
        out.push_back(v);
      }
    }
    return out;
  };
  const std::vector<double> points = decode("Points");
  ASSERT_EQ(points.size(), 21u);  // 7 points × 3
  // Vertex 1 of element 0 is (1, 0) moved by (0.002, -0.004).
  EXPECT_DOUBLE_EQ(points[3], 1.002);
  EXPECT_DOUBLE_EQ(points[4], -0.004);
  const std::vector<double> stress = decode("stress");
  EXPECT_EQ(stress, (std::vector<double>{1e6, -2e6, 5e5, 3e6, 4e6, -5e6}));
}


// Reading frames back (vtu_reader.h): a frame, compressed or text, gives back exactly the
// positions, displacements, stresses and identifiers written, and the cells of the mesh.
// An effect's part of a frame (the flow network, effect_output.h FramePart): its own file per
// step beside the frame, listed in frames.pvd at the frame's time as part 1; its line cells read
// back as lines with the values written, in both formats; an earlier run's part files go.
TEST(OutputWriter, FramePartsAreListedBesideTheirFrame) {
  for (const FrameFormat format : {FrameFormat::text, FrameFormat::compressed}) {
    TempDir dir;
    const fs::path out = dir.path() / "run";
    fs::create_directories(out / "frames");
    std::ofstream(out / "frames" / "flow_000099.vtu") << "an earlier run's";
    std::ofstream(out / "frames" / "notes.vtu") << "not ours";
    const Mesh mesh = two_element_mesh();
    OutputWriter w(out.string(), format);
    FramePart part;
    part.name = "flow";
    part.grid.cell_type = PolygonGrid::kLine;
    for (const double x : {0.0, 1.0, 2.0}) part.grid.add_point(x, 0.5);
    part.grid.add_cell({0, 1});
    part.grid.add_cell({1, 2});
    part.grid.add_point_array("pressure", 1, std::vector<double>{1e6, 5e5, 0.1});
    part.grid.add_cell_array("aperture", 1, std::vector<double>{1e-4, 2.5e-4});
    const Fields f = fields_at(mesh, 1);
    w.write_frame(10, 0.01, mesh, f.view(false), 0, {part});
    w.write_frame(20, 0.02, mesh, f.view(false), 0, {part});
    EXPECT_EQ(all_files(out), (std::vector<std::string>{"frames.pvd", "frames/flow_000010.vtu", "frames/flow_000020.vtu",
                                                         "frames/frame_000010.vtu", "frames/frame_000020.vtu",
                                                         "frames/notes.vtu"}));
    EXPECT_EQ(read_file(out / "frames.pvd"),
              "<?xml version=\"1.0\"?>\n"
              "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
              "  <Collection>\n"
              "    <DataSet timestep=\"0.01\" group=\"\" part=\"0\" file=\"frames/frame_000010.vtu\"/>\n"
              "    <DataSet timestep=\"0.01\" group=\"\" part=\"1\" file=\"frames/flow_000010.vtu\"/>\n"
              "    <DataSet timestep=\"0.02\" group=\"\" part=\"0\" file=\"frames/frame_000020.vtu\"/>\n"
              "    <DataSet timestep=\"0.02\" group=\"\" part=\"1\" file=\"frames/flow_000020.vtu\"/>\n"
              "  </Collection>\n"
              "</VTKFile>\n");
    const PolygonGrid back = read_vtu((out / "frames" / "flow_000020.vtu").string());
    EXPECT_EQ(back.cell_type, PolygonGrid::kLine);
    EXPECT_EQ(back.connectivity, (std::vector<std::int32_t>{0, 1, 1, 2}));
    ASSERT_EQ(back.point_data.size(), 1u);
    EXPECT_EQ(back.point_data[0].f64, (std::vector<double>{1e6, 5e5, 0.1}));
    ASSERT_EQ(back.cell_data.size(), 1u);
    EXPECT_EQ(back.cell_data[0].f64, (std::vector<double>{1e-4, 2.5e-4}));
    // The elements' frame is still all polygons.
    EXPECT_EQ(read_vtu((out / "frames" / "frame_000020.vtu").string()).cell_type, PolygonGrid::kPolygon);
  }
  // A line cell of three points is a caller's bug, never a file.
  PolygonGrid bad;
  bad.cell_type = PolygonGrid::kLine;
  for (const double x : {0.0, 1.0, 2.0}) bad.add_point(x, 0);
  bad.add_cell({0, 1, 2});
  EXPECT_THROW(check_grid(bad), std::logic_error);
}

TEST(VtuReader, FramesReadBackToTheValuesWritten) {
  for (const FrameFormat format : {FrameFormat::compressed, FrameFormat::text}) {
    TempDir dir;
    const Mesh mesh = two_element_mesh();
    write_run(dir.path(), mesh, format);
    const Fields f = fields_at(mesh, 2);
    const PolygonGrid g = read_vtu((dir.path() / "frames/frame_000020.vtu").string());
    const PolygonGrid want = mesh_to_grid(mesh);
    ASSERT_EQ(g.point_count(), 7u);
    EXPECT_EQ(g.offsets, want.offsets);
    EXPECT_EQ(g.connectivity, want.connectivity);
    const GridArray* disp = nullptr;
    for (const GridArray& a : g.point_data)
      if (a.name == "displacement") disp = &a;
    ASSERT_NE(disp, nullptr);
    for (std::size_t v = 0; v < 7; ++v) {
      // Text frames are written with the shortest round-trip text: exact in both formats.
      EXPECT_EQ(disp->f64[3 * v], f.u[2 * v]) << v;
      EXPECT_EQ(disp->f64[3 * v + 1], f.u[2 * v + 1]) << v;
      EXPECT_EQ(g.points[3 * v], f.xy[2 * v]) << v;
      EXPECT_EQ(g.points[3 * v + 1], f.xy[2 * v + 1]) << v;
    }
    std::vector<std::string> cell_names;
    for (const GridArray& a : g.cell_data) {
      cell_names.push_back(a.name);
      if (a.name == "stress") {
        EXPECT_EQ(a.f64, f.stress);
      } else if (a.name == "block") {
        EXPECT_EQ(a.i32, (std::vector<std::int32_t>{0, 1}));
      } else if (a.name == "contact_state") {
        EXPECT_EQ(a.f64, f.extra);
      }
    }
    EXPECT_EQ(cell_names, (std::vector<std::string>{"element", "block", "body", "stress",
                                                     "contact_state"}));
  }
}

// Arrays larger than one 32 KiB zlib block (a real frame's) come back whole, in order.
TEST(VtuReader, MultiBlockArraysRoundTrip) {
  PolygonGrid g;
  const int n = 5000;  // 15000 doubles = 120 kB of points: 4 blocks, the last one partial
  for (int i = 0; i < n; ++i) g.add_point(0.001 * i, std::sin(0.37 * i));
  for (int i = 0; i + 2 < n; i += 3) g.add_cell({i, i + 1, i + 2});
  std::vector<double> d(3 * static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = std::cos(1.1 * static_cast<double>(i)) * 1e-3;
  g.add_point_array("displacement", 3, d);
  const PolygonGrid back = parse_vtu(vtu_compressed(g), "test.vtu");
  EXPECT_EQ(back.points, g.points);
  EXPECT_EQ(back.connectivity, g.connectivity);
  EXPECT_EQ(back.offsets, g.offsets);
  ASSERT_EQ(back.point_data.size(), 1u);
  EXPECT_EQ(back.point_data[0].f64, d);
}

// Damaged frames are InputErrors naming the file and a byte offset, never a crash or a short array.
TEST(VtuReader, DamagedFramesAreInputErrors) {
  PolygonGrid g;
  for (int i = 0; i < 300; ++i) g.add_point(i, 2.0 * i);
  for (int i = 0; i + 2 < 300; i += 3) g.add_cell({i, i + 1, i + 2});
  const std::string good = vtu_compressed(g);
  ASSERT_NO_THROW(parse_vtu(good, "f.vtu"));
  auto fails = [](const std::string& s, const std::string& part) {
    try {
      parse_vtu(s, "f.vtu");
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "f.vtu");
      EXPECT_EQ(e.where().rfind("byte ", 0), 0u) << e.what();
      EXPECT_TRUE(contains(e.what(), part)) << e.what();
      return;
    }
    ADD_FAILURE() << "no InputError for \"" << part << "\" (" << s.size() << " bytes)";
  };
  fails(good.substr(0, good.size() - 200), "");                    // truncated
  std::string flipped = good;
  const std::size_t last_byte = good.rfind("\n  </AppendedData>") - 1;  // of the last stream
  flipped[last_byte] = static_cast<char>(flipped[last_byte] ^ 0x5a);
  fails(flipped, "does not inflate");                               // a corrupt zlib stream
  std::string other = good;
  other.replace(other.find("vtkZLibDataCompressor"), 21, "vtkLZ4DataCompressor!");
  fails(other, "compressor");
  fails("<html></html>", "VTKFile");
}


// Any damage — a byte changed, a stretch cut out, the file cut short — is an InputError or a
// grid that passes check_grid, never a crash, another exception or a huge allocation.
TEST(VtuReader, RandomDamageIsOnlyEverAnInputError) {
  PolygonGrid g;
  for (int i = 0; i < 400; ++i) g.add_point(0.5 * i, std::cos(0.1 * i));
  for (int i = 0; i + 3 < 400; i += 4) g.add_cell({i, i + 1, i + 2, i + 3});
  std::vector<double> d(1200, 0.25);
  g.add_point_array("displacement", 3, d);
  for (const std::string& good : {vtu_compressed(g), vtu_text(g)}) {
    std::uint64_t x = 0x9e3779b97f4a7c15ull;  // fixed seed: the same cases every run
    auto next = [&x]() {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;
      return x;
    };
    int errors = 0;
    for (int trial = 0; trial < 1500; ++trial) {
      std::string bad = good;
      const std::size_t at = next() % bad.size();
      switch (trial % 3) {
        case 0: bad[at] = static_cast<char>(next()); break;
        case 1: bad.erase(at, 1 + next() % 16); break;
        default: bad.resize(at); break;
      }
      try {
        parse_vtu(bad, "f.vtu");
      } catch (const InputError&) {
        ++errors;
      } catch (const std::exception& e) {
        ADD_FAILURE() << "trial " << trial << ": " << e.what();
      }
    }
    EXPECT_GT(errors, 500);  // most damage is seen (a changed digit in ASCII may pass)
  }
}

// contacts.csv.gz (gzip_text.h): the same text back, same input same bytes, damage detected.
TEST(GzipText, RoundTripAndDamage) {
  std::string text = "step,time,contact,x,y\n";
  for (int i = 0; i < 5000; ++i) text += std::to_string(i) + ",0.001," + std::to_string(i % 7) + ",1.5,-2.25\n";
  const std::string gz = gzip_compress(text);
  EXPECT_TRUE(is_gzip(gz));
  EXPECT_FALSE(is_gzip(text));
  EXPECT_LT(gz.size(), text.size() / 3);
  EXPECT_EQ(gzip_compress(text), gz) << "deterministic";
  EXPECT_EQ(gzip_decompress(gz, "c.csv.gz"), text);
  EXPECT_THROW(gzip_decompress(gz.substr(0, gz.size() / 2), "c.csv.gz"), InputError);
  std::string bad = gz;
  bad[bad.size() - 6] = static_cast<char>(bad[bad.size() - 6] ^ 0x40);  // in the CRC-32
  try {
    gzip_decompress(bad, "c.csv.gz");
    ADD_FAILURE() << "a wrong CRC was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "c.csv.gz");
  }
}

}  // namespace
}  // namespace nmm::solve
