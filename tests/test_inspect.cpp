// Tests of the mesh report (summary, JSON), the SVG and VTK writers and the nmm-inspect
// command line, on a mesh built by hand so every expected number is known exactly.
//
// The mesh: a unit square body cut by one joint along y = 0.5 into two blocks.
//
//   3 (0,1) +-----------+ 2 (1,1)        T0 = (0,1,2), T1 = (0,2,3), both CCW
//           | E3     /  |                E0 = T0 below the joint, E1 = T0 above (area .375/.125)
//   joint  -+------/----+-               E2 = T1 below the joint, E3 = T1 above (area .125/.375)
//           | E2 /  E0  |                each node's star is cut by the joint into two physical
//   0 (0,0) +/----------+ 1 (1,0)        covers: PC 2n below, PC 2n+1 above, 8 in all
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/mesh.h"
#include "common/mesh_file.h"
#include "common/mesh_report.h"
#include "common/scene.h"
#include "common/svg_writer.h"
#include "common/vtk_writer.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;
using nmm::test::TempDir;

namespace {

// Two materials so that the body's material index (1, "rock", sorted by name) differs from 0.
const char* const kSceneText = R"({
  // one body, one joint right across it
  "name": "split-square",
  "materials": {
    "granite": { "density": 2700, "young": 5e10, "poisson": 0.2 },
    "rock": { "density": 2650, "young": 1e10, "poisson": 0.25 }
  },
  "joint_sets": {
    "bedding": { "friction_deg": 20, "cohesion": 0, "tensile_strength": 0,
                 "normal": { "model": "constant", "kn": 5e11 },
                 "shear": { "model": "constant", "ks": 2e11 } }
  },
  "bodies": [ { "material": "rock", "outer": [[0,0],[1,0],[1,1],[0,1]] } ],
  "joints": [ { "set": "bedding", "points": [[-0.2,0.5],[1.2,0.5]] } ],
  "mesh": { "size": 1 }
})";

struct LoopEdge {
  double x, y;
  std::uint8_t origin;
  std::int32_t joint;
};

nmm::Mesh split_square() {
  using nmm::kEdgeBoundary;
  using nmm::kEdgeJoint;
  using nmm::kEdgeMesh;
  const std::uint8_t mb = kEdgeMesh | kEdgeBoundary;
  nmm::Mesh m;
  m.mesh_size = 1;
  m.node_xy = {0, 0, 1, 0, 1, 1, 0, 1};
  m.triangle_nodes = {0, 1, 2, 0, 2, 3};
  m.cover_node = {0, 0, 1, 1, 2, 2, 3, 3};
  m.cover_body.assign(8, 0);
  m.element_triangle = {0, 0, 1, 1};
  m.element_body = {0, 0, 0, 0};
  m.element_block = {0, 1, 0, 1};
  m.element_covers = {0, 2, 4, 1, 3, 5, 0, 4, 6, 1, 5, 7};
  const std::vector<std::vector<LoopEdge>> loops = {
      {{0, 0, mb, -1}, {1, 0, mb, -1}, {1, 0.5, kEdgeJoint, 0}, {0.5, 0.5, kEdgeMesh, -1}},
      {{0.5, 0.5, kEdgeJoint, 0}, {1, 0.5, mb, -1}, {1, 1, kEdgeMesh, -1}},
      {{0, 0, kEdgeMesh, -1}, {0.5, 0.5, kEdgeJoint, 0}, {0, 0.5, mb, -1}},
      {{0, 0.5, kEdgeJoint, 0}, {0.5, 0.5, kEdgeMesh, -1}, {1, 1, mb, -1}, {0, 1, mb, -1}}};
  const std::vector<std::int32_t> opposite = {1, 0, 3, 2};  // element across the joint
  m.element_loop_offset = {0};
  for (std::size_t e = 0; e < loops.size(); ++e) {
    for (const LoopEdge& v : loops[e]) {
      const auto index = static_cast<std::int32_t>(m.loop_edge_origin.size());
      m.loop_xy.push_back(v.x);
      m.loop_xy.push_back(v.y);
      m.loop_edge_origin.push_back(v.origin);
      m.loop_edge_joint.push_back(v.joint);
      if (v.origin & (kEdgeJoint | kEdgeBoundary)) {
        m.contact_edge.push_back(index);
        m.contact_edge_element.push_back(static_cast<std::int32_t>(e));
        m.contact_edge_opposite.push_back(v.origin & kEdgeJoint ? opposite[e] : -1);
      }
    }
    m.element_loop_offset.push_back(static_cast<std::int32_t>(m.loop_edge_origin.size()));
  }
  m.block_body = {0, 0};
  m.tool_version = "test";
  m.scene_file = "split-square.json";
  m.scene_text = kSceneText;
  m.scene_sha256 = nmm::sha256(m.scene_text);
  return m;
}

