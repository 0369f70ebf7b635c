// What the binding sources of the Python module _nmm share (module.cpp, mesh_binding.cpp,
// solver_binding.cpp, run_files.cpp): NumPy arrays over the library's plain arrays, the JSON the
// library speaks as Python objects, and the errors of the tools as Python exceptions.
//
// The module adds no physics and no logic of the tools: every call goes to the same library
// functions nmm-preprocess, nmm-inspect and nmm-solve call (docs/python.md).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/mesh.h"
#include "preprocess/preprocess_scene.h"

namespace nmm::python {

namespace py = pybind11;

/// An InputError about a scene (a JSON path in it): raised in Python as nmm.SceneError, the
/// other InputErrors as nmm.InputError (errors.py).
class SceneInputError : public InputError {
 public:
  explicit SceneInputError(const InputError& e) : InputError(e) {}
};

/// A read-only NumPy array over `data` (C order, `shape`), kept alive by `base` (the Python
/// object that owns the data): no copy.
template <class T>
py::array view(const T* data, std::vector<py::ssize_t> shape, py::handle base) {
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = sizeof(T);
  for (std::size_t k = shape.size(); k-- > 0;) {
    strides[k] = stride;
    stride *= shape[k];
  }
  py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), data, base);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

/// A NumPy array of its own (a copy) of `values`, shaped `shape`.
template <class T>
py::array copy(const std::vector<T>& values, std::vector<py::ssize_t> shape) {
  py::array_t<T> a(std::move(shape));
  std::copy(values.begin(), values.end(), a.mutable_data());
  return std::move(a);
}

/// JSON as Python objects (dict, list, str, float, int, bool, None) and back.
py::object to_python(const nlohmann::json& j);
std::string json_text(py::handle value);

/// A file name from a str or os.PathLike.
std::string path_of(py::handle path);

/// The `set` argument as the tools' --set list: a dict {PATH: VALUE} (each VALUE written as
/// JSON), or a list of "PATH=VALUE" strings; None: no settings.
std::vector<std::string> set_list(py::handle set);

/// Runs `f`, turning an InputError into a SceneInputError.
template <class F>
auto as_scene_error(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const SceneInputError&) {
    throw;
  } catch (const InputError& e) {
    throw SceneInputError(e);
  }
}

/// A mesh as Python holds it (nmm.Mesh): the library's mesh, shared with the solvers on it.
struct PyMesh {
  std::shared_ptr<const Mesh> mesh;
  std::string path;  ///< the mesh file it was loaded from or saved to; "" in memory only
  std::string name;  ///< names it in errors: the path, or "mesh of SCENE"
};

/// A scene as Python holds it (nmm.Scene): prepared as nmm-preprocess prepares it.
struct PyScene {
  pre::PreparedScene prepared;
};

void bind_mesh(py::module_& m);
void bind_solver(py::module_& m);
void bind_run_files(py::module_& m);

}  // namespace nmm::python
