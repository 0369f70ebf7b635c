#include "common/error.h"

#include <utility>

namespace nmm {

namespace {
std::string join_line(const std::string& file, const std::string& where, const std::string& msg) {
  std::string line;
  if (!file.empty()) line += file + ": ";
  if (!where.empty()) line += where + ": ";
  line += msg;
  // One line, always: a message built from user data must not break the format.
  for (char& c : line)
    if (c == '\n' || c == '\r') c = ' ';
  return line;
}
}  // namespace

InputError::InputError(std::string file, std::string where, std::string message)
    : std::runtime_error(join_line(file, where, message)),
      file_(std::move(file)),
      where_(std::move(where)),
      message_(std::move(message)) {}

}  // namespace nmm
