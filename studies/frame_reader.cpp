// Frame reading (see the header).
#include "studies/frame_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.h"

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

// The numbers of the <DataArray ... Name="name" ...> element; empty if there is none.
std::vector<double> data_array(const std::string& xml, const std::string& name) {
  const std::size_t at = xml.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const std::size_t open = xml.find('>', at);
  const std::size_t close = xml.find("</DataArray>", open);
  if (open == std::string::npos || close == std::string::npos) return {};
  std::istringstream in(xml.substr(open + 1, close - open - 1));
  std::vector<double> v;
  double x;
  while (in >> x) v.push_back(x);
  return v;
}

std::vector<int> ints(const std::vector<double>& v) { return std::vector<int>(v.begin(), v.end()); }

}  // namespace

std::vector<std::pair<double, std::string>> list_frames(const std::string& run_dir) {
  const std::string pvd = slurp(fs::path(run_dir) / "frames.pvd");
  std::vector<std::pair<double, std::string>> out;
  for (std::size_t at = pvd.find("<DataSet"); at != std::string::npos; at = pvd.find("<DataSet", at + 1)) {
    const std::size_t t = pvd.find("timestep=\"", at), f = pvd.find("file=\"", at);
    if (t == std::string::npos || f == std::string::npos) break;
    if (pvd.compare(f + 6, 13, "frames/frame_") != 0) continue;  // an effect's part (frames/flow_*.vtu)
    const double time = std::stod(pvd.substr(t + 10));
    const std::size_t end = pvd.find('"', f + 6);
    out.emplace_back(time, (fs::path(run_dir) / pvd.substr(f + 6, end - f - 6)).string());
  }
  std::sort(out.begin(), out.end());
  if (out.empty()) throw RunError(run_dir + "/frames.pvd: no frame");
  return out;
}

Frame read_frame(const std::string& vtu_path) {
  const std::string xml = slurp(vtu_path);
  Frame f;
  f.points = data_array(xml, "Points");
  f.displacement = data_array(xml, "displacement");
  f.connectivity = ints(data_array(xml, "connectivity"));
  f.offsets = ints(data_array(xml, "offsets"));
  f.block = ints(data_array(xml, "block"));
  if (f.points.empty() || f.displacement.size() != f.points.size() || f.offsets.empty())
    throw RunError(vtu_path + ": not a solver frame (Points, displacement, cells)");
  for (int v : f.connectivity)
    if (v < 0 || 3 * static_cast<std::size_t>(v) >= f.points.size())
      throw RunError(vtu_path + ": connectivity out of range");
  if (!f.block.empty() && f.block.size() != f.offsets.size())
    throw RunError(vtu_path + ": block array does not match the cells");
  return f;
}

std::vector<double> block_mean_displacement(const Frame& f) {
  if (f.block.empty()) return {};
  const int nb = *std::max_element(f.block.begin(), f.block.end()) + 1;
  std::vector<double> sum(2 * static_cast<std::size_t>(std::max(nb, 0)), 0.0);
  std::vector<double> count(static_cast<std::size_t>(std::max(nb, 0)), 0.0);
  std::size_t begin = 0;
  for (std::size_t c = 0; c < f.offsets.size(); ++c) {
    const auto end = static_cast<std::size_t>(f.offsets[c]);
    const int b = f.block[c];
    for (std::size_t k = begin; k < end && k < f.connectivity.size(); ++k) {
      const auto v = static_cast<std::size_t>(f.connectivity[k]);
      if (b < 0) continue;
      sum[2 * b] += f.displacement[3 * v];
      sum[2 * b + 1] += f.displacement[3 * v + 1];
      count[b] += 1;
    }
    begin = end;
  }
  for (int b = 0; b < nb; ++b)
    if (count[b] > 0) {
      sum[2 * b] /= count[b];
      sum[2 * b + 1] /= count[b];
    }
  return sum;
}

}  // namespace nmm::studies
