// The CSV files a run's parts write a block of rows to at each output step (bolts.csv,
// contacts.csv, reactions.csv; next crack_tips.csv, flow.csv): one table per file, kept in memory
// and written whole (temporary name, then rename) when the run's histories are flushed, so a
// reader never sees half a file. An effect writes its rows through this, at the stage
// Effect::write_outputs (effect.h), and declares its file names (Effect::output_files) so that
// a run removes what an earlier run left in the folder; the driver (solver/output/run_driver.h)
// calls every effect at every output step and names none.
//
// A row is "step,time" and the values the table's part adds, each as the shortest text that
// reads back to the same double (std::to_chars: locale-independent, "0.001" rather than
// "0.0010000000000000000208") or as an integer:
//
//   OutputTable& t = out.tables.table("bolts.csv", "step,time,bolt,s,axial_force");
//   t.row(out.step, out.time);  t.add_index(b);  t.add(s);  t.add(axial);  t.end_row();
//
// Sampling: a table may keep the rows of every n-th output step only (contacts.csv with nmm-solve
// --contacts-every); the rows of the last output step are always kept. A table whose file is
// gzipped (--contacts-gzip) is written as name.gz. A table with no rows is not written.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>

namespace nmm::solve {

class OutputTable {
 public:
  OutputTable(std::string header, int every) : header_(std::move(header)), every_(every < 1 ? 1 : every) {}
  /// Starts a row: "step,time".
  void row(std::int64_t step, double time);
  /// Appends ",v" (shortest round-trip text of a double).
  void add(double v);
  /// Appends ",i".
  void add_index(std::int64_t i);
  /// Ends the row.
  void end_row() { (*rows_) += '\n'; }

  /// The rows are those of output step `serial` (OutputTables::begin_output_step): a new one
  /// drops the last skipped step's rows and decides whether this one's are kept.
  void start_output_step(std::uint64_t serial);
  /// Keeps the rows of the last output step the sampling skipped (the run's last state so far).
  void keep_pending() {
    kept_ += pending_;
    pending_.clear();
  }
  /// The CSV of the rows kept (header line and rows).
  std::string text() const { return header_ + "\n" + kept_; }
  bool empty() const { return kept_.empty(); }

 private:
  std::string header_;
  int every_;
  std::string kept_;            // rows of the output steps kept
  std::string pending_;         // rows of the last output step skipped by the sampling
  std::string* rows_ = &kept_;  // where this output step's rows go
  std::uint64_t serial_ = 0;    // the output step the rows belong to (0: none yet)
  std::int64_t calls_ = 0;      // output steps that wrote rows so far
};

class OutputTables {
 public:
  /// Before a new output step's rows.
  void begin_output_step() { ++serial_; }
  /// The table of file `name` (in the output folder; header: its first line, without "\n"),
  /// created on first use, ready for the rows of this output step.
  OutputTable& table(const std::string& name, const std::string& header);
  /// Keep every n-th output step's rows of `name` (the last always); before its first rows.
  void set_every(const std::string& name, int n) { every_[name] = n; }
  /// Write `name` gzip-compressed, as name + ".gz".
  void set_gzip(const std::string& name, bool on) { gzip_[name] = on; }
  /// Writes every table that has rows into folder `dir` (WriteError when it cannot); the rows
  /// of a skipped output step are kept from here on (the last state the run wrote).
  void write(const std::string& dir);

 private:
  std::map<std::string, OutputTable> tables_;
  std::map<std::string, int> every_;
  std::map<std::string, bool> gzip_;
  std::uint64_t serial_ = 0;
};

}  // namespace nmm::solve
