// flow.csv: see flow_output.h.
#include "solver/output/flow_output.h"

#include <charconv>
#include <filesystem>

#include "common/atomic_file.h"
#include "solver/flow/flow_effect.h"

namespace nmm::solve {

namespace {

void append_number(std::string& out, double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}

const FlowEffect* flow_of(const RunView& run) {
  for (const Effect* e : run.effects)
    if (const auto* f = dynamic_cast<const FlowEffect*>(e); f && f->active()) return f;
  return nullptr;
}

}  // namespace

void FlowOutput::add_rows(const RunView& run) {
  const FlowEffect* flow = flow_of(run);
  const RunState& s = run.state;
  if (!flow || s.step == last_step_ || s.flow_pressure.size() != flow->network().nodes()) return;
  last_step_ = s.step;
  const FlowNetwork& net = flow->network();
  const std::vector<double> aperture = net.node_apertures(s.flow_aperture);
  for (std::size_t i = 0; i < net.nodes(); ++i) {
    rows_ += std::to_string(s.step);
    rows_ += ',';
    append_number(rows_, s.time);
    rows_ += ',' + std::to_string(i);
    for (double v : {net.node_xy()[2 * i], net.node_xy()[2 * i + 1], s.flow_pressure[i], aperture[i]}) {
      rows_ += ',';
      append_number(rows_, v);
    }
    rows_ += '\n';
  }
}

void FlowOutput::finish(const RunView& run, const Outcome&, std::int64_t) {
  if (!flow_of(run)) return;
  add_rows(run);
  write_file_atomically((std::filesystem::path(dir_) / "flow.csv").string(),
                        "step,time,node,x,y,pressure,aperture\n" + rows_);
}

}  // namespace nmm::solve
