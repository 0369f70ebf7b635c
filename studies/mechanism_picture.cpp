// Mechanism picture from the last VTU frame (see the header).
#include "mechanism_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "atomic_file.h"
#include "error.h"
#include "frame_reader.h"
#include "svg_writer.h"
#include "vtk_writer.h"

namespace nmm::studies {
namespace fs = std::filesystem;

namespace {

// Blue → cyan → yellow → red.
std::string colour(double s) {
  s = std::clamp(s, 0.0, 1.0);
  const double r = std::clamp(2 * s, 0.0, 1.0), b = std::clamp(2 - 2 * s, 0.0, 1.0);
  const double g = 1 - std::abs(2 * s - 1) * 0.6;
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", int(r * 255), int(g * 230), int(b * 255));
  return buf;
}

}  // namespace

void write_mechanism_svg(const std::string& run_dir, const std::string& title,
                         const std::string& svg_path) {
  const Frame frame = read_frame(list_frames(run_dir).back().second);
  const std::vector<double>& pts = frame.points;
  const std::vector<double>& u = frame.displacement;
  const std::vector<int>& conn = frame.connectivity;
  const std::vector<int>& offs = frame.offsets;

  double umax = 0;
  for (std::size_t i = 0; i + 2 < u.size(); i += 3) umax = std::max(umax, std::hypot(u[i], u[i + 1]));
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (std::size_t i = 0; i + 2 < pts.size(); i += 3) {
    xmin = std::min(xmin, pts[i]);
    xmax = std::max(xmax, pts[i]);
    ymin = std::min(ymin, pts[i + 1]);
    ymax = std::max(ymax, pts[i + 1]);
  }
  const double size = std::max(xmax - xmin, ymax - ymin);

  SvgWriter svg;
  std::size_t begin = 0;
  for (int o : offs) {
    const auto stop = static_cast<std::size_t>(o);
    std::vector<Vec2> poly;
    double um = 0;
    for (std::size_t k = begin; k < stop && k < conn.size(); ++k) {
      const auto v = static_cast<std::size_t>(conn[k]);
      poly.push_back({pts[3 * v], pts[3 * v + 1]});
      um += std::hypot(u[3 * v], u[3 * v + 1]);
    }
    begin = stop;
    if (poly.size() < 3) continue;
    um /= static_cast<double>(poly.size());
    SvgStyle st;
    st.fill = colour(umax > 0 ? um / umax : 0);
    st.stroke = st.fill;
    st.stroke_width = 0.002 * size;
    svg.polygon(poly, st);
  }
  // Colour bar under the picture.
  const double bar_y = ymin - 0.08 * size, bar_h = 0.025 * size, bar_w = 0.5 * size;
  for (int i = 0; i < 20; ++i) {
    SvgStyle st;
    st.fill = colour((i + 0.5) / 20);
    svg.rect({xmin + bar_w * i / 20, bar_y}, bar_w / 20 + 1e-9 * size, bar_h, st);
  }
  char label[96];
  std::snprintf(label, sizeof label, "|u|: 0 to %.3g m", umax);
  svg.text({xmin + bar_w + 0.02 * size, bar_y}, label, 0.03 * size, "#000000");
  svg.text({xmin, ymax + 0.03 * size}, title, 0.035 * size, "#000000");
  write_file_atomically(svg_path, svg.str());
}

}  // namespace nmm::studies
