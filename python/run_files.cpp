// The files of a run folder read back as nmm-report reads them (report/run_report.h,
// report/result_redraw.h, common/vtu_reader.h), for nmm.read_run (python/nmm/run.py): CSVs
// (plain or gzip) as a column table, the frames listed in frames.pvd, a frame's .vtu (binary
// or text) as arrays.
#include <utility>

#include "common/vtu_reader.h"
#include "python/binding.h"
#include "report/result_picture.h"
#include "report/result_redraw.h"
#include "report/run_report.h"
#include "solver/output/output_writer.h"

namespace nmm::python {

namespace {

py::array grid_array(const GridArray& a, std::size_t tuples) {
  const auto n = static_cast<py::ssize_t>(tuples);
  std::vector<py::ssize_t> shape{n};
  if (a.components > 1) shape.push_back(a.components);
  return a.type == GridArray::Type::Float64 ? copy(a.f64, shape) : copy(a.i32, shape);
}

}  // namespace

void bind_run_files(py::module_& m) {
  m.def(
      "read_number_csv",
      [](const std::string& path) {
        report::NumberTable t;
        {
          py::gil_scoped_release release;
          t = report::read_number_csv(path);
        }
        const std::size_t columns = t.names.size();
        std::vector<double> values;
        values.reserve(t.rows.size() * columns);
        for (const auto& row : t.rows) {
          if (row.size() != columns)
            throw InputError(path, "", "a row of " + std::to_string(row.size()) + " values under a header of " +
                                           std::to_string(columns));
          values.insert(values.end(), row.begin(), row.end());
        }
        return py::make_tuple(t.names, copy(values, {static_cast<py::ssize_t>(t.rows.size()),
                                                     static_cast<py::ssize_t>(columns)}));
      },
      py::arg("path"), "(column names, array (rows, columns)) of a run's CSV, plain or gzip");
  m.def("list_run_frames", &report::list_run_frames, py::arg("dir"),
        "[(time s, step), ...] of the frames RUN/frames.pvd lists, in order");
  m.def("frame_file_name", &solve::frame_file_name, py::arg("step"),
        "the frame of a step, relative to the run folder ('frames/frame_000010.vtu')");
  m.def(
      "read_vtu",
      [](const std::string& path) {
        PolygonGrid g;
        {
          py::gil_scoped_release release;
          g = read_vtu(path);
        }
        std::vector<double> xy;
        for (std::size_t p = 0; p < g.point_count(); ++p) xy.insert(xy.end(), {g.points[3 * p], g.points[3 * p + 1]});
        py::dict point_data, cell_data;
        for (const GridArray& a : g.point_data) point_data[py::str(a.name)] = grid_array(a, g.point_count());
        for (const GridArray& a : g.cell_data) cell_data[py::str(a.name)] = grid_array(a, g.cell_count());
        py::dict d;
        d["points"] = copy(xy, {static_cast<py::ssize_t>(g.point_count()), 2});
        d["offsets"] = copy(g.offsets, {static_cast<py::ssize_t>(g.offsets.size())});
        d["connectivity"] = copy(g.connectivity, {static_cast<py::ssize_t>(g.connectivity.size())});
        d["point_data"] = point_data;
        d["cell_data"] = cell_data;
        return d;
      },
      py::arg("path"),
      "a frame (.vtu) as arrays: points (n, 2) m, offsets and connectivity (each cell's polygon), "
      "point_data and cell_data {name: array}");

  // The rules of result.svg (result_picture.h), for nmm.plot's pictures.
  m.def("automatic_exaggeration", &report::automatic_exaggeration, py::arg("max_displacement"),
        py::arg("model_size"), "the factor result.svg draws displacements with when none is asked for");
  m.def("weighted_quantile", &report::weighted_quantile, py::arg("values"), py::arg("weights"), py::arg("q"),
        "the weighted quantile q of values (result.svg's colour bar: area-weighted, 1st to 99th)");
}

}  // namespace nmm::python