// The same mesh scaled by `s` (geometry only; the embedded scene is left as it is).
nmm::Mesh scaled(nmm::Mesh m, double s) {
  for (double& v : m.node_xy) v *= s;
  for (double& v : m.loop_xy) v *= s;
  m.mesh_size *= s;
  return m;
}

double signed_area(const nlohmann::json& poly) {
  double twice = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto& a = poly[i];
    const auto& b = poly[(i + 1) % poly.size()];
    twice += a[0].get<double>() * b[1].get<double>() - b[0].get<double>() * a[1].get<double>();
  }
  return 0.5 * twice;
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + what.size())) ++n;
  return n;
}

// A minimal well-formedness check: every start tag is closed in order (no attribute may contain
// '>', which holds for our writers).
bool xml_balanced(const std::string& s, std::string* why) {
  std::vector<std::string> stack;
  std::size_t p = 0;
  while ((p = s.find('<', p)) != std::string::npos) {
    const std::size_t q = s.find('>', p);
    if (q == std::string::npos) return *why = "unterminated tag", false;
    std::string tag = s.substr(p + 1, q - p - 1);
    p = q + 1;
    if (tag.empty()) return *why = "empty tag", false;
    if (tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (stack.empty() || stack.back() != name) return *why = "unbalanced </" + name + ">", false;
      stack.pop_back();
      continue;
    }
    if (tag.back() == '/') continue;
    stack.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
  }
  if (!stack.empty()) return *why = "unclosed <" + stack.back() + ">", false;
  return true;
}

std::string attribute(const std::string& s, const std::string& name) {
  const std::regex re(name + "=\"([^\"]*)\"");
  std::smatch m;
  if (!std::regex_search(s, m, re)) return "";
  return m[1];
}

