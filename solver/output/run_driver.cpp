// A run as a pipeline of the stepping core and observers: see run_driver.h.
#include "solver/output/run_driver.h"

#include "solver/stepping/restart.h"
#include "solver/output/run_summary.h"
#include "common/stopwatch.h"
#include "common/error.h"

namespace nmm::solve {

// Frames (and contacts.csv) every output_every steps, history.csv rows every history_every: a
// history at every step costs no frame. The last step, and the last state of a run that stopped
// (or that the caller finished) between output steps, always get a frame.
class RunDriver::FrameOutput : public StepObserver {
 public:
  FrameOutput(OutputWriter& out, std::int64_t first_step, const SolverDef& sv)
      : out_(out), first_step_(first_step), output_every_(sv.output_every),
        history_every_(sv.history_every > 0 ? sv.history_every : sv.output_every) {}

  void start(const RunView& st) override { frame(st, 0); }
  void after_step(const RunView& st, std::int64_t n, bool last) override {
    if (n % output_every_ == 0 || last) frame(st, n);
    else if (n % history_every_ == 0) history(st, n);
  }
  void finish(const RunView& st, const Outcome&, std::int64_t done) override {
    if (done != last_frame_) frame(st, done);  // the last good state
    out_.flush_history();
  }

 private:
  void history(const RunView& st, std::int64_t n) {
    if (n == last_history_) return;
    std::vector<MeasureSample> samples;
    for (const TrackedPoint& p : st.state.measure) samples.push_back({p.x, p.y, p.x - p.x0, p.y - p.y0});
    out_.add_history(first_step_ + n, st.state.time, samples);
    last_history_ = n;
  }
  void frame(const RunView& st, std::int64_t n) {
    const std::int64_t step = first_step_ + n;
    last_frame_ = n;
    history(st, n);
    const RunState& s = st.state;
    const Mesh& mesh = st.mesh;
    FrameFields fields;
    fields.loop_xy = &s.loop_xy;
    fields.loop_u = &s.loop_u;
    const std::vector<double> mean = mean_stress(st);  // n = 0: the element stresses themselves
    fields.stress = &mean;
    std::vector<double> at_vertex;
    if (st.space.order() > 0) {
      at_vertex.resize(s.loop_xy.size() / 2 * 3);
      for (std::size_t e = 0; e < mesh.element_count(); ++e)
        for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
          const auto sg = stress_at(st, e, s.loop_xy[2 * v], s.loop_xy[2 * v + 1]);
          for (int r = 0; r < 3; ++r) at_vertex[3 * static_cast<std::size_t>(v) + r] = sg[r];
        }
      fields.vertex_stress = &at_vertex;
    }
    // The effects' grids beside the elements (EffectOutput::frame_parts), then the output step's rows of
    // the CSV files: every effect's (effect_output.h), none named here.
    OutputStep o{step, s.time, mesh, s, out_.tables(), st.model, st.space, st.effects};
    std::vector<FramePart> parts;
    for (const Effect* e : st.effects) e->frame_parts(o, parts);
    for (const MeshChange* c : st.changes) c->frame_parts(o, parts);
    out_.write_frame(step, s.time, mesh, fields, st.topology, parts);
    out_.tables().begin_output_step();
    for (const Effect* e : st.effects) e->write_outputs(o);
    for (const MeshChange* c : st.changes) c->write_outputs(o);
  }

  OutputWriter& out_;
  std::int64_t first_step_;
  std::int64_t output_every_, history_every_;
  std::int64_t last_history_ = -1;
  std::int64_t last_frame_ = -1;
};

// checkpoint.nmmstate every checkpoint_every steps (0: never), and after the last completed
// step, also when the run stopped early.
class RunDriver::CheckpointOutput : public StepObserver {
 public:
  CheckpointOutput(std::string path, std::int64_t every) : path_(std::move(path)), every_(every) {}
  void after_step(const RunView& st, std::int64_t n, bool) override {
    if (every_ > 0 && n % every_ == 0) write_checkpoint(st, path_);
  }
  void finish(const RunView& st, const Outcome&, std::int64_t) override {
    write_checkpoint(st, path_);
  }

 private:
  std::string path_;
  std::int64_t every_;
};

std::vector<ContactSample> contact_samples(const RunView& st, bool open_too) {
  return contact_samples(st.contacts, st.model, st.state, open_too);
}

RunDriver::RunDriver(TimeStepper& stepper, OutputWriter* out) : stepper_(stepper), out_(out) {}

RunDriver::~RunDriver() = default;

