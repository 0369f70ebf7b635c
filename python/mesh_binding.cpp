// nmm.Scene, nmm.preprocess and nmm.Mesh: a scene prepared and cut as nmm-preprocess does it
// (preprocess/preprocess_scene.h), the mesh file read and written as every tool does
// (common/mesh_file.h), and what nmm-inspect reports (common/mesh_report.h), with the mesh's
// arrays as read-only NumPy views (no copy).
#include <utility>

#include "common/mesh_file.h"
#include "common/whole_file.h"
#include "common/mesh_report.h"
#include "common/scene.h"
#include "python/binding.h"

namespace nmm::python {

namespace {

/// Names a scene given as a dict in errors, as a file name names a scene file.
constexpr const char* kDictScene = "<scene dict>";

PyScene make_scene(py::handle source, py::handle set) {
  std::string text, file;
  if (py::isinstance<py::dict>(source)) {
    text = json_text(source) + "\n";
    file = kDictScene;
  } else {
    file = path_of(source);
    text = as_scene_error([&] { return read_text_file(file); });
  }
  const std::vector<std::string> sets = set_list(set);
  py::gil_scoped_release release;  // a generated network and the geometry checks take a while
  return PyScene{as_scene_error([&] { return pre::prepare_scene(std::move(text), file, sets); })};
}

py::array ring_array(const std::vector<Vec2>& ring) {
  std::vector<double> xy;
  for (const Vec2& p : ring) xy.insert(xy.end(), {p.x, p.y});
  return copy(xy, {static_cast<py::ssize_t>(ring.size()), 2});
}

template <class Defs>
py::list names(const Defs& defs) {
  py::list out;
  for (const auto& d : defs) out.append(d.name);
  return out;
}

/// A mesh's array as a read-only view shaped (n) or (n, columns), kept alive by the mesh.
template <class T>
py::array mesh_view(py::object self, const std::vector<T>& (*field)(const Mesh&), py::ssize_t columns = 0) {
  const Mesh& mesh = *self.cast<PyMesh&>().mesh;
  const std::vector<T>& v = field(mesh);
  const auto n = static_cast<py::ssize_t>(v.size());
  if (columns == 0) return view(v.data(), {n}, self);
  return view(v.data(), {n / columns, columns}, self);
}

}  // namespace

void bind_mesh(py::module_& m) {
  py::class_<PyScene>(m, "Scene", R"(A scene, checked as nmm-preprocess checks it.

Scene(source, set=None): `source` is a scene file's path or the scene as a dict (JSON's
objects); `set` edits it first, as nmm-preprocess --set does: {PATH: VALUE} or
["PATH=VALUE", ...] (e.g. {"joint_sets.cross.generate.seed": 3}). Generated joint sets are
generated here. A bad scene raises nmm.SceneError with the tools' one line (str(e)) and its
.file, .where (the JSON path, e.g. /joints/3/points/1) and .message.)")
      .def(py::init(&make_scene), py::arg("source"), py::arg("set") = py::none())
      .def_property_readonly("file", [](const PyScene& s) { return s.prepared.file; },
                             "the scene file as given, or '<scene dict>'")
      .def_property_readonly("name", [](const PyScene& s) { return s.prepared.scene.name; },
                             "the scene's 'name' ('' if it has none)")
      .def_property_readonly("text", [](const PyScene& s) { return s.prepared.text; },
                             "the scene a mesh of it embeds (JSON text)")
      .def("to_dict", [](const PyScene& s) { return to_python(parse_json_text(s.prepared.text, s.prepared.name)); },
           "the scene as a dict (generated joints listed)")
      .def_property_readonly("mesh_size", [](const PyScene& s) { return s.prepared.scene.mesh_size; },
                             "m, the side of the mathematical triangles")
      .def_property_readonly("materials", [](const PyScene& s) { return names(s.prepared.scene.materials); },
                             "material names, in index order")
      .def_property_readonly("joint_sets", [](const PyScene& s) { return names(s.prepared.scene.joint_sets); },
                             "joint set names, in index order")
      .def_property_readonly(
          "joints",
          [](const PyScene& s) {
            py::list out;
            for (const JointDef& j : s.prepared.scene.joints) out.append(ring_array(j.points));
            return out;
          },
          "each joint's polyline, an array (points, 2) in m")
      .def_property_readonly(
          "joint_set",
          [](const PyScene& s) {
            std::vector<std::int32_t> set;
            for (const JointDef& j : s.prepared.scene.joints) set.push_back(j.set);
            return copy(set, {static_cast<py::ssize_t>(set.size())});
          },
          "each joint's set, an index into joint_sets")
      .def_property_readonly(
          "bodies",
          [](const PyScene& s) {
            py::list out;
            for (const BodyDef& b : s.prepared.scene.bodies) {
              py::list holes;
              for (const Ring& h : b.holes) holes.append(ring_array(h));
              out.append(py::dict(py::arg("material") = s.prepared.scene.materials[static_cast<std::size_t>(b.material)].name,
                                  py::arg("outer") = ring_array(b.outer), py::arg("holes") = holes));
            }
            return out;
          },
          "each body: {'material': name, 'outer': array (points, 2), 'holes': [arrays]}")
      .def(
          "warnings",
          [](const PyScene& s, bool strict_joints) {
            return as_scene_error([&] { return pre::scene_warnings(s.prepared, strict_joints); });
          },
          py::arg("strict_joints") = false,
          "what nmm-preprocess warns of, one line each (strict_joints: a stray joint raises)")
      .def("__repr__", [](const PyScene& s) {
        return "<nmm.Scene " + s.prepared.file + ": " + std::to_string(s.prepared.scene.bodies.size()) +
               " bodies, " + std::to_string(s.prepared.scene.joints.size()) + " joints, mesh size " +
               std::to_string(s.prepared.scene.mesh_size) + " m>";
      });