// The numbers inside <DataArray ... Name="name" ...> ... </DataArray>.
std::vector<double> data_array(const std::string& vtu, const std::string& name) {
  const std::size_t p = vtu.find("Name=\"" + name + "\"");
  if (p == std::string::npos) return {};
  const std::size_t b = vtu.find('>', p) + 1;
  const std::size_t e = vtu.find("</DataArray>", b);
  std::istringstream in(vtu.substr(b, e - b));
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(InspectMesh, HandBuiltMeshIsValid) {
  const nmm::Mesh m = split_square();
  EXPECT_NO_THROW(nmm::validate_mesh(m, "split-square"));
  EXPECT_DOUBLE_EQ(nmm::total_area(m), 1.0);
}

TEST(InspectReport, JsonKeysCountsAndArea) {
  const nmm::Mesh m = split_square();
  const nlohmann::json j = nmm::mesh_report_json(m, false);
  EXPECT_EQ(j.at("nodes"), 4);
  EXPECT_EQ(j.at("triangles"), 2);
  EXPECT_EQ(j.at("mathematical_covers"), 4);
  EXPECT_EQ(j.at("physical_covers"), 8);
  EXPECT_EQ(j.at("manifold_elements"), 4);
  EXPECT_EQ(j.at("blocks"), 2);
  EXPECT_DOUBLE_EQ(j.at("area").get<double>(), 1.0);
  EXPECT_EQ(j.at("bodies"), 1);
  EXPECT_EQ(j.at("joints"), 1);
  EXPECT_EQ(j.at("scene_name"), "split-square");
  EXPECT_EQ(j.at("scene_sha256"), nmm::to_hex(nmm::sha256(kSceneText)));
  EXPECT_EQ(j.at("format_version"), nmm::kMeshFormatVersion);
  EXPECT_DOUBLE_EQ(j.at("mesh_size").get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j.at("min_element_area").get<double>(), 0.125);
  EXPECT_DOUBLE_EQ(j.at("max_element_area").get<double>(), 0.375);
  EXPECT_DOUBLE_EQ(j.at("scene_area").get<double>(), 1.0);
  EXPECT_EQ(j.at("sliver_elements"), 0);
  EXPECT_EQ(j.at("contact_edges"), 10);
  EXPECT_EQ(j.at("contact_edges_paired"), 4);
  EXPECT_FALSE(j.contains("elements"));
  EXPECT_FALSE(j.contains("node_xy"));
}

TEST(InspectReport, SliverElementsCounted) {
  nmm::Mesh m = split_square();
  // Move the joint's crossing point (0.5, 0.5) to (1e-7, 1e-7): E0 and E2 shrink to slivers
  // (areas about 1e-7 and 5e-15, below 1e-6·h²). Only loop coordinates change; the report does
  // not re-derive topology.
  for (std::size_t v = 0; v < m.loop_vertex_count(); ++v)
    if (m.loop_xy[2 * v + 1] == 0.5) m.loop_xy[2 * v + 1] = 1e-7;
  for (std::size_t v = 0; v < m.loop_vertex_count(); ++v)
    if (m.loop_xy[2 * v] == 0.5) m.loop_xy[2 * v] = 1e-7;
  const nlohmann::json j = nmm::mesh_report_json(m, false);
  EXPECT_EQ(j.at("sliver_elements"), 2);
  EXPECT_NEAR(j.at("area").get<double>(), 1.0, 1e-12);
}

TEST(InspectReport, FullArraysAreConsistent) {
  const nmm::Mesh m = split_square();
  const nlohmann::json j = nmm::mesh_report_json(m, true);
  ASSERT_EQ(j.at("node_xy").size(), 4u);
  EXPECT_EQ(j.at("node_xy")[2], nlohmann::json::array({1.0, 1.0}));
  ASSERT_EQ(j.at("triangle_nodes").size(), 2u);
  EXPECT_EQ(j.at("triangle_nodes")[1], nlohmann::json::array({0, 2, 3}));
  ASSERT_EQ(j.at("physical_cover_node").size(), 8u);
  const auto& elements = j.at("elements");
  ASSERT_EQ(elements.size(), 4u);
  double sum = 0;
  for (const auto& el : elements) {
    const int t = el.at("triangle");
    ASSERT_GE(t, 0);
    ASSERT_LT(t, 2);
    const double a = signed_area(el.at("polygon"));
    EXPECT_GT(a, 0) << "element polygon must be counter-clockwise";
    EXPECT_DOUBLE_EQ(a, el.at("area").get<double>());
    sum += a;
    ASSERT_EQ(el.at("covers").size(), 3u);
    // Each cover lies on the triangle's node in the same position.
    for (int k = 0; k < 3; ++k) {
      const int pc = el.at("covers")[static_cast<std::size_t>(k)];
      EXPECT_EQ(j.at("physical_cover_node")[static_cast<std::size_t>(pc)],
                j.at("triangle_nodes")[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)]);
    }
    EXPECT_EQ(el.at("material"), "rock");
    EXPECT_GE(el.at("block").get<int>(), 0);
    EXPECT_LT(el.at("block").get<int>(), 2);
  }
  EXPECT_DOUBLE_EQ(sum, j.at("area").get<double>());
  EXPECT_EQ(elements[1].at("polygon"), nlohmann::json::parse("[[0.5,0.5],[1,0.5],[1,1]]"));
  EXPECT_EQ(elements[3].at("covers"), nlohmann::json::array({1, 5, 7}));
}

