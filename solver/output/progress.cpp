// Progress line: see progress.h.
#include "solver/output/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace nmm::solve {
namespace {

// "1 h 02 min", "3 min 05 s", "12 s": short enough for one line.
std::string duration(double s) {
  char buf[48];
  if (!std::isfinite(s) || s < 0) return "?";
  const long long t = std::llround(s);
  if (t >= 3600)
    std::snprintf(buf, sizeof buf, "%lld h %02lld min", t / 3600, (t % 3600) / 60);
  else if (t >= 60)
    std::snprintf(buf, sizeof buf, "%lld min %02lld s", t / 60, t % 60);
  else
    std::snprintf(buf, sizeof buf, "%lld s", t);
  return buf;
}

}  // namespace

ProgressLine::ProgressLine(Mode mode, double t_end, std::FILE* out, double terminal_period,
                           double plain_period)
    : mode_(mode), t_end_(t_end), out_(out),
      period_(mode == Mode::terminal ? terminal_period : plain_period), start_(Clock::now()) {}

ProgressLine::Mode ProgressLine::choose(bool quiet, std::FILE* out) {
  if (quiet) return Mode::off;
  return isatty(fileno(out)) ? Mode::terminal : Mode::plain;
}

double ProgressLine::seconds_since_start() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

std::string ProgressLine::line(std::int64_t step, double time, double wall) const {
  const double fraction = t_end_ > 0 ? std::clamp(time / t_end_, 0.0, 1.0) : 1.0;
  // The estimate assumes the remaining simulated time costs what the past did per second;
  // step cuts make it optimistic, so it is labelled "about".
  const std::string left = fraction > 0 ? duration(wall * (1 - fraction) / fraction) : "?";
  char buf[200];
  std::snprintf(buf, sizeof buf, "nmm-solve: %5.1f%%  t = %.4g / %.4g s  step %lld  %s spent, about %s left",
                100 * fraction, time, t_end_, static_cast<long long>(step),
                duration(wall).c_str(), left.c_str());
  return buf;
}

void ProgressLine::print_warning() {
  if (warning_.empty()) return;
  std::fprintf(out_, "nmm-solve: warning: %s\n", warning_.c_str());
  warning_.clear();
}

void ProgressLine::update(std::int64_t step, double time) {
  if (mode_ == Mode::off) return;
  const double now = seconds_since_start();
  if (now - last_ < period_) return;
  last_ = now;
  if (!printed_) print_warning();
  printed_ = true;
  if (mode_ == Mode::terminal)
    std::fprintf(out_, "\r%s\033[K", line(step, time, now).c_str());
  else
    std::fprintf(out_, "%s\n", line(step, time, now).c_str());
  std::fflush(out_);
}

void ProgressLine::finish(std::int64_t step, double time, bool ended_ok, const std::string& note) {
  if (mode_ == Mode::off) return;
  // A run that did not end "ok" is reported by the caller in exactly one line (the exit-status
  // contract): only end a terminal's in-place line here.
  if (!ended_ok) {
    if (mode_ == Mode::terminal && printed_) std::fprintf(out_, "\n");
    std::fflush(out_);
    return;
  }
  const std::string text =
      line(step, time, seconds_since_start()) + (note.empty() ? std::string() : "; " + note);
  if (!printed_) print_warning();
  if (mode_ == Mode::terminal) std::fprintf(out_, "\r%s\033[K\n", text.c_str());
  else std::fprintf(out_, "%s\n", text.c_str());
  std::fflush(out_);
}

}  // namespace nmm::solve
