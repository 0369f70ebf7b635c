// Mechanism picture of a trial run (see the header).
#include "studies/mechanism_picture.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "report/result_redraw.h"

namespace nmm::studies {

void write_mechanism_svg(const std::string& run_dir, const std::string& title,
                         const std::string& svg_path) {
  report::RedrawOptions options;
  options.title = title;
  options.field = "displacement";  // the mechanism is a displacement picture, whatever the run drew
  std::string svg;
  try {
    svg = report::redraw_result_svg(run_dir, options);
  } catch (const InputError& e) {
    // The trial's folder is the study's own output, not the user's input: a run fault.
    throw RunError(std::string("mechanism picture of ") + run_dir + ": " + e.what());
  }
  write_file_atomically(svg_path, svg);
}

}  // namespace nmm::studies
