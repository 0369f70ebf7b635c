// The picture of one state of a run (result.svg): the deformed blocks, each manifold element
// filled by a colour scale of displacement magnitude or one stress component, joints and body
// boundaries in their current position, fixed points, supports (what each holds) and measure
// points marked, a colour bar with units and a title with the time.
//
// Joints by contact state: every loop edge that lies on a joint or a body boundary is drawn in
// the state of the closed contacts on it — sliding (orange) if any contact touching the edge
// slides, else sticking (blue) if any sticks, else open (joints dark red, free boundaries black).
// A contact touches the two loop edges at its vertex P and the edge P faces, so both faces of a
// joint show the state. The legend counts the contacts and the joint length in each state.
// When the state's contacts were not recorded (contacts.csv sampled with --contacts-every), the
// joints are drawn grey and the legend says so: no state is invented.
//
// Colour scale without slivers: an element's weight in the scale is its area, and the bar
// spans the area-weighted 1st to 99th percentile of the field (displacement: 0 to the 99th).
// A sliver of 1e-4 of the mean element area carries 1e-4 of the weight, so a spurious 37 MPa in
// one 0.0125 m² element cannot stretch the bar of a slope whose stresses are about 1 MPa.
// Values beyond the bar are drawn in its end colours, and the bar says how much area that is.
//
// Frame and scale: axes in metres along the bottom and left of the model (round ticks), a
// scale bar under the x axis. Displacements smaller than 1 % of the model size are drawn
// exaggerated (automatic_exaggeration, or nmm-solve/nmm-report --exaggerate F), the factor in
// the title: drawn position = start + F × displacement, for elements, joints, contacts and
// measure points. The colour bar, the legend's lengths and every number stay true.
//
// A run that stopped on a failure gets a short title ("stopped, reason below"); the reason and
// its likely cause (failure_cause.h) are written under the picture, wrapped to its width.
//
// Cracks the run made (docs/fracture.md) are joints too: closed, they show their contacts' state
// like any joint; open, they are drawn by how they formed — tensile red, shear purple — with
// their lengths in the legend.
//
// Bolts: each segment a thick line in the colour of its axial force (the mean of its two
// points'), red for tension and blue for compression, from light (none) to dark (the largest
// |force| of the picture, stated in the legend); a broken bolt grey and dashed.
//
// Flow (--picture-field pressure; docs/flow.md): the elements are drawn light grey and the flow
// network's segments (frames/flow_<step>.vtu: flow_effect.h) over them, thick, each coloured by
// the mean pressure of its two nodes on the colour bar, which spans the network's lowest to
// highest node pressure (kPa). A scene without flow has no such picture (the caller refuses it).
//
// Excavated bodies (excavation.h) are gone from the model: the solver only holds their covers
// still so that the system stays regular. They are not filled, not in the colour scale, and
// their outline is drawn thin, grey and dashed where they were, the legend saying "excavated".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/mesh.h"
#include "common/outcome.h"
#include "common/scene.h"
#include "common/vtk_writer.h"