TEST(InspectReport, DoublesRoundTrip) {
  nmm::Mesh m = split_square();
  m.node_xy[2] = 0.1 + 0.2;  // 0.30000000000000004: needs all 17 digits
  const std::string text = nmm::mesh_report_json(m, true).dump();
  EXPECT_EQ(nlohmann::json::parse(text).at("node_xy")[1][0].get<double>(), 0.1 + 0.2);
}

TEST(InspectReport, SummaryText) {
  const nmm::Mesh m = split_square();
  const std::string s = nmm::mesh_summary_text(m);
  EXPECT_NE(s.find("split-square"), std::string::npos);
  EXPECT_NE(s.find("physical covers"), std::string::npos);
  EXPECT_NE(s.find(nmm::to_hex(m.scene_sha256)), std::string::npos);
  EXPECT_TRUE(std::regex_search(s, std::regex("manifold elements +4\n")));
  EXPECT_TRUE(std::regex_search(s, std::regex("mathematical covers +4\n")));
  EXPECT_TRUE(std::regex_search(s, std::regex("blocks +2\n")));
  EXPECT_TRUE(std::regex_search(s, std::regex("area +1 m²")));
  EXPECT_TRUE(std::regex_search(s, std::regex("sliver elements +0 ")));
}

TEST(InspectReport, CoverReport) {
  const nmm::Mesh m = split_square();
  const nlohmann::json c = nmm::cover_report_json(m, 4);  // node 2, below the joint
  EXPECT_EQ(c.at("node"), 2);
  EXPECT_EQ(c.at("elements"), nlohmann::json::array({0, 2}));
  EXPECT_DOUBLE_EQ(c.at("area").get<double>(), 0.5);
  EXPECT_THROW(nmm::cover_report_json(m, 8), nmm::InputError);
  EXPECT_THROW(nmm::cover_report_json(m, -1), nmm::InputError);
}

TEST(InspectReport, SceneNotMatchingMeshIsInputError) {
  nmm::Mesh m = split_square();
  m.element_body[2] = 1;  // the scene has one body only
  EXPECT_THROW(nmm::embedded_scene(m, "bad.nmm"), nmm::InputError);
}

TEST(InspectSvg, WellFormedOnePolygonPerElement) {
  const nmm::Mesh m = split_square();
  const nmm::SceneDef scene = nmm::embedded_scene(m, "t");
  const std::string svg = nmm::mesh_svg(m, &scene, -1);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  std::string why;
  EXPECT_TRUE(xml_balanced(svg, &why)) << why;
  EXPECT_EQ(count(svg, "<polygon "), 4u);
  EXPECT_EQ(count(svg, nmm::kSvgHighlightColour), 0u);
  EXPECT_NE(svg.find("split-square"), std::string::npos);
  EXPECT_NE(svg.find(nmm::block_colour(0)), std::string::npos);
  EXPECT_NE(svg.find(nmm::block_colour(1)), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);  // the scene joint
  // Deterministic.
  EXPECT_EQ(svg, nmm::mesh_svg(m, &scene, -1));
}

