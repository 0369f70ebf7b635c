// The picture of one state of a run (result.svg): the deformed blocks, each manifold element
// filled by a colour scale of displacement magnitude or one stress component, joints and body
// boundaries in their current position, closed contacts marked by state (sticking, sliding),
// fixed points and measure points marked, a colour bar with units and a title with the time.
//
// Colour scale without slivers: an element's weight in the scale is its area, and the bar
// spans the area-weighted 1st to 99th percentile of the field (displacement: 0 to the 99th).
// A sliver of 1e-4 of the mean element area carries 1e-4 of the weight, so a spurious 37 MPa in
// one 0.0125 m² element cannot stretch the bar of a slope whose stresses are about 1 MPa.
// Values beyond the bar are drawn in its end colours, and the bar says how much area that is.
#pragma once

#include <string>
#include <vector>

#include "mesh.h"
#include "scene.h"

namespace nmm::solve {

/// What colours the elements.
enum class PictureField { displacement, stress_xx, stress_yy, stress_xy };

/// "displacement", "sxx", "syy", "sxy" → field; false when the name is none of them.
bool parse_picture_field(const std::string& name, PictureField& field);

/// One closed contact to mark.
struct PictureContact {
  double x, y;  ///< m, current position of the contact vertex
  int state;    ///< 1 sticking (locked), 2 sliding (ContactState)
};

struct PictureState {
  double time = 0;                      ///< s, simulated time of the state
  std::string status;                   ///< run status ("ok", "interrupted", ...), shown in title
  const std::vector<double>* loop_xy;   ///< [2·v] m, current loop vertex positions
  const std::vector<double>* stress;    ///< [3·me] Pa, σxx σyy σxy (tension positive)
  std::vector<PictureContact> contacts;
  std::vector<Vec2> measure_points;     ///< m, current positions
};

/// The area-weighted quantile q in [0, 1] of `values` with weights `weights` (same length).
double weighted_quantile(const std::vector<double>& values, const std::vector<double>& weights,
                         double q);

/// The SVG document.
std::string result_svg(const Mesh& mesh, const SceneDef& scene, const PictureState& state,
                       PictureField field);

}  // namespace nmm::solve
