// nmm.Solver: a run of a mesh as nmm-solve makes it (solver/output/solve_run.h), stepped from
// Python: step(), run(steps), run_until(t), with the GIL released while it computes. The state
// is read as NumPy arrays (views of the run state where its layout allows, copies where a value
// is derived), the summary as the dict summary.json holds; outputs are written only to an
// output folder given (out=...), the same files nmm-solve writes.
//
// Ctrl-C: between steps the run asks Python for pending signals (PyErr_CheckSignals, in the
// main thread); a KeyboardInterrupt, like an exception from the progress callback, stops the run
// after the step under way, as SIGINT stops nmm-solve: the state stays consistent, the outputs
// are finished (history.csv, summary.json with status "interrupted", the checkpoint), and then
// the exception is raised.
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>

#include "report/run_pictures.h"
#include "solver/flow/flow_effect.h"
#include "solver/stepping/fracture_effect.h"
#include "solver/output/solve_run.h"
#include "python/binding.h"
#include "python/crack_arrays.h"

namespace nmm::python {

namespace {

using solve::SolveOptions;
using solve::SolveRun;

/// Names a merge patch given as a dict in errors, as a file name names a --config file.
constexpr const char* kDictConfig = "<config dict>";

class PySolver;

// After every accepted step: the progress callback, with the GIL.
class PythonProgress : public solve::StepObserver {
 public:
  explicit PythonProgress(PySolver& solver) : solver_(solver) {}
  void after_step(const solve::RunView&, std::int64_t, bool) override;

 private:
  PySolver& solver_;
};

class PySolver {
 public:
  PySolver(py::object mesh, py::handle set, py::handle config, py::handle restart, py::handle out, int threads,
           py::object progress, bool text_frames, int contacts_every, bool contacts_gzip)
      : mesh_obj_(std::move(mesh)), mesh_(mesh_obj_.cast<PyMesh&>().mesh), progress_fn_(py::none()), observer_(*this) {
    const PyMesh& m = mesh_obj_.cast<PyMesh&>();
    SolveOptions o;
    o.sets = set_list(set);
    if (py::isinstance<py::dict>(config)) {
      o.config_text = json_text(config);
      o.config_path = kDictConfig;
    } else if (!config.is_none()) {
      o.config_path = path_of(config);
    }
    if (!restart.is_none()) o.restart_path = path_of(restart);
    if (!out.is_none()) o.out_dir = path_of(out);
    o.threads = threads;
    o.frame_format = text_frames ? solve::FrameFormat::text : solve::FrameFormat::compressed;
    o.contacts_every = contacts_every;
    o.contacts_gzip = contacts_gzip;
    if (progress.is(py::bool_(true))) o.progress = solve::ProgressLine::choose(false);
    else if (!progress.is_none() && !progress.is(py::bool_(false))) progress_fn_ = std::move(progress);
    if (!o.out_dir.empty())
      o.inputs = as_scene_error([&] { return solve::run_inputs(m.path, o, "displacement", nullptr); });
    py::gil_scoped_release release;
    // The variants first, so that every mistake in them is a SceneError (they are a scene's).
    as_scene_error([&] {
      return o.config_text ? solve::make_run_scene(*mesh_, m.name, *o.config_text, o.config_path, o.sets)
                           : solve::make_run_scene(*mesh_, m.name, o.config_path, o.sets);
    });
    try {
      run_ = std::make_unique<SolveRun>(*mesh_, m.name, std::move(o));
    } catch (const InputError& e) {
      // A point of the scene outside every body, a support off the boundary: its JSON path.
      if (e.where().rfind('/', 0) == 0) throw SceneInputError(e);
      throw;  // the checkpoint, the output folder
    }
    run_->add(observer_);
    run_->set_stop_check([this] { return stop_check(); });
  }

  /// Steps as advance() does, with the GIL released; `finish`: then the outputs a finished run
  /// has (with an output folder). Raises what stopped the run from Python, after finishing.
  Outcome advance(py::handle self, double t_end, std::int64_t max_steps, bool finish) {
    if (busy_.exchange(true))
      throw py::value_error("this solver is stepping already (in another thread, or from its own callback)");
    struct Idle {
      std::atomic<bool>& busy;
      ~Idle() { busy = false; }
    } idle{busy_};
    stepping_thread_ = std::this_thread::get_id();
    self_ = self;
    pending_.reset();
    const py::object threading = py::module_::import("threading");
    check_signals_ = threading.attr("current_thread")().is(threading.attr("main_thread")());
    Outcome outcome;
    {
      py::gil_scoped_release release;
      outcome = run_->advance(t_end, max_steps);
      if (finish) run_->finish();
    }
    self_ = py::handle();
    if (pending_) {
      const py::error_already_set e = *pending_;
      pending_.reset();
      throw e;
    }
    return outcome;
  }

