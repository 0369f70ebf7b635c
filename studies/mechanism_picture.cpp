// Mechanism picture from the last VTU frame (see the header).
#include "mechanism_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "error.h"
#include "svg_writer.h"
#include "vtk_writer.h"

namespace nmm::studies {
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw RunError(p.string() + ": cannot read");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The numbers of the <DataArray ... Name="name" ...> element.
std::vector<double> data_array(const std::string& xml, const std::string& name, const std::string& file) {
  const std::string key = "Name=\"" + name + "\"";
  const std::size_t at = xml.find(key);
  if (at == std::string::npos) throw RunError(file + ": no DataArray " + name);
  const std::size_t open = xml.find('>', at);
  const std::size_t close = xml.find("</DataArray>", open);
  std::istringstream in(xml.substr(open + 1, close - open - 1));
  std::vector<double> v;
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

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
  const std::string pvd = slurp(fs::path(run_dir) / "frames.pvd");
  const std::size_t at = pvd.rfind("file=\"");
  if (at == std::string::npos) throw RunError(run_dir + "/frames.pvd: no frame");
  const std::size_t end = pvd.find('"', at + 6);
  const fs::path vtu = fs::path(run_dir) / pvd.substr(at + 6, end - at - 6);
  const std::string xml = slurp(vtu);
  const std::vector<double> pts = data_array(xml, "Points", vtu.string());
  const std::vector<double> u = data_array(xml, "displacement", vtu.string());
  const std::vector<double> conn = data_array(xml, "connectivity", vtu.string());
  const std::vector<double> offs = data_array(xml, "offsets", vtu.string());
  if (u.size() != pts.size()) throw RunError(vtu.string() + ": displacement and points differ");

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
  for (double o : offs) {
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