namespace nmm::report {

/// What colours the elements.
enum class PictureField { displacement, stress_xx, stress_yy, stress_xy, pressure };

/// "displacement", "sxx", "syy", "sxy", "pressure" → field; false when the name is none of them.
bool parse_picture_field(const std::string& name, PictureField& field);

/// One segment of the flow network to draw by its pressure.
struct PictureFlowSegment {
  Vec2 a, b;        ///< m, its ends now
  Vec2 a0, b0;      ///< m, where they were when the mesh was cut (the exaggerated drawing)
  double pa, pb;    ///< Pa, the pressure at its ends
};

/// The segments of a frame's flow part (points where the nodes are, point arrays "pressure" and
/// "displacement", line cells: flow_effect.h). std::invalid_argument when the arrays are missing.
std::vector<PictureFlowSegment> flow_segments_of(const PolygonGrid& flow_part);

/// One closed contact to mark.
struct PictureContact {
  double x, y;      ///< m, current position of the contact vertex
  int state;        ///< 1 sticking (locked), 2 sliding (ContactState)
  int vertex = -1;  ///< loop vertex P of the contact (-1: unknown, then only its dot is drawn)
  int edge = -1;    ///< first loop vertex of the edge P faces (-1: unknown)
};

/// One bolt to draw (solver/reinforcement/bolt_readout.h): coloured by its axial force.
struct PictureBolt {
  std::vector<Vec2> points;   ///< m, its points now, first to last
  std::vector<Vec2> start;    ///< m, where each was when the mesh was cut (the exaggerated drawing)
  std::vector<double> axial;  ///< N per bolt at each point, tension positive
  bool broken = false;        ///< drawn grey and dashed
};

struct PictureState {
  double time = 0;                      ///< s, simulated time of the state
  std::string status;                   ///< run status ("ok", "interrupted", "step 30", or a
                                        ///< stopped run's reason), shown in the title
  StopCode stop = StopCode::ok;         ///< how the run ended, where this is its last state: a
                                        ///< failure draws `status` as the reason, and its likely cause
  const std::vector<double>* loop_xy;   ///< [2·v] m, current loop vertex positions
  const std::vector<double>* stress;    ///< [3·me] Pa, σxx σyy σxy (tension positive)
  std::vector<PictureContact> contacts;
  bool contacts_known = true;           ///< false: this state's contacts were not recorded
  std::vector<PictureBolt> bolts;       ///< rock bolts and cables
  std::vector<PictureFlowSegment> flow; ///< the flow network (PictureField::pressure draws it)
  std::vector<Vec2> measure_points;     ///< m, current positions
  std::vector<std::uint8_t> excavated_body;  ///< [body] 1: excavated by this state (empty: none)
  /// [joint of the mesh] what each joint is: 0 a scene joint, 1 a tensile crack, 2 a shear crack
  /// (the run's cracks follow the scene's joints, docs/fracture.md); empty: no cracks
  std::vector<std::uint8_t> joint_crack;
  /// m, where each measure point started (empty: drawn where it is, not exaggerated)
  std::vector<Vec2> measure_start;
  /// Factor the drawn displacements are multiplied by (1: true scale); 0: automatic_exaggeration.
  double exaggeration = 0;
  std::string title;  ///< first words of the title; "": the scene's name
};

/// The colour map of every result picture (result.svg, nmm-fos's mechanism.svg): viridis, five
/// stops, linear between them; f in [0, 1] (clamped; NaN gives the low end).
std::string colour_map(double f);
inline constexpr const char* kColourMapName = "viridis";

/// The exaggeration drawn when none is asked for: 1 (true scale) when the largest displacement
/// is 1 % of the model size or more, or too small to be anything but round-off (1e-9 of it);
/// else the 1, 2 or 5 × 10^k at or below 5 % of the model size over the largest displacement,
/// so that the largest displacement is drawn as about 2–5 % of the picture.
double automatic_exaggeration(double max_displacement, double model_size);

/// Joint length (m, current configuration) per drawn state, as the legend of result_svg states it.
struct JointStateLengths {
  double open = 0, sticking = 0, sliding = 0;  ///< m, of joint or boundary edges with contact
};

/// The state of each loop edge: 0 no closed contact, 1 sticking, 2 sliding (see above).
std::vector<int> edge_contact_states(const Mesh& mesh, const std::vector<PictureContact>& contacts);

/// The area-weighted quantile q in [0, 1] of `values` with weights `weights` (same length).
double weighted_quantile(const std::vector<double>& values, const std::vector<double>& weights,
                         double q);

/// The SVG document.
std::string result_svg(const Mesh& mesh, const SceneDef& scene, const PictureState& state,
                       PictureField field);

}  // namespace nmm::report
