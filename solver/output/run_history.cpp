// run_history.csv: see run_history.h.
#include "solver/output/run_history.h"

#include <cstdio>
#include <filesystem>

#include "common/atomic_file.h"

namespace nmm::solve {

void write_run_history(const std::string& dir, const std::vector<StepRecord>& rows) {
  std::string s = "step,time,dt,iterations,cuts,closed_contacts,max_unbalanced_ratio,"
                  "mean_unbalanced_ratio,max_velocity\n";
  char buf[256];
  for (const StepRecord& r : rows) {
    std::snprintf(buf, sizeof buf, "%lld,%.17g,%.17g,%lld,%lld,%lld,%.6g,%.6g,%.6g\n",
                  static_cast<long long>(r.step), r.time, r.dt,
                  static_cast<long long>(r.iterations), static_cast<long long>(r.cuts),
                  static_cast<long long>(r.closed_contacts), r.max_unbalanced_ratio,
                  r.mean_unbalanced_ratio, r.max_velocity);
    s += buf;
  }
  write_file_atomically((std::filesystem::path(dir) / "run_history.csv").string(), s);
}

void RunHistory::start(const RunView& st) {
  iterations_ = st.state.iterations;
  cuts_ = st.state.cuts;
  t_prev_ = st.state.time;  // 0, or the checkpoint's time
}

void RunHistory::after_step(const RunView& st, std::int64_t, bool) {
  const double t = st.state.time;
  const EquilibriumSample& eq = st.equilibrium;
  rows_.push_back({st.state.step, t, t - t_prev_, static_cast<std::int64_t>(st.state.iterations - iterations_),
                   static_cast<std::int64_t>(st.state.cuts - cuts_),
                   static_cast<std::int64_t>(st.contacts.totals().closed), eq.max_ratio, eq.mean_ratio,
                   eq.max_velocity});
  iterations_ = st.state.iterations;
  cuts_ = st.state.cuts;
  t_prev_ = t;
}

void RunHistory::finish(const RunView&, const Outcome&, std::int64_t) { write_run_history(dir_, rows_); }

}  // namespace nmm::solve
