// The extension module nmm._nmm (pybind11): the library's scenes, meshes, solver and run files
// for the package nmm (python/nmm/__init__.py re-exports them; docs/python.md). Errors: the
// library's InputError becomes nmm.InputError (nmm.SceneError where it is about a scene), with
// the tools' one line as its text and file, where (a JSON path such as /joints/3/points/1) and
// message as attributes; RunError becomes nmm.RunError.
#include <pybind11/pybind11.h>

#include "nmm_version.h"
#include "python/binding.h"

namespace nmm::python {

py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(
      j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

std::string json_text(py::handle value) {
  return py::module_::import("json").attr("dumps")(value, py::arg("allow_nan") = false).cast<std::string>();
}

std::string path_of(py::handle path) { return py::module_::import("os").attr("fspath")(path).cast<std::string>(); }

std::vector<std::string> set_list(py::handle set) {
  std::vector<std::string> sets;
  if (set.is_none()) return sets;
  if (py::isinstance<py::dict>(set)) {
    for (const auto& [key, value] : set.cast<py::dict>())
      sets.push_back(py::str(key).cast<std::string>() + "=" + json_text(value));
    return sets;
  }
  if (py::isinstance<py::str>(set))
    throw py::type_error("set: a dict {PATH: VALUE} or a list of 'PATH=VALUE' strings, not one string");
  for (const py::handle item : set) sets.push_back(item.cast<std::string>());
  return sets;
}

namespace {

void raise(const char* name, const InputError& e) {
  const py::object cls = py::module_::import("nmm.errors").attr(name);
  const py::object err = cls(e.what(), e.file(), e.where(), e.message());
  PyErr_SetObject(cls.ptr(), err.ptr());
}

}  // namespace

}  // namespace nmm::python

PYBIND11_MODULE(_nmm, m) {
  using namespace nmm::python;
  m.doc() = "nmm's library: scenes, meshes, the solver and run files (use the package nmm)";
  m.attr("__version__") = NMM_VERSION;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneInputError& e) {
      raise("SceneError", e);
    } catch (const nmm::InputError& e) {
      raise("InputError", e);
    } catch (const nmm::RunError& e) {
      const py::object cls = py::module_::import("nmm.errors").attr("RunError");
      PyErr_SetObject(cls.ptr(), cls(e.what()).ptr());
    }
  });
  bind_mesh(m);
  bind_solver(m);
  bind_run_files(m);
}
