// A run of a mesh as nmm-solve makes it: see solve_run.h.
#include "solver/output/solve_run.h"

#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/scene.h"
#include "solver/discretisation/blas_info.h"
#include "solver/output/run_energy.h"
#include "solver/stepping/equilibrium_indicator.h"

namespace nmm::solve {

// energy.csv: the energy terms after every step, a row per output step and the last
// (energy.h); the meter starts from the state the run starts from.
class SolveRun::EnergyOutput : public StepObserver {
 public:
  EnergyOutput(const RunView& run, std::string dir, std::int64_t output_every)
      : energy_(run, true), dir_(std::move(dir)), output_every_(output_every) {}
  void after_step(const RunView& st, std::int64_t n, bool) override {
    energy_.after_step(st, n % output_every_ == 0);
  }
  void finish(const RunView& run, const Outcome&, std::int64_t) override {
    energy_.finish(run);
    energy_.meter().write_csv(dir_);
  }
  // What the effects write of the run's energy totals into summary.json (effect_energy.h
  // summarise_energy), from energy.csv's last step.
  void summarise(nlohmann::json& summary) const override { energy_.meter().summarise(energy_.sources(), summary); }

 private:
  RunEnergy energy_;
  std::string dir_;
  std::int64_t output_every_;
};

namespace {

RunScene run_scene(const Mesh& mesh, const std::string& mesh_name, const SolveOptions& o) {
  return o.config_text ? make_run_scene(mesh, mesh_name, *o.config_text, o.config_path, o.sets)
                       : make_run_scene(mesh, mesh_name, o.config_path, o.sets);
}

}  // namespace

nlohmann::json run_inputs(const std::string& mesh_path, const SolveOptions& o,
                          const std::string& picture_field, const nlohmann::json& exaggerate) {
  auto absolute = [](const std::string& p) {
    return p.empty() ? nlohmann::json(nullptr)
                     : nlohmann::json(std::filesystem::absolute(p).lexically_normal().string());
  };
  nlohmann::json inputs = {{"mesh", absolute(mesh_path)},
          {"config", o.config_text ? nlohmann::json(nullptr) : absolute(o.config_path)},
          {"set", o.sets},
          {"restart", absolute(o.restart_path)},
          {"picture_field", picture_field},
          {"exaggerate", exaggerate},
          {"contacts_every", o.contacts_every},
          {"contacts_gzip", o.contacts_gzip},
          {"text_frames", o.frame_format == FrameFormat::text}};
  // A merge patch given in memory is kept whole (nmm-report applies it as a --config file).
  if (o.config_text) inputs["config_patch"] = parse_json_text(*o.config_text, o.config_path);
  return inputs;
}

SolveRun::SolveRun(const Mesh& mesh, const std::string& mesh_name, SolveOptions options)
    : options_(std::move(options)),
      run_(run_scene(mesh, mesh_name, options_)),
      stepper_(mesh, run_.scene, run_.name) {
  stepper_.set_threads(options_.threads);
  if (!options_.restart_path.empty()) stepper_.restart_from(options_.restart_path);
  if (!options_.out_dir.empty()) {
    out_ = std::make_unique<OutputWriter>(options_.out_dir, options_.frame_format);
    out_->set_contacts_every(options_.contacts_every);
    out_->set_contacts_gzip(options_.contacts_gzip);
    out_->set_run_inputs(options_.inputs);
  }
  driver_ = std::make_unique<RunDriver>(stepper_, out_.get());
  if (out_) {
    history_ = std::make_unique<RunHistory>(options_.out_dir);
    energy_ = std::make_unique<EnergyOutput>(stepper_.view(), options_.out_dir, run_.scene.solver.output_every);
    driver_->add(*history_);
    driver_->add(*energy_);
  }
  progress_line_ = std::make_unique<StepFunction>([this](const RunView& st, std::int64_t, bool) {
    if (progress_) progress_->update(st.state.step, st.state.time);
  });
  driver_->add(*progress_line_);
}

SolveRun::~SolveRun() = default;

double SolveRun::time_after(std::int64_t steps) const {
  const SolverDef& sv = run_.scene.solver;
  return stepper_.view().state.time + static_cast<double>(steps) * sv.time_step;
}

Outcome SolveRun::advance(double t_end, std::int64_t max_steps) {
  // The solver's threads are the calling thread's (solver_threads.h): set them on this one.
  stepper_.set_threads(options_.threads);
  if (options_.progress != ProgressLine::Mode::off && max_steps < 0 &&
      t_end < std::numeric_limits<double>::infinity()) {
    progress_ = std::make_unique<ProgressLine>(options_.progress, t_end);
    // Slow BLAS kernels: said once, with the progress (blas_info.h); summary.json's blas says it always.
    progress_->set_warning(blas_warning(blas_info()));
  }
  return driver_->advance(t_end, max_steps);
}

nlohmann::json SolveRun::finish() {
  const nlohmann::json summary = driver_->finish();
  // What the effects warn of (effect_output.h warnings), said
  // once, at the end.
  if (options_.progress != ProgressLine::Mode::off) {
    std::vector<std::string> lines;
    const RunView v = stepper_.view();
    for (const Effect* e : v.effects) e->warnings(summary, lines);
    for (const MeshChange* c : v.changes) c->warnings(summary, lines);
    for (const std::string& line : lines) std::fprintf(stderr, "nmm-solve: warning: %s\n", line.c_str());
  }
  if (progress_) {
    const Outcome& outcome = driver_->outcome();
    progress_->finish(stepper_.view().state.step, stepper_.view().state.time, outcome.ok(),
                      outcome.status() + ", " + equilibrium_line(summary["equilibrium"]) +
                          (summary["stopped_by"] == "stop_at_ratio" ? ", stopped by stop_at_ratio" : ""));
    progress_.reset();
  }
  return summary;
}

nlohmann::json SolveRun::run() {
  advance(time_after(run_.scene.solver.steps));
  return finish();
}

}  // namespace nmm::solve