TEST(InspectSvg, HighlightedCover) {
  const nmm::Mesh m = split_square();
  const nmm::SceneDef scene = nmm::embedded_scene(m, "t");
  const std::string svg = nmm::mesh_svg(m, &scene, 7);
  std::string why;
  EXPECT_TRUE(xml_balanced(svg, &why)) << why;
  EXPECT_EQ(count(svg, "<polygon "), 4u);
  // Cover 7 (node 3, above the joint) covers element 3 only.
  EXPECT_EQ(count(svg, std::string("<polygon points=\"0,-0.5 0.5,-0.5 1,-1 0,-1\" fill=\"") +
                           nmm::kSvgHighlightColour),
            1u);
  EXPECT_NE(svg.find("<circle cx=\"0\" cy=\"-1\""), std::string::npos);
  EXPECT_THROW(nmm::mesh_svg(m, &scene, 8), nmm::InputError);
}

TEST(InspectSvg, YFlippedAndFitted) {
  nmm::SvgWriter w;
  nmm::SvgStyle st;
  st.fill = "#123456";
  w.polygon({{0, 0}, {10, 0}, {10, 2}}, st);
  const std::string svg = w.str(0.1, 500);
  EXPECT_NE(svg.find("points=\"0,0 10,0 10,-2\""), std::string::npos);
  // Box x 0..10, y 0..2, margin 1: x from -1, SVG y from -3, 12 wide, 4 high.
  EXPECT_EQ(attribute(svg, "viewBox"), "-1 -3 12 4");
  EXPECT_EQ(attribute(svg, "width"), "500");
  EXPECT_EQ(attribute(svg, "height"), "167");
}

TEST(InspectSvg, StrokesScaleWithTheModel) {
  // The same mesh at 1 m and at 100 m must give the same picture up to scale.
  auto boundary_width_share = [](const nmm::Mesh& mesh) {
    const std::string svg = nmm::mesh_svg(mesh, nullptr, -1);
    std::smatch m;
    EXPECT_TRUE(
        std::regex_search(svg, m, std::regex("stroke=\"#000000\" stroke-width=\"([^\"]+)\"")));
    const std::string vb = attribute(svg, "viewBox");
    std::istringstream in(vb);
    double x, y, w;
    in >> x >> y >> w;
    return std::stod(m[1]) / w;
  };
  const nmm::Mesh m = split_square();
  const double a = boundary_width_share(m);
  const double b = boundary_width_share(scaled(m, 100));
  EXPECT_GT(a, 0);
  EXPECT_NEAR(a / b, 1.0, 1e-3);
}

TEST(InspectVtk, VtuParsesBack) {
  const nmm::Mesh m = split_square();
  const std::string vtu = nmm::vtu_text(nmm::mesh_to_grid(m));
  std::string why;
  EXPECT_TRUE(xml_balanced(vtu, &why)) << why;
  EXPECT_EQ(attribute(vtu, "NumberOfPoints"), "14");
  EXPECT_EQ(attribute(vtu, "NumberOfCells"), "4");
  const std::vector<double> conn = data_array(vtu, "connectivity");
  const std::vector<double> offs = data_array(vtu, "offsets");
  const std::vector<double> types = data_array(vtu, "types");
  ASSERT_EQ(offs.size(), 4u);
  EXPECT_EQ(offs.back(), static_cast<double>(conn.size()));
  EXPECT_EQ(offs, (std::vector<double>{4, 7, 10, 14}));
  EXPECT_EQ(types, (std::vector<double>(4, 7.0)));
  EXPECT_EQ(data_array(vtu, "Points").size(), 3u * 14u);
  EXPECT_EQ(data_array(vtu, "area"), (std::vector<double>{0.375, 0.125, 0.125, 0.375}));
  EXPECT_EQ(data_array(vtu, "block"), (std::vector<double>{0, 1, 0, 1}));
  EXPECT_EQ(data_array(vtu, "covers").size(), 12u);
  for (const char* name : {"element", "triangle", "body"})
    EXPECT_EQ(data_array(vtu, name).size(), 4u) << name;
}

