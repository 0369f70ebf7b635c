// The CSV tables of a run's output steps: see output_tables.h.
#include "solver/discretisation/output_tables.h"

#include <charconv>
#include <filesystem>
#include <string>

#include "common/atomic_file.h"
#include "common/gzip_text.h"

namespace nmm::solve {

void OutputTable::row(std::int64_t step, double time) {
  (*rows_) += std::to_string(step);
  add(time);
}

void OutputTable::add(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  (*rows_) += ',';
  rows_->append(buf, res.ptr);
}

void OutputTable::add_index(std::int64_t i) {
  (*rows_) += ',';
  (*rows_) += std::to_string(i);
}

void OutputTable::start_output_step(std::uint64_t serial) {
  if (serial == serial_) return;
  serial_ = serial;
  // The last skipped step's rows give way to this step's: only the run's last output step's
  // are kept whatever the sampling.
  pending_.clear();
  rows_ = calls_++ % every_ == 0 ? &kept_ : &pending_;
}

OutputTable& OutputTables::table(const std::string& name, const std::string& header) {
  auto it = tables_.find(name);
  if (it == tables_.end()) {
    const auto every = every_.find(name);
    it = tables_.emplace(name, OutputTable(header, every == every_.end() ? 1 : every->second)).first;
  }
  it->second.start_output_step(serial_);
  return it->second;
}

void OutputTables::write(const std::string& dir) {
  for (auto& [name, table] : tables_) {
    table.keep_pending();
    if (table.empty()) continue;
    const std::string path = (std::filesystem::path(dir) / name).string();
    const auto gz = gzip_.find(name);
    if (gz != gzip_.end() && gz->second)
      write_file_atomically(path + ".gz", gzip_compress(table.text()));
    else
      write_file_atomically(path, table.text());
  }
}

}  // namespace nmm::solve
