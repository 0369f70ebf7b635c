// Text for XML files (SVG, VTK XML): one escaping rule for every writer.
#pragma once

#include <string>

namespace nmm {

/// Escapes & < > " ' and turns control characters into spaces (XML 1.0 forbids most of them
/// even escaped, and user text such as scene names may hold them).
std::string xml_escape(const std::string& s);

}  // namespace nmm
