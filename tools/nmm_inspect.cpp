// nmm-inspect: reads a mesh file (.nmm) and reports on it; docs/inspect.md.
//
//   nmm-inspect MESH.nmm [--json [--full]] [--svg FILE] [--vtk FILE] [--cover N]
//               [--network] [--network-svg PREFIX]
//
// Everything is read and checked before any file is written, so bad input never leaves some
// outputs written and others not. Exit status 0, or 2 with one line on stderr for bad input of
// any kind (docs/interface.md).
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/mesh.h"
#include "common/mesh_file.h"
#include "common/mesh_report.h"
#include "preprocess/network_report.h"
#include "common/scene.h"
#include "common/svg_writer.h"
#include "common/vtk_writer.h"

namespace {

int run(int argc, char** argv) {
  CLI::App app{
      "Reads an NMM mesh file written by nmm-preprocess and reports on it: a summary (default) "
      "or JSON on stdout, and optionally an SVG picture and a VTK file for ParaView.",
      "nmm-inspect"};
  std::string mesh_path, svg_path, vtk_path, network_prefix;
  bool json = false, full = false, network = false;
  long long cover = -1;
  app.add_option("mesh", mesh_path, "Mesh file (.nmm) written by nmm-preprocess")
      ->required()
      ->type_name("FILE");
  CLI::Option* json_opt =
      app.add_flag("--json", json, "Print one JSON object on stdout instead of the summary");
  app.add_flag("--full", full,
               "With --json: add node_xy, triangle_nodes, physical_cover_node and elements")
      ->needs(json_opt);
  app.add_option("--svg", svg_path, "Write a picture of the mesh to FILE (SVG)")->type_name("FILE");
  app.add_option("--vtk", vtk_path,
                 "Write the manifold elements for ParaView to FILE: XML (.vtu) if FILE ends in "
                 ".vtu, legacy VTK otherwise")
      ->type_name("FILE");
  CLI::Option* cover_opt = app.add_option(
      "--cover", cover,
      "Report on physical cover N; highlight it in the SVG and flag its elements in the VTK file");
  cover_opt->type_name("N");
  app.add_flag("--network", network,
               "Report the joint network: per set requested and measured P21, P10 on scanlines, "
               "mean spacing, trace lengths; block count and block-area percentiles (with --json: "
               "the key \"network\")");
  app.add_option("--network-svg", network_prefix,
                 "Write PREFIX-rose.svg, PREFIX-trace-lengths.svg, PREFIX-block-areas.svg and "
                 "PREFIX-network.svg (docs/joint-networks.md)")
      ->type_name("PREFIX");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help: print it, exit 0
    // CLI11's own report spans several lines; the contract wants exactly one.
    throw nmm::InputError("", "command line", e.what());
  }

  const nmm::Mesh mesh = nmm::read_mesh_file(mesh_path);
  const nmm::SceneDef scene = nmm::embedded_scene(mesh, mesh_path);
  const bool has_cover = cover_opt->count() > 0;
  nlohmann::json cover_json;
  if (has_cover) cover_json = nmm::cover_report_json(mesh, cover);  // range check before output

  // Build every output in memory first; only then touch the file system.
  const bool want_network = network || !network_prefix.empty();
  nmm::pre::NetworkReport network_rep;
  if (want_network) network_rep = nmm::pre::network_report(mesh, scene);
  std::vector<std::pair<std::string, std::string>> network_svgs;
  if (!network_prefix.empty())
    network_svgs = {{network_prefix + "-rose.svg", nmm::pre::rose_svg(network_rep)},
                    {network_prefix + "-trace-lengths.svg",
                     nmm::pre::trace_length_histogram_svg(network_rep)},
                    {network_prefix + "-block-areas.svg", nmm::pre::block_area_cdf_svg(network_rep)},
                    {network_prefix + "-network.svg", nmm::pre::network_svg(scene)}};
  std::string svg_text;
  if (!svg_path.empty())
    svg_text = nmm::mesh_svg(mesh, &scene, has_cover ? static_cast<int>(cover) : -1);
  std::string vtk_text;
  if (!vtk_path.empty()) {
    nmm::PolygonGrid grid = nmm::mesh_to_grid(mesh);
    if (has_cover) {
      std::vector<std::int32_t> in_cover(mesh.element_count(), 0);
      for (const auto& e : cover_json["elements"]) in_cover[e.get<std::size_t>()] = 1;
      grid.add_cell_array("in_cover_" + std::to_string(cover), 1, std::move(in_cover));
    }
    vtk_text = nmm::is_vtu_path(vtk_path)
                   ? nmm::vtu_text(grid)
                   : nmm::legacy_vtk_text(
                         grid, "nmm mesh " + (scene.name.empty() ? mesh_path : scene.name));
  }
  if (!svg_path.empty()) nmm::write_file_atomically(svg_path, svg_text);
  if (!vtk_path.empty()) nmm::write_file_atomically(vtk_path, vtk_text);
  for (const auto& [path, text] : network_svgs) nmm::write_file_atomically(path, text);

  // Scene names, file names and the tool version come from the file: invalid UTF-8 there must
  // not make the JSON dump throw, so it is replaced.
  constexpr auto kReplace = nlohmann::json::error_handler_t::replace;
  if (json) {
    nlohmann::json report = nmm::mesh_report_json(mesh, &scene, full);
    if (has_cover) report["cover"] = cover_json;
    if (network) report["network"] = nmm::pre::network_report_json(network_rep);
    // --full is large: one compact line; the short report is indented for people.
    std::cout << (full ? report.dump(-1, ' ', false, kReplace)
                       : report.dump(2, ' ', false, kReplace))
              << '\n';
  } else {
    std::cout << nmm::mesh_summary_text(mesh, &scene);
    if (has_cover) std::cout << nmm::cover_summary_text(mesh, cover);
    if (network) std::cout << nmm::pre::network_report_text(network_rep);
    if (!svg_path.empty()) std::cout << "wrote " << svg_path << '\n';
    if (!vtk_path.empty()) std::cout << "wrote " << vtk_path << '\n';
    for (const auto& svg : network_svgs) std::cout << "wrote " << svg.first << '\n';
  }
  std::cout.flush();
  if (!std::cout) throw nmm::InputError("", "stdout", "cannot write the report");
  return nmm::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const nmm::InputError& e) {
    std::cerr << e.what() << '\n';
    return nmm::kExitBadInput;
  } catch (const std::exception& e) {
    // Not expected (out of memory, a bug): still one line and no crash, as the contract asks.
    std::string line = std::string("nmm-inspect: internal error: ") + e.what();
    for (char& c : line)
      if (c == '\n' || c == '\r') c = ' ';
    std::cerr << line << '\n';
    return nmm::kExitBadInput;
  }
}