  m.def(
      "_cut",
      [](const PyScene& scene, bool strict_joints) {
        std::vector<std::string> warnings =
            as_scene_error([&] { return pre::scene_warnings(scene.prepared, strict_joints); });
        PyMesh mesh;
        {
          py::gil_scoped_release release;
          mesh.mesh = std::make_shared<const Mesh>(as_scene_error([&] { return pre::cut_scene(scene.prepared); }));
        }
        mesh.name = "mesh of " + scene.prepared.file;
        return py::make_tuple(std::move(mesh), warnings);
      },
      py::arg("scene"), py::arg("strict_joints") = false,
      "the mesh of a scene and the scene's warnings (nmm.preprocess warns with them)");

  py::class_<PyMesh>(m, "Mesh", R"(A mesh: the covers, manifold elements and blocks cut from a scene.

From nmm.preprocess(scene) or nmm.Mesh.load(path); mesh.save(path) writes the mesh file the
tools read. Arrays are read-only NumPy views of the mesh (no copy): nodes (n, 2) m,
triangles (t, 3), cover_node and cover_body (pc), element_triangle, element_body,
element_block (me), element_covers (me, 3), element_offsets (me + 1) into element_vertices
(v, 2) m (each element's polygon, counter-clockwise: element_polygon(e)), block_body (blocks).
cover(i), report() and summary() are what nmm-inspect --cover, --json and its summary show.)")
      .def_static(
          "load",
          [](const std::string& path) {
            PyMesh mesh;
            {
              py::gil_scoped_release release;
              mesh.mesh = std::make_shared<const Mesh>(read_mesh_file(path));
            }
            mesh.path = mesh.name = path;
            return mesh;
          },
          py::arg("path"), "reads a mesh file (.nmm), with every check the tools make")
      .def(
          "save",
          [](PyMesh& self, py::object path) {
            const std::string file = path_of(path);
            {
              py::gil_scoped_release release;
              write_mesh_file(*self.mesh, file);
            }
            if (self.path.empty()) self.path = self.name = file;
          },
          py::arg("path"), "writes the mesh file (atomically) that nmm-solve and nmm-inspect read")
      .def_property_readonly("path", [](const PyMesh& s) { return s.path.empty() ? py::object(py::none()) : py::str(s.path); },
                             "the mesh file it was loaded from or saved to, None if none")
      .def_property_readonly("name", [](const PyMesh& s) { return s.name; }, "names the mesh in errors")
      .def_property_readonly(
          "scene", [](const PyMesh& s) {
            const std::string name = s.name + " (embedded scene)";
            return PyScene{pre::PreparedScene{as_scene_error([&] { return embedded_scene(*s.mesh, s.name); }),
                                              s.mesh->scene_text, name, s.mesh->scene_file}};
          },
          "the scene the mesh embeds (nmm.Scene)")
      .def_property_readonly("mesh_size", [](const PyMesh& s) { return s.mesh->mesh_size; }, "m")
      .def_property_readonly("node_count", [](const PyMesh& s) { return s.mesh->node_count(); })
      .def_property_readonly("triangle_count", [](const PyMesh& s) { return s.mesh->triangle_count(); })
      .def_property_readonly("mathematical_cover_count", [](const PyMesh& s) { return s.mesh->mathematical_cover_count(); })
      .def_property_readonly("cover_count", [](const PyMesh& s) { return s.mesh->cover_count(); },
                             "physical covers")
      .def_property_readonly("element_count", [](const PyMesh& s) { return s.mesh->element_count(); },
                             "manifold elements")
      .def_property_readonly("block_count", [](const PyMesh& s) { return s.mesh->block_count(); })
      .def_property_readonly("vertex_count", [](const PyMesh& s) { return s.mesh->loop_vertex_count(); },
                             "element polygon vertices (all elements)")
      .def_property_readonly("area", [](const PyMesh& s) { return total_area(*s.mesh); }, "m², of all elements")
      .def_property_readonly("nodes", [](py::object self) {
        return mesh_view<double>(self, [](const Mesh& g) -> const std::vector<double>& { return g.node_xy; }, 2);
      }, "(n, 2) m, the mathematical mesh's nodes")
      .def_property_readonly("triangles", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.triangle_nodes; }, 3);
      }, "(t, 3), node indices, counter-clockwise")
      .def_property_readonly("cover_node", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.cover_node; });
      }, "(pc,), the node whose star each physical cover lies in")
      .def_property_readonly("cover_body", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.cover_body; });
      }, "(pc,), the body of each physical cover")
      .def_property_readonly("element_triangle", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.element_triangle; });
      }, "(me,), the triangle each manifold element lies in")
      .def_property_readonly("element_body", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.element_body; });
      }, "(me,), each element's body")
      .def_property_readonly("element_block", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.element_block; });
      }, "(me,), each element's block")
      .def_property_readonly("element_covers", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.element_covers; }, 3);
      }, "(me, 3), the physical cover of each of the triangle's nodes, in their order")
      .def_property_readonly("element_offsets", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.element_loop_offset; });
      }, "(me + 1,), element e's polygon is element_vertices[offsets[e]:offsets[e + 1]]")
      .def_property_readonly("element_vertices", [](py::object self) {
        return mesh_view<double>(self, [](const Mesh& g) -> const std::vector<double>& { return g.loop_xy; }, 2);
      }, "(v, 2) m, the elements' polygons, counter-clockwise, one after the other")
      .def_property_readonly("edge_joint", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.loop_edge_joint; });
      }, "(v,), the joint under the polygon edge from vertex v to the next, -1 if none")
      .def_property_readonly("block_body", [](py::object self) {
        return mesh_view<std::int32_t>(self, [](const Mesh& g) -> const std::vector<std::int32_t>& { return g.block_body; });
      }, "(blocks,), each block's body")
      .def(
          "element_polygon",
          [](py::object self, py::ssize_t e) {
            const Mesh& mesh = *self.cast<PyMesh&>().mesh;
            if (e < 0 || static_cast<std::size_t>(e) >= mesh.element_count())
              throw py::index_error("element " + std::to_string(e) + " does not exist (the mesh has " +
                                    std::to_string(mesh.element_count()) + " elements)");
            const std::int32_t a = mesh.element_loop_offset[static_cast<std::size_t>(e)];
            const std::int32_t b = mesh.element_loop_offset[static_cast<std::size_t>(e) + 1];
            return view(mesh.loop_xy.data() + 2 * a, {b - a, 2}, self);
          },
          py::arg("e"), "(k, 2) m, element e's polygon, counter-clockwise (a view)")
      .def(
          "element_areas",
          [](const PyMesh& s) {
            std::vector<double> a(s.mesh->element_count());
            for (std::size_t e = 0; e < a.size(); ++e) a[e] = element_area(*s.mesh, e);
            return copy(a, {static_cast<py::ssize_t>(a.size())});
          },
          "(me,) m², each element's area")
      .def(
          "cover",
          [](const PyMesh& s, long long i) {
            nlohmann::json j;
            try {
              j = cover_report_json(*s.mesh, i);
            } catch (const InputError& e) {
              throw py::index_error(e.message());
            }
            py::dict d;
            d["index"] = i;
            d["node"] = j["node"].get<long long>();
            d["node_xy"] = copy(j["node_xy"].get<std::vector<double>>(), {2});
            d["body"] = j["body"].get<long long>();
            const auto elements = j["elements"].get<std::vector<std::int64_t>>();
            d["elements"] = copy(elements, {static_cast<py::ssize_t>(elements.size())});
            d["area"] = j["area"].get<double>();
            return d;
          },
          py::arg("i"),
          "physical cover i as nmm-inspect --cover shows it: index, node, node_xy (m), body, "
          "elements (indices), area (m²); IndexError if there is none")
      .def(
          "report",
          [](const PyMesh& s, bool full) { return to_python(mesh_report_json(*s.mesh, full)); },
          py::arg("full") = false, "the dict nmm-inspect --json [--full] prints")
      .def("summary", [](const PyMesh& s) { return mesh_summary_text(*s.mesh); },
           "the text nmm-inspect prints")
      .def("__repr__", [](const PyMesh& s) {
        return "<nmm.Mesh " + s.name + ": " + std::to_string(s.mesh->cover_count()) + " physical covers, " +
               std::to_string(s.mesh->element_count()) + " manifold elements, " +
               std::to_string(s.mesh->block_count()) + " blocks>";
      });
}

}  // namespace nmm::python
