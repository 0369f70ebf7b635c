// PNG copies of SVG pictures, for viewers and documents that do not show SVG: made by
// rsvg-convert (Debian librsvg2-bin) when it is on PATH, on a white background. Used by
// nmm-solve --pictures / nmm-report (run_report.h), nmm-fos and nmm-sweep.
#pragma once

#include <string>

namespace nmm {

/// True when rsvg-convert can be run (looked up once per process).
bool png_converter_available();

/// Writes PICTURE.png next to PICTURE.svg (`svg_path` must end in ".svg"). Returns the PNG's
/// path, or "" when rsvg-convert is absent or failed (the SVG is the picture; the PNG a copy).
std::string write_png_copy(const std::string& svg_path);

}  // namespace nmm
