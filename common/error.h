// Error types shared by every tool.
//
// InputError: bad input of any kind (command line, scene, mesh file). The tools print its what()
// as one line on stderr and exit with status 2. The line names the file, the place inside it (a
// JSON path such as /joints/3/points/1, or a byte offset) and what is wrong.
// RunError: a simulation that cannot go on (exit status 3).
// WriteError: an output file that cannot be written (write_file_atomically: a full disk, a
// folder gone). It is an InputError — a tool whose output path is unusable before any work is
// done reports bad input (2) — and nmm-solve's run turns one thrown after its first step into a
// stop with StopCode::output_failed (exit status 3, run_driver.h).
#pragma once

#include <stdexcept>
#include <string>

namespace nmm {

/// Exit statuses of every tool (the contract in docs/interface.md).
constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitRunFailed = 3;

class InputError : public std::runtime_error {
 public:
  /// file: the file at fault ("" for the command line); where: a JSON path or "byte N" ("" if
  /// the whole file); message: what is wrong, in words a user can act on.
  InputError(std::string file, std::string where, std::string message);
  const std::string& file() const { return file_; }
  const std::string& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_, where_, message_;
};

class WriteError : public InputError {
 public:
  using InputError::InputError;
};

class RunError : public std::runtime_error {
 public:
  explicit RunError(const std::string& reason) : std::runtime_error(reason) {}
};

}  // namespace nmm