void RunDriver::start() {
  const Stopwatch wall;
  std::exception_ptr write_failed;  // frame 0 could not be written: advance() takes no step
  const SolverDef& sv = stepper_.view().model.scene().solver;
  record_.first_step = stepper_.view().state.step;  // a restart continues from the checkpoint's
  if (out_) {
    frames_ = std::make_unique<FrameOutput>(*out_, record_.first_step, sv);
    checkpoint_ = std::make_unique<CheckpointOutput>(out_->dir() + "/checkpoint.nmmstate", sv.checkpoint_every);
    // What an earlier run's effects wrote into the folder (every effect of the list names its
    // files, whether or not this run calls for it).
    for (const Effect* e : stepper_.view().effects) out_->remove_files(e->output_files());
    for (const MeshChange* c : stepper_.view().changes) out_->remove_files(c->output_files());
    const Stopwatch sw;
    guarded([&] { frames_->start(stepper_.view()); }, write_failed);
    record_.output_seconds += sw.seconds();
  }
  for (StepObserver* o : observers_) guarded([&] { o->start(stepper_.view()); }, write_failed);
  started_ = true;
  record_.wall_seconds += wall.seconds();
}

void RunDriver::guarded(const std::function<void()>& f, std::exception_ptr& first) {
  try {
    f();
  } catch (const WriteError& e) {
    if (!first) first = std::current_exception();
    output_failed_ = true;
    if (!record_.outcome.failed())
      record_.outcome = Outcome::stop(StopCode::output_failed, e.what(), stepper_.view().state.time);
  }
}

Outcome RunDriver::advance(double t_end, std::int64_t max_steps) {
  if (!started_) start();
  if (output_failed_) return record_.outcome;  // a run whose output cannot be written does not go on
  const Stopwatch wall;
  const SolverDef& sv = stepper_.view().model.scene().solver;
  const std::int64_t before = record_.done;
  std::exception_ptr write_failed;
  try {
    record_.outcome = stepper_.run_until(
        t_end,
        [&](std::int64_t k) {
          const std::int64_t n = before + k;
          record_.done = n;
          const bool last = stepper_.view().state.time >= t_end - StepControl::kRoundOff * sv.time_step ||
                            stepper_.view().stopped_at_ratio;
          // Every observer sees the step, whichever write of it fails; then the run stops.
          if (out_) {
            // Output seconds: the frames', histories' and checkpoints' (summary.json timings.output).
            const Stopwatch sw;
            guarded([&] { frames_->after_step(stepper_.view(), n, last); }, write_failed);
            guarded([&] { checkpoint_->after_step(stepper_.view(), n, last); }, write_failed);
            record_.output_seconds += sw.seconds();
          }
          for (StepObserver* o : observers_) guarded([&] { o->after_step(stepper_.view(), n, last); }, write_failed);
          if (write_failed) std::rethrow_exception(write_failed);
        },
        max_steps);
  } catch (const WriteError&) {
    // The step is complete and the stepper between steps; record_.outcome says why it stopped.
    if (!write_failed) throw;  // not an observer's write: not ours to turn into a stop
  }
  record_.wall_seconds += wall.seconds();
  return record_.outcome;
}

nlohmann::json RunDriver::full_summary() const {
  nlohmann::json summary = run_summary(stepper_.view(), record_);
  for (const StepObserver* o : observers_) o->summarise(summary);
  return summary;
}

nlohmann::json RunDriver::finish() {
  if (!started_) start();
  const Stopwatch wall;
  std::exception_ptr write_failed;
  // A run the output stopped: summary.json first, while there may still be room for it.
  if (out_ && output_failed_)
    guarded([&] { out_->write_summary(full_summary()); }, write_failed);
  if (out_) {
    const Stopwatch sw;
    guarded([&] { frames_->finish(stepper_.view(), record_.outcome, record_.done); }, write_failed);
    guarded([&] { checkpoint_->finish(stepper_.view(), record_.outcome, record_.done); }, write_failed);
    record_.output_seconds += sw.seconds();
  }
  for (StepObserver* o : observers_) guarded([&] { o->finish(stepper_.view(), record_.outcome, record_.done); }, write_failed);
  if (out_) {
    // The files the effects write whole once the run has stopped (EffectOutput::write_files).
    const Stopwatch sw;
    const RunView v = stepper_.view();
    OutputStep o{v.state.step, v.state.time, v.mesh, v.state, out_->tables(), v.model, v.space, v.effects};
    for (const Effect* e : v.effects) guarded([&] { e->write_files(o, out_->dir()); }, write_failed);
    for (const MeshChange* c : v.changes) guarded([&] { c->write_files(o, out_->dir()); }, write_failed);
    record_.output_seconds += sw.seconds();
  }
  record_.wall_seconds += wall.seconds();
  nlohmann::json summary = full_summary();
  if (out_) guarded([&] { out_->write_summary(summary); }, write_failed);
  if (write_failed) summary = full_summary();  // the stop the failed write made
  return summary;
}

nlohmann::json RunDriver::run() {
  start();
  const SolverDef& sv = stepper_.view().model.scene().solver;
  advance(stepper_.view().state.time + static_cast<double>(sv.steps) * sv.time_step);
  return finish();
}

nlohmann::json RunDriver::summary() const { return full_summary(); }

nlohmann::json run_to_end(TimeStepper& stepper, OutputWriter& out) { return RunDriver(stepper, out).run(); }

}  // namespace nmm::solve