TEST(InspectVtk, LegacyHeaderAndCells) {
  const nmm::Mesh m = split_square();
  const std::string vtk = nmm::legacy_vtk_text(nmm::mesh_to_grid(m), "split square");
  std::istringstream in(vtk);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_GT(lines.size(), 5u);
  EXPECT_EQ(lines[0], "# vtk DataFile Version 3.0");
  EXPECT_EQ(lines[1], "split square");
  EXPECT_EQ(lines[2], "ASCII");
  EXPECT_EQ(lines[3], "DATASET UNSTRUCTURED_GRID");
  EXPECT_EQ(lines[4], "POINTS 14 double");
  EXPECT_NE(vtk.find("\nCELLS 4 18\n4 0 1 2 3\n3 4 5 6\n"), std::string::npos);
  EXPECT_NE(vtk.find("\nCELL_TYPES 4\n7\n7\n7\n7\n"), std::string::npos);
  EXPECT_NE(vtk.find("\nCELL_DATA 4\n"), std::string::npos);
  EXPECT_NE(vtk.find("\nFIELD FieldData 6\nelement 1 4 int\n0 1 2 3\n"), std::string::npos);
  EXPECT_NE(vtk.find("\narea 1 4 double\n0.375 0.125 0.125 0.375\n"), std::string::npos);
  EXPECT_NE(vtk.find("\ncovers 3 4 int\n0 2 4 1 3 5 0 4 6 1 5 7\n"), std::string::npos);
  EXPECT_EQ(vtk.find("POINT_DATA"), std::string::npos);
}

TEST(InspectVtk, SolverStyleGridWithPointVectors) {
  // What the solver's frames need: per-vertex displacement (3 components) and cell stress.
  nmm::PolygonGrid g;
  const auto a = g.add_point(0, 0), b = g.add_point(1, 0), c = g.add_point(0, 1);
  g.add_cell({a, b, c});
  g.add_point_array("displacement", 3, std::vector<double>{0, 0, 0, 1e-3, 0, 0, 0, -2e-3, 0});
  g.add_cell_array("stress", 3, std::vector<double>{1e6, -2e6, 3.5e5});
  g.add_cell_array("weird name", 5, std::vector<double>{1, 2, 3, 4, 5});
  const std::string vtu = nmm::vtu_text(g);
  std::string why;
  EXPECT_TRUE(xml_balanced(vtu, &why)) << why;
  EXPECT_NE(vtu.find("<PointData>"), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"displacement\" NumberOfComponents=\"3\""), std::string::npos);
  EXPECT_EQ(data_array(vtu, "displacement")[3], 1e-3);
  const std::string vtk = nmm::legacy_vtk_text(g, "frame");
  EXPECT_NE(vtk.find("\nPOINT_DATA 3\nFIELD FieldData 1\ndisplacement 3 3 double\n"),
            std::string::npos);
  EXPECT_NE(vtk.find("\nCELL_DATA 1\nFIELD FieldData 2\nstress 3 1 double\n"), std::string::npos);
  EXPECT_NE(vtk.find("\nweird_name 5 1 double\n1 2 3 4 5\n"), std::string::npos);

  g.add_cell_array("short", 1, std::vector<double>{1, 2});  // 2 values for 1 cell
  EXPECT_THROW(nmm::vtu_text(g), std::logic_error);
}

TEST(InspectFiles, AtomicWrite) {
  TempDir dir;
  const fs::path out = dir.path() / "mesh.vtu";
  nmm::write_vtk_by_extension(nmm::mesh_to_grid(split_square()), out.string());
  EXPECT_EQ(read_file(out).rfind("<?xml", 0), 0u);
  const fs::path legacy = dir.path() / "mesh.vtk";
  nmm::write_vtk_by_extension(nmm::mesh_to_grid(split_square()), legacy.string());
  EXPECT_EQ(read_file(legacy).rfind("# vtk DataFile", 0), 0u);
  const fs::path bad = dir.path() / "no-such-dir" / "x.svg";
  EXPECT_THROW(nmm::write_mesh_svg(split_square(), nullptr, -1, bad.string()), nmm::InputError);
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    ++files;
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  }
  EXPECT_EQ(files, 2u);
}

