// PNG copies of SVG pictures: see png_copy.h.
#include "common/png_copy.h"

#include <cstdlib>
#include <filesystem>

namespace nmm {

namespace {

// The path in single quotes for sh, with any single quote in it closed, escaped and reopened.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

bool png_converter_available() {
  static const bool found = std::system("command -v rsvg-convert >/dev/null 2>&1") == 0;
  return found;
}

std::string write_png_copy(const std::string& svg_path) {
  if (!png_converter_available() || svg_path.size() < 4 ||
      svg_path.compare(svg_path.size() - 4, 4, ".svg") != 0)
    return "";
  const std::string png = svg_path.substr(0, svg_path.size() - 4) + ".png";
  const std::string cmd =
      "rsvg-convert -b white -o " + quoted(png) + " " + quoted(svg_path) + " 2>/dev/null";
  if (std::system(cmd.c_str()) != 0) {
    std::error_code ec;
    std::filesystem::remove(png, ec);  // no half-written copy
    return "";
  }
  return png;
}

}  // namespace nmm