  /// The outputs a finished run has (with an output folder), and the summary.
  py::object flush() {
    if (busy_) throw py::value_error("this solver is stepping: flush() when step() or run() has returned");
    nlohmann::json summary;
    {
      py::gil_scoped_release release;
      summary = run_->options().out_dir.empty() ? run_->summary() : run_->finish();
    }
    return to_python(summary);
  }

  void pictures(const std::string& field_name, py::handle exaggerate) {
    if (run_->options().out_dir.empty())
      throw py::value_error("pictures are drawn into the output folder: make the Solver with out=DIR");
    report::PictureField field;
    if (!report::parse_picture_field(field_name, field))
      throw py::value_error("field: '" + field_name + "' is not one of displacement, sxx, syy, sxy, pressure");
    const double f = exaggerate.is_none() ? 0.0 : exaggerate.cast<double>();
    flush();
    py::gil_scoped_release release;
    report::write_run_pictures(run_->view(), run_->scene().scene, run_->outcome(), run_->options().out_dir, f, field);
  }

  /// The run, to read: from any thread while it rests, from its callback while it steps.
  const SolveRun& run() const {
    if (busy_ && std::this_thread::get_id() != stepping_thread_)
      throw py::value_error("this solver is stepping in another thread: read it when step() or run() has returned");
    return *run_;
  }
  py::object mesh() const { return mesh_obj_; }
  /// Numbers the tips crack_tips() reads, over its calls (crack_arrays.h).
  solve::CrackTipFinder& tip_finder() { return tip_finder_; }

  // Called on the stepping thread, between steps.
  bool stop_check() {
    if (pending_) return true;
    if (!check_signals_) return false;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) pending_ = std::make_unique<py::error_already_set>();
    return pending_ != nullptr;
  }
  void call_progress() {
    if (progress_fn_.is_none() || pending_) return;
    py::gil_scoped_acquire gil;
    try {
      progress_fn_(self_);
    } catch (py::error_already_set& e) {
      pending_ = std::make_unique<py::error_already_set>(std::move(e));
    }
  }

 private:
  py::object mesh_obj_;                    // the nmm.Mesh: keeps the mesh alive
  std::shared_ptr<const Mesh> mesh_;
  py::object progress_fn_;                 // None, or called with the solver after each step
  PythonProgress observer_;
  std::unique_ptr<SolveRun> run_;
  std::atomic<bool> busy_{false};
  std::thread::id stepping_thread_;        // the thread of the last advance()
  bool check_signals_ = false;             // stepping on the main thread: Ctrl-C is seen
  py::handle self_;                        // the Python solver, while it steps
  std::unique_ptr<py::error_already_set> pending_;  // what stops the run, raised after it
  solve::CrackTipFinder tip_finder_;       // crack_tips(): the tips' numbers over its calls
};

void PythonProgress::after_step(const solve::RunView&, std::int64_t, bool) { solver_.call_progress(); }

/// One of the run state's arrays shaped `shape`: a view (it is updated in place step after
/// step: the view follows it), or a copy in a run that can crack — a crack re-cuts the mesh and
/// the state's arrays are replaced by longer ones (docs/fracture.md), which a view would outlive.
py::array state_array(py::handle self, const std::vector<double>& v, std::vector<py::ssize_t> shape) {
  if (fracture_of(self.cast<PySolver&>().run().view()).active()) return copy(v, std::move(shape));
  return view(v.data(), std::move(shape), self);
}

py::array state_view(py::handle self, const std::vector<double>& v, py::ssize_t columns) {
  return state_array(self, v, {static_cast<py::ssize_t>(v.size()) / columns, columns});
}

const solve::RunState& state_of(py::handle self) { return self.cast<PySolver&>().run().view().state; }

}  // namespace

