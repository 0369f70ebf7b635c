// What `nmm-inspect --network` reports about the joint network of a mesh (issue 14;
// docs/joint-networks.md, "Inspecting a network"): per joint set the requested and measured P21,
// P10 along scanlines and the mean spacing normal to the set, trace-length and orientation
// statistics; the block count and block-area distribution; and four SVG pictures.
//
// Definitions (A = area of the measuring region R: for a generated set its generation region
// (default the bodies' bounding box) ∩ that box, where the generator meets its request; for a set
// typed by hand the rock itself, the bodies without their holes):
//   P21          = Σ (length of each joint inside R) / A                           m/m²
//   mean angle θ̄ = ½ atan2(Σ Lᵢ sin 2θᵢ, Σ Lᵢ cos 2θᵢ) (axial, length-weighted), resultant
//                  R̄ = |Σ Lᵢ e^{2iθᵢ}| / Σ Lᵢ (1: parallel joints)
//   scanlines    K = 50 parallel lines along the set's normal n = (−sin θ̄, cos θ̄), evenly spaced
//                  across R (offsets (k + ½)·W/K along the trace direction, W the width of R
//                  along it), each clipped to R
//   P10          = (crossings of the set's joints with the scanlines) / (scanline length)   1/m
//   P10 expected = P21 · Σ Lᵢ |cos(θᵢ − θ̄)| / Σ Lᵢ (stereology: a joint of direction θ is crossed
//                  by a line along n with probability ∝ L |cos(θ − θ̄)|)
//   mean spacing = mean distance between consecutive crossings on a scanline piece         m
//   percentiles  linear interpolation between order statistics (p-th: x at rank p·(n−1))
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::pre {

/// Order statistics of a sample (all 0 with count 0).
struct SampleStats {
  std::size_t count = 0;
  double total = 0, mean = 0, median = 0, min = 0, max = 0, std_dev = 0;  ///< sample's unit
};
SampleStats sample_stats(std::vector<double> values);
/// p in [0, 1]: linear interpolation between order statistics of `sorted` (ascending).
double percentile(const std::vector<double>& sorted, double p);

struct JointSetNetworkReport {
  std::string name;
  bool generated = false;       ///< the set carries generated_from (or generate)
  double requested_p21 = 0;     ///< m/m², 0 when not generated
  double region_area = 0;       ///< m², of the measuring region (see top of file)
  double measured_p21 = 0;      ///< m/m²
  double mean_angle_deg = 0;    ///< degrees, axial mean in [0, 180) (generated: request ± 90)
  double requested_angle_deg = 0;  ///< degrees, the generate block's mean_deg (generated sets)
  double resultant_length = 0;  ///< –, R̄ of the doubled angles
  double scanline_angle_deg = 0;  ///< degrees in [0, 180), direction of the scanlines (θ̄ + 90°)
  int scanlines = 0;
  double scanline_length = 0;   ///< m, total
  std::size_t crossings = 0;
  double p10 = 0;               ///< 1/m
  double p10_expected = 0;      ///< 1/m, from P21 and the orientations (see top of file)
  double mean_spacing = 0;      ///< m, 0 when no scanline crosses twice
  std::size_t spacings = 0;     ///< gaps measured
  SampleStats trace_lengths;    ///< m, whole joints as listed in the scene
  std::vector<double> lengths;  ///< m, per joint
  std::vector<double> angles_deg;  ///< degrees in [0, 180), per joint segment
  std::vector<double> angle_weights;  ///< m, segment length of each angle
};

struct NetworkReport {
  std::vector<JointSetNetworkReport> sets;  ///< in the scene's order (by name)
  std::size_t blocks = 0;
  std::vector<double> block_areas;  ///< m², ascending
  double block_area_total = 0;      ///< m²
  double block_area_mean = 0;       ///< m²
};

/// The report of a mesh and its (embedded) scene.
NetworkReport network_report(const Mesh& mesh, const SceneDef& scene);
/// Only the joint-set part (no mesh): used on scenes and in tests.
std::vector<JointSetNetworkReport> joint_set_reports(const SceneDef& scene);

nlohmann::json network_report_json(const NetworkReport& report);
std::string network_report_text(const NetworkReport& report);

/// Rose diagram of trace directions, one panel per set with joints: 18 bins of 10° over
/// [0°, 180°) drawn twice (θ and θ + 180°, traces are axial), wedge radius ∝ count in the bin.
std::string rose_svg(const NetworkReport& report);
/// Trace-length histogram, one step line per set (20 bins from 0 to the longest trace).
std::string trace_length_histogram_svg(const NetworkReport& report);
/// Cumulative distribution of block areas (fraction of blocks with area ≤ a), log area axis.
std::string block_area_cdf_svg(const NetworkReport& report);
/// The bodies (grey) with every joint in its set's colour, then the holes over them (white:
/// joint parts in an opening are not in the rock), and a legend.
std::string network_svg(const SceneDef& scene);

/// Colour of set i in the network pictures.
std::string set_colour(std::size_t set);

}  // namespace nmm::pre