// ---- the executable ------------------------------------------------------------------------
namespace {

struct RunResult {
  int status = -1;
  std::string out, err;
};

// nmm-inspect is built into the same folder as this test (CMAKE_RUNTIME_OUTPUT_DIRECTORY =
// <build>/bin); the per-folder layout (<build>/preprocess/) is the fallback.
fs::path inspect_binary() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const fs::path here = self.parent_path() / "nmm-inspect";
  if (fs::exists(here)) return here;
  return self.parent_path().parent_path() / "preprocess" / "nmm-inspect";
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

RunResult run_inspect(const TempDir& dir, const std::string& args) {
  const fs::path out = dir.path() / "stdout.txt", err = dir.path() / "stderr.txt";
  const std::string cmd = quote(inspect_binary().string()) + " " + args + " >" +
                          quote(out.string()) + " 2>" + quote(err.string());
  const int raw = std::system(cmd.c_str());
  RunResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

class InspectCli : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(inspect_binary())) GTEST_SKIP() << "nmm-inspect not built next to the test";
    mesh_ = (dir_.path() / "square.nmm").string();
    nmm::write_mesh_file(split_square(), mesh_);
  }
  TempDir dir_;
  std::string mesh_;
};

std::size_t lines(const std::string& s) {
  return count(s, "\n");
}

}  // namespace

TEST_F(InspectCli, SummaryByDefault) {
  const RunResult r = run_inspect(dir_, quote(mesh_));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("split-square"), std::string::npos);
  EXPECT_TRUE(r.err.empty());
}

TEST_F(InspectCli, JsonFullWithAllOutputs) {
  const fs::path svg = dir_.path() / "pic.svg", vtu = dir_.path() / "m.vtu";
  const RunResult r = run_inspect(dir_, quote(mesh_) + " --json --full --cover 1 --svg " +
                                            quote(svg.string()) + " --vtk " + quote(vtu.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("manifold_elements"), 4);
  EXPECT_EQ(j.at("elements").size(), 4u);
  EXPECT_EQ(j.at("cover").at("elements"), nlohmann::json::array({1, 3}));
  EXPECT_NE(read_file(svg).find(nmm::kSvgHighlightColour), std::string::npos);
  const std::string v = read_file(vtu);
  EXPECT_EQ(attribute(v, "NumberOfCells"), "4");
  EXPECT_EQ(data_array(v, "in_cover_1"), (std::vector<double>{0, 1, 0, 1}));
  for (const auto& entry : fs::directory_iterator(dir_.path()))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
}

TEST_F(InspectCli, BadInputIsOneLineAndStatus2) {
  const fs::path svg = dir_.path() / "never.svg";
  struct Case {
    std::string args, expect;
  };
  const std::string garbage = (dir_.path() / "garbage.nmm").string();
  std::ofstream(garbage) << "this is not a mesh file";
  const std::vector<Case> cases = {
      {quote(mesh_) + " --full", "--json"},
      {quote(mesh_) + " --cover 8 --svg " + quote(svg.string()), "--cover"},
      {quote(mesh_) + " --cover -1", "--cover"},
      {quote(mesh_) + " --cover x", "command line"},
      {quote(mesh_) + " --no-such-option", "command line"},
      {"", "command line"},
      {quote((dir_.path() / "missing.nmm").string()), "missing.nmm"},
      {quote(garbage), "garbage.nmm"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_inspect(dir_, c.args);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(lines(r.err), 1u) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << c.args;
  }
  EXPECT_FALSE(fs::exists(svg));
}

TEST_F(InspectCli, HelpExitsZero) {
  const RunResult r = run_inspect(dir_, "--help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("--svg"), std::string::npos);
}
