// Command-line parsing shared by the tools: the exit-status contract in one place.
#pragma once

#include <CLI/CLI.hpp>

#include <iostream>

#include "error.h"

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

}  // namespace nmm
