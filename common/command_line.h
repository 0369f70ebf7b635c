// Command-line parsing shared by the tools: the exit-status contract in one place.
#pragma once

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "common/error.h"

namespace nmm {

/// Parses argv into `app`. Returns -1 to go on, or the status to exit with: 0 after --help or
/// --version, kExitBadInput (2) after a command-line error, reported on one line on stderr.
inline int parse_command_line(CLI::App& app, int argc, char** argv, const char* tool) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << tool << ": command line: " << e.what() << " (see --help)\n";
    return kExitBadInput;
  }
  return -1;
}

/// The exit status for the exception being handled (call inside a catch block), reported on one
/// line on stderr: InputError → its "file: where: what" line and kExitBadInput (2); RunError →
/// "tool: reason" and kExitRunFailed (3); anything else is a bug, not bad input →
/// "tool: internal error: what" and 1. Each tool's main ends with this.
inline int exit_status_of_current_exception(const char* tool) {
  try {
    throw;
  } catch (const InputError& e) {
    std::cerr << e.what() << "\n";
    return kExitBadInput;
  } catch (const RunError& e) {
    std::cerr << tool << ": " << e.what() << "\n";
    return kExitRunFailed;
  } catch (const std::exception& e) {
    std::string line = std::string(tool) + ": internal error: " + e.what();
    for (char& c : line)
      if (c == '\n' || c == '\r') c = ' ';
    std::cerr << line << "\n";
    return 1;
  } catch (...) {
    std::cerr << tool << ": internal error: an exception of unknown type\n";
    return 1;
  }
}

}  // namespace nmm