void bind_solver(py::module_& m) {
  py::class_<Outcome>(m, "Outcome", R"(How a run or a step ended (common/outcome.h).

code: "ok", "interrupted", or what stopped it ("penetration", "step_displacement",
"contact_not_converged", "direction_not_finite", "unconstrained", "element_folded",
"displacement_not_finite"): summary.json's stop_code. reason: in words. time: s, of the state it
stopped at. ok; failed (nmm-solve's exit status 3); interrupted.)")
      .def_property_readonly("code", [](const Outcome& o) { return stop_code_name(o.code); })
      .def_readonly("reason", &Outcome::reason)
      .def_readonly("time", &Outcome::time)
      .def_property_readonly("ok", &Outcome::ok)
      .def_property_readonly("failed", &Outcome::failed)
      .def_property_readonly("interrupted", [](const Outcome& o) { return o.code == StopCode::interrupted; })
      .def_property_readonly("status", &Outcome::status, "summary.json's status: 'ok', 'interrupted' or the reason")
      .def("__repr__", [](const Outcome& o) {
        return std::string("<nmm.Outcome ") + stop_code_name(o.code) + (o.reason.empty() ? "" : ": " + o.reason) + ">";
      });

  py::class_<PySolver>(m, "Solver", R"(A run of a mesh, as nmm-solve makes it, stepped from Python.

Solver(mesh, set=None, config=None, restart=None, out=None, threads=0, progress=None,
       text_frames=False, contacts_every=1, contacts_gzip=False)
set: {PATH: VALUE} or ["PATH=VALUE", ...] (nmm-solve --set); config: a dict (a JSON merge patch
on the mesh's scene) or a file (--config); restart: a checkpoint file (--restart); out: the
output folder (-o): without it nothing is written. progress: True for nmm-solve's progress line
on stderr, or a function called with the solver after every accepted step (an exception from
it stops the run as Ctrl-C does). Bad variants raise nmm.SceneError, a bad checkpoint
nmm.InputError.)")
      .def(py::init<py::object, py::handle, py::handle, py::handle, py::handle, int, py::object, bool, int, bool>(),
           py::arg("mesh"), py::kw_only(), py::arg("set") = py::none(), py::arg("config") = py::none(),
           py::arg("restart") = py::none(), py::arg("out") = py::none(), py::arg("threads") = 0,
           py::arg("progress") = py::none(), py::arg("text_frames") = false, py::arg("contacts_every") = 1,
           py::arg("contacts_gzip") = false)
      .def(
          "step",
          [](py::object self) {
            return self.cast<PySolver&>().advance(self, std::numeric_limits<double>::infinity(), 1, false);
          },
          "one accepted step (of solver.time_step, or shorter where step control cut it); returns "
          "the Outcome. Outputs: history rows and frames as they fall due (flush() finishes them)")
      .def(
          "run",
          [](py::object self, py::object steps) {
            PySolver& s = self.cast<PySolver&>();
            const std::int64_t n = steps.is_none() ? s.run().scene().scene.solver.steps : steps.cast<std::int64_t>();
            if (n < 0) throw py::value_error("steps: must be >= 0");
            return s.advance(self, s.run().time_after(n), -1, true);
          },
          py::arg("steps") = py::none(),
          "advances by `steps` steps of solver.time_step (default: the scene's solver.steps), as "
          "nmm-solve runs, then finishes the outputs; returns the Outcome")
      .def(
          "run_until",
          [](py::object self, double t) {
            if (!std::isfinite(t)) throw py::value_error("t: must be a finite time in s");
            return self.cast<PySolver&>().advance(self, t, -1, true);
          },
          py::arg("t"), "advances to simulated time t (s), then finishes the outputs; returns the Outcome")
      .def("flush", &PySolver::flush,
           "writes what a finished run has (the last frame, history.csv, contacts.csv, energy.csv, "
           "run_history.csv, the checkpoint, summary.json) when there is an output folder; returns the summary")
      .def("pictures", &PySolver::pictures, py::arg("field") = "displacement", py::arg("exaggerate") = py::none(),
           "nmm-solve --pictures: result.svg of the current state and the run's report in the output folder")
      .def_property_readonly("mesh", &PySolver::mesh)
      .def_property_readonly("out", [](const PySolver& s) {
        const std::string& dir = s.run().options().out_dir;
        return dir.empty() ? py::object(py::none()) : py::str(dir);
      }, "the output folder, None without one")
      .def_property_readonly("scene", [](const PySolver& s) { return to_python(s.run().scene().effective); },
                             "the scene this run steps: the mesh's with the variants, as a dict")
      .def_property_readonly("time", [](const PySolver& s) { return s.run().view().state.time; }, "s, simulated time")
      .def_property_readonly("step_number", [](const PySolver& s) { return s.run().view().state.step; },
                             "steps since step 0 of the first run (after a restart, on from the checkpoint's)")
      .def_property_readonly("steps_done", [](const PySolver& s) { return s.run().steps_done(); },
                             "accepted steps of this solver")
      .def_property_readonly("outcome", [](const PySolver& s) { return s.run().outcome(); },
                             "how the last step(), run() or run_until() ended")
      .def_property_readonly("summary", [](const PySolver& s) { return to_python(s.run().summary()); },
                             "the dict summary.json holds, of the run so far")
      .def_property_readonly("state_hash", [](const PySolver& s) { return solve::state_hash(s.run().view()); },
                             "SHA-256 of the run state and contact history (summary.json's state_hash)")
      .def_property_readonly("cover_unknowns", [](py::object self) {
        const PySolver& s = self.cast<PySolver&>();
        return state_view(self, state_of(self).cover_u, s.run().view().space.dofs_per_cover());
      }, "(pc, m) m: each physical cover's cover-function coefficients, the displacement since the "
         "start (m = 2, 6, 12 at cover order 0, 1, 2; order 0: ux, uy). A view")
      .def_property_readonly("cover_velocity", [](py::object self) {
        const PySolver& s = self.cast<PySolver&>();
        return state_view(self, state_of(self).velocity, s.run().view().space.dofs_per_cover());
      }, "(pc, m) m/s, the velocity the next step starts from. A view")
      .def_property_readonly("cover_position", [](py::object self) {
        return state_view(self, state_of(self).cover_xy, 2);
      }, "(pc, 2) m, where each physical cover's node is now. A view")
      .def_property_readonly("vertex_position", [](py::object self) {
        return state_view(self, state_of(self).loop_xy, 2);
      }, "(v, 2) m, the element polygons' vertices now (Mesh.element_vertices at the start). A view")
      .def_property_readonly("vertex_displacement", [](py::object self) {
        return state_view(self, state_of(self).loop_u, 2);
      }, "(v, 2) m, their displacement since the start. A view")
      .def_property_readonly("stress_coefficients", [](py::object self) {
        const PySolver& s = self.cast<PySolver&>();
        const auto terms = static_cast<py::ssize_t>(s.run().view().space.terms());
        const std::vector<double>& v = state_of(self).stress;
        return state_array(self, v, {static_cast<py::ssize_t>(v.size()) / (3 * terms), terms, 3});
      }, "(me, T, 3) Pa: each element's stress polynomial (σxx, σyy, τxy; tension positive), "
         "T = 1, 3, 6 terms at cover order 0, 1, 2. A view")
      .def_property_readonly("element_stress", [](const PySolver& s) {
        const std::vector<double> mean = solve::mean_stress(s.run().view());
        return copy(mean, {static_cast<py::ssize_t>(mean.size() / 3), 3});
      }, "(me, 3) Pa: each element's mean σxx, σyy, τxy (what the frames hold). A copy")
      .def_property_readonly("measure_position", [](const PySolver& s) {
        std::vector<double> xy;
        for (const solve::TrackedPoint& p : s.run().view().state.measure) xy.insert(xy.end(), {p.x, p.y});
        return copy(xy, {static_cast<py::ssize_t>(xy.size() / 2), 2});
      }, "(points, 2) m, where the measure points are now (history.csv x, y). A copy")
      .def_property_readonly("measure_displacement", [](const PySolver& s) {
        std::vector<double> u;
        for (const solve::TrackedPoint& p : s.run().view().state.measure) u.insert(u.end(), {p.x - p.x0, p.y - p.y0});
        return copy(u, {static_cast<py::ssize_t>(u.size() / 2), 2});
      }, "(points, 2) m, their displacement since the start (history.csv ux, uy). A copy")
      .def(
          "contacts",
          [](const PySolver& s, bool open) {
            const std::vector<solve::ContactSample> rows = solve::contact_samples(s.run().view(), open);
            const auto n = static_cast<py::ssize_t>(rows.size());
            py::dict d;
            auto column = [&](const char* name, auto get) {
              using T = decltype(get(rows.front()));
              py::array_t<T> a(n);
              for (py::ssize_t i = 0; i < n; ++i) a.mutable_at(i) = get(rows[static_cast<std::size_t>(i)]);
              d[name] = a;
            };
            using C = solve::ContactSample;
            column("x", [](const C& c) { return c.x; });
            column("y", [](const C& c) { return c.y; });
            column("state", [](const C& c) { return c.state; });
            column("set", [](const C& c) { return c.law; });
            column("closure", [](const C& c) { return c.closure; });
            column("shear", [](const C& c) { return c.shear; });
            column("normal_force", [](const C& c) { return c.normal_force; });
            column("shear_force", [](const C& c) { return c.shear_force; });
            column("kn", [](const C& c) { return c.kn; });
            column("ks", [](const C& c) { return c.ks; });
            column("length", [](const C& c) { return c.length; });
            column("vertex", [](const C& c) { return c.vertex; });
            column("edge", [](const C& c) { return c.edge; });
            // The joint's stresses, Pa, as contacts.csv gives them: the forces over the length.
            column("normal_stress", [](const C& c) { return c.normal_force / c.length; });
            column("shear_stress", [](const C& c) { return c.shear_force / c.length; });
            column("pressure", [](const C& c) { return c.pressure; });
            column("jrc_mob", [](const C& c) { return c.jrc_mob; });
            column("dilation", [](const C& c) { return c.dilation; });
            return d;
          },
          py::arg("open") = false,
          "the contacts now, as contacts.csv's columns (a dict of arrays): x, y (m), state (0 open, "
          "1 locked, 2 sliding), set, closure, shear (m), normal_force, shear_force (N), kn, ks (N/m), "
          "length (m), vertex, edge, normal_stress, shear_stress, pressure (Pa), jrc_mob, dilation "
          "(m). Closed contacts only, as contacts.csv, unless open=True")
      // Cracks and crack tips (crack_arrays.h; docs/python.md "Cracks and crack tips").
      .def(
          "cracks", [](const PySolver& s) { return crack_segments(s.run().view()); },
          "the crack segments of the run so far, as cracks.csv's columns (a dict of arrays, a row per "
          "segment in the order they formed): x0, y0, x1, y1 (m, where its ends were when it formed), "
          "mode (0 tensile, 1 shear), crack (which crack), step, time (s)")
      .def(
          "crack_tips", [](PySolver& s) { return crack_tips(s.run().view(), s.tip_finder()); },
          "the crack tips inside a body now (the scene's joints' and the cracks'), as crack_tips.csv's "
          "columns (a dict of arrays, a row per tip): tip (its number, kept as its crack grows), x, y (m), "
          "k1, k2 (Pa·√m, K_I and K_II by the interaction integral), angle_deg (the maximum tangential "
          "stress direction, deg from +x), direction ((n, 2) the same as a unit vector), radius (m)")
      .def(
          "flow",
          [](const PySolver& s) -> py::object {
            const solve::RunView v = s.run().view();
            const solve::FlowEffect* flow = nullptr;
            for (const solve::Effect* e : v.effects)
              if (const auto* f = dynamic_cast<const solve::FlowEffect*>(e); f != nullptr && f->active()) flow = f;
            if (flow == nullptr) return py::none();
            const solve::FlowNetwork& net = flow->network();
            const solve::RunState& st = v.state;
            const auto n = static_cast<py::ssize_t>(net.nodes());
            const auto ns = static_cast<py::ssize_t>(net.segments().size());
            std::vector<double> position(net.node_xy());
            const std::vector<double> u = net.node_displacements(st.loop_u);
            for (std::size_t i = 0; i < position.size(); ++i) position[i] += u[i];
            std::vector<std::int32_t> ends, joint;
            for (const solve::FlowSegment& sg : net.segments()) {
              ends.insert(ends.end(), {sg.a, sg.b});
              joint.push_back(sg.joint);
            }
            py::dict d;
            d["xy"] = copy(net.node_xy(), {n, 2});
            d["position"] = copy(position, {n, 2});
            d["pressure"] = copy(st.flow_pressure, {n});
            d["aperture"] = copy(net.node_apertures(st.flow_aperture), {n});
            d["boundary"] = copy(net.node_boundary(), {n});
            d["segments"] = copy(ends, {ns, 2});
            d["segment_joint"] = copy(joint, {ns});
            d["segment_aperture"] = copy(st.flow_aperture, {ns, 2});
            return std::move(d);
          },
          "the flow network now (a scene with \"flow\"; None without), a dict of arrays (copies): "
          "xy (n, 2) m, each node where it is in the mesh as cut (flow.csv x, y); position (n, 2) m, "
          "where it is now; pressure (n,) Pa; aperture (n,) m, the mean hydraulic aperture of the "
          "segment ends at the node (flow.csv); boundary (n,) the `boundaries` entry holding it, -1 "
          "free; segments (s, 2) its segments' end nodes; segment_joint (s,) the scene's joint of "
          "each; segment_aperture (s, 2) m, the hydraulic aperture at each segment's two ends")
      .def("__repr__", [](const PySolver& s) {
        const solve::RunView v = s.run().view();
        return "<nmm.Solver t = " + std::to_string(v.state.time) + " s, step " + std::to_string(v.state.step) +
               ", " + std::to_string(v.mesh.element_count()) + " elements>";
      });
}

}  // namespace nmm::python
