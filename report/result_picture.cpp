// result.svg: see result_picture.h.
#include "report/result_picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "report/failure_cause.h"
#include "solver/discretisation/joint_water.h"
#include "common/math_constants.h"
#include "common/number_format.h"
#include "common/svg_plot.h"
#include "common/svg_writer.h"
#include "common/vec2.h"

namespace nmm::report {

namespace {
/// A bolt's colour for f = force / the picture's largest |force| in [−1, 1]: white to dark red
/// for tension, white to dark blue for compression (linear in |f|, from a pale tint).
std::string bolt_colour(double f) {
  const double t = std::clamp(std::abs(f), 0.0, 1.0);
  static const int kTension[2][3] = {{252, 210, 200}, {165, 0, 38}}, kCompression[2][3] = {{200, 215, 245}, {49, 54, 149}};
  const int(*ends)[3] = f >= 0 ? kTension : kCompression;
  int rgb[3];
  for (int k = 0; k < 3; ++k) rgb[k] = static_cast<int>(std::lround(ends[0][k] * (1 - t) + ends[1][k] * t));
  char c[16];
  std::snprintf(c, sizeof c, "#%02x%02x%02x", rgb[0], rgb[1], rgb[2]);
  return c;
}
}  // namespace

std::string colour_map(double f) {
  // viridis: perceptually ordered, readable in grey and by most colour-blind readers.
  static const double stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140},
                                     {94, 201, 98}, {253, 231, 37}};
  f = std::clamp(std::isfinite(f) ? f : 0.0, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(f));
  const double t = f - i;
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x",
                static_cast<int>(std::lround(stops[i][0] + t * (stops[i + 1][0] - stops[i][0]))),
                static_cast<int>(std::lround(stops[i][1] + t * (stops[i + 1][1] - stops[i][1]))),
                static_cast<int>(std::lround(stops[i][2] + t * (stops[i + 1][2] - stops[i][2]))));
  return buf;
}

double automatic_exaggeration(double max_displacement, double model_size) {
  if (!(model_size > 0) || !(max_displacement > 1e-9 * model_size) ||
      max_displacement >= 0.01 * model_size)
    return 1;
  return round_down_125(0.05 * model_size / max_displacement);
}

bool parse_picture_field(const std::string& name, PictureField& field) {
  if (name == "displacement") field = PictureField::displacement;
  else if (name == "sxx") field = PictureField::stress_xx;
  else if (name == "syy") field = PictureField::stress_yy;
  else if (name == "sxy") field = PictureField::stress_xy;
  else if (name == "pressure") field = PictureField::pressure;
  else return false;
  return true;
}

std::vector<PictureFlowSegment> flow_segments_of(const PolygonGrid& g) {
  const GridArray *pressure = nullptr, *displacement = nullptr;
  for (const GridArray& a : g.point_data) {
    if (a.type != GridArray::Type::Float64) continue;
    if (a.name == "pressure" && a.components == 1) pressure = &a;
    if (a.name == "displacement" && a.components == 3) displacement = &a;
  }
  if (pressure == nullptr || displacement == nullptr || g.cell_type != PolygonGrid::kLine)
    throw std::invalid_argument("not a flow network: line cells with point arrays pressure and displacement");
  std::vector<PictureFlowSegment> out;
  for (std::size_t c = 0; c < g.cell_count(); ++c) {
    const auto i = static_cast<std::size_t>(g.connectivity[static_cast<std::size_t>(g.offsets[c])]);
    const auto j = static_cast<std::size_t>(g.connectivity[static_cast<std::size_t>(g.offsets[c]) + 1]);
    const Vec2 a{g.points[3 * i], g.points[3 * i + 1]}, b{g.points[3 * j], g.points[3 * j + 1]};
    const std::vector<double>& u = displacement->f64;
    out.push_back({a, b, {a.x - u[3 * i], a.y - u[3 * i + 1]}, {b.x - u[3 * j], b.y - u[3 * j + 1]},
                   pressure->f64[i], pressure->f64[j]});
  }
  return out;
}

double weighted_quantile(const std::vector<double>& values, const std::vector<double>& weights,
                         double q) {
  if (values.empty()) return 0;
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  double sum = 0;
  for (std::size_t i : order) {
    sum += weights[i];
    if (sum >= q * total) return values[i];
  }
  return values[order.back()];
}

std::vector<int> edge_contact_states(const Mesh& mesh,
                                     const std::vector<PictureContact>& contacts) {
  const std::size_t nv = mesh.loop_vertex_count();
  std::vector<int> state(nv, 0);
  // Loop neighbours of a vertex: its element's loop is element_loop_offset[e] .. [e+1].
  std::vector<std::int32_t> prev(nv), next(nv);
  for (std::size_t e = 0; e + 1 < mesh.element_loop_offset.size(); ++e) {
    const int b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    for (int v = b; v < end; ++v) {
      next[v] = v + 1 < end ? v + 1 : b;
      prev[v] = v > b ? v - 1 : end - 1;
    }
  }
  auto mark = [&](int v, int s) {
    if (v >= 0 && static_cast<std::size_t>(v) < nv) state[v] = std::max(state[v], s);
  };
  for (const PictureContact& c : contacts) {
    const int s = c.state == 2 ? 2 : 1;
    if (c.vertex >= 0 && static_cast<std::size_t>(c.vertex) < nv) {
      mark(c.vertex, s);
      mark(prev[c.vertex], s);
    }
    mark(c.edge, s);
  }
  return state;
}

namespace {
// Open cracks by how they formed (docs/fracture.md).
constexpr const char* kTensileCrack = "#e41a1c";
constexpr const char* kShearCrack = "#7b3294";
}  // namespace

std::string result_svg(const Mesh& mesh, const SceneDef& scene, const PictureState& state,
                       PictureField field) {
  const std::vector<double>& xy = *state.loop_xy;
  const std::vector<double>& sigma = *state.stress;
  const std::size_t ne = mesh.element_count();
  if (xy.size() != mesh.loop_xy.size() || sigma.size() != 3 * ne)
    throw std::logic_error("result_svg: state arrays do not match the mesh");

  // Elements of excavated bodies: not drawn, no weight in the colour scale.
  std::vector<std::uint8_t> gone(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto b = static_cast<std::size_t>(mesh.element_body[e]);
    gone[e] = b < state.excavated_body.size() && state.excavated_body[b] != 0;
  }
  // Per-element value (mm or MPa) and area weight.
  std::vector<double> value(ne), area(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    area[e] = gone[e] ? 0.0 : std::abs(element_area(mesh, e));
    const int b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    if (field == PictureField::pressure) {
      value[e] = 0;  // the elements are drawn grey; the network carries the colours
    } else if (field == PictureField::displacement) {
      double s = 0;
      for (int v = b; v < end; ++v)
        s += std::hypot(xy[2 * v] - mesh.loop_xy[2 * v], xy[2 * v + 1] - mesh.loop_xy[2 * v + 1]);
      value[e] = 1e3 * s / std::max(1, end - b);
    } else {
      const int c = field == PictureField::stress_xx ? 0 : field == PictureField::stress_yy ? 1 : 2;
      value[e] = 1e-6 * sigma[3 * e + c];
    }
  }
  double lo = field == PictureField::displacement ? 0.0 : weighted_quantile(value, area, 0.01);
  double hi = weighted_quantile(value, area, 0.99);
  if (field == PictureField::pressure) {  // kPa, the network's whole range
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (const PictureFlowSegment& f : state.flow)
      for (const double p : {f.pa, f.pb}) {
        lo = std::min(lo, 1e-3 * p);
        hi = std::max(hi, 1e-3 * p);
      }
    if (state.flow.empty()) lo = hi = 0;
  }
  if (!(hi > lo)) hi = lo + (lo == 0 ? 1e-9 : std::abs(lo) * 1e-6);
  double clamped_area = 0, total_area = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    total_area += area[e];
    if (value[e] < lo || value[e] > hi) clamped_area += area[e];
  }

  // The drawn positions: start + F × displacement. F = 1 keeps the positions themselves, so a
  // true-scale picture is the state's geometry bit for bit.
  double umax = 0;
  for (std::size_t e = 0; e < ne; ++e) {
    if (gone[e]) continue;
    for (int v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v)
      umax = std::max(umax, std::hypot(xy[2 * v] - mesh.loop_xy[2 * v],
                                       xy[2 * v + 1] - mesh.loop_xy[2 * v + 1]));
  }
  const double factor =
      state.exaggeration > 0
          ? state.exaggeration
          : automatic_exaggeration(umax, bounding_box_xy(mesh.loop_xy).longer_side());
  std::vector<double> drawn(xy);
  if (factor != 1)
    for (std::size_t i = 0; i < xy.size(); ++i)
      drawn[i] = mesh.loop_xy[i] + factor * (xy[i] - mesh.loop_xy[i]);
  auto at = [&](int v) { return Vec2{drawn[2 * v], drawn[2 * v + 1]}; };

  SvgWriter svg;
  const Box view = bounding_box_xy(drawn);
  const double xmin = view.x0, xmax = view.x1, ymin = view.y0, ymax = view.y1;
  const double size = view.longer_side();
  const double font = 0.022 * size, line = 0.0012 * size;

  // Elements: no outline of their own, so the colour field reads as a field, not a mesh.
  std::vector<Vec2> pts;
  for (std::size_t e = 0; e < ne; ++e) {
    if (gone[e]) continue;
    pts.clear();
    for (int v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v)
      pts.push_back(at(v));
    const std::string c = field == PictureField::pressure ? "#e4e4e4" : colour_map((value[e] - lo) / (hi - lo));
    svg.polygon(pts, {c, c, 0.3 * line, 0, 1});
  }
  // Joints and boundaries where they are now, coloured by the state of their contacts; the
  // legend's lengths are the true ones.
  const std::vector<int> edge_state = edge_contact_states(mesh, state.contacts);
  std::vector<std::pair<Vec2, Vec2>> joints, bounds, stick_edges, slide_edges, excavated, tensile, shear;
  JointStateLengths len;
  double tensile_length = 0, shear_length = 0;  // m, of open cracks
  const auto crack_mode = [&](int v) -> std::uint8_t {
    const auto j = static_cast<std::size_t>(mesh.loop_edge_joint[static_cast<std::size_t>(v)]);
    return mesh.loop_edge_joint[static_cast<std::size_t>(v)] >= 0 && j < state.joint_crack.size() ? state.joint_crack[j] : 0;
  };
  for (std::size_t e = 0; e < ne; ++e) {
    const int b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    for (int v = b; v < end; ++v) {
      const int w = v + 1 < end ? v + 1 : b;
      const std::pair<Vec2, Vec2> seg{at(v), at(w)};
      const bool joint = mesh.loop_edge_origin[v] & kEdgeJoint;
      const bool bound = mesh.loop_edge_origin[v] & kEdgeBoundary;
      if (gone[e]) {  // the outline of what was taken out (its joints are gone with it)
        if (bound) excavated.push_back(seg);
        continue;
      }
      if (!joint && !bound) continue;
      // Each face of a joint is a loop edge of its own: half the length per face, so the legend
      // gives the joint's length, not twice it.
      const double l = 0.5 * std::hypot(xy[2 * w] - xy[2 * v], xy[2 * w + 1] - xy[2 * v + 1]);
      if (edge_state[v] == 2) {
        slide_edges.push_back(seg);
        len.sliding += l;
      } else if (edge_state[v] == 1) {
        stick_edges.push_back(seg);
        len.sticking += l;
      } else if (joint && crack_mode(v) == 1) {
        tensile.push_back(seg);
        tensile_length += l;
      } else if (joint && crack_mode(v) == 2) {
        shear.push_back(seg);
        shear_length += l;
      } else if (joint) {
        joints.push_back(seg);
        len.open += l;
      } else {
        bounds.push_back(seg);
      }
    }
  }
  const std::string joint_colour = state.contacts_known ? "#8b0000" : "#888888";
  // Water (joint_water.h): each wet face drawn as a wide cyan band under its state colour, by
  // the pressure at its middle: five bands from light (low) to dark (the largest pressure).
  const solve::JointWater water(mesh, scene);
  double water_max = 0;
  if (water.active()) {
    static const char* const kCyans[] = {"#b8f0ff", "#66dcff", "#00bfe6", "#008fb3", "#005f73"};
    std::vector<std::pair<double, std::pair<Vec2, Vec2>>> wet;
    for (std::size_t i = 0; i < water.edges().size(); ++i) {
      const solve::BoundaryEdge& be = water.edges()[i];
      if (gone[static_cast<std::size_t>(be.element)]) continue;
      const double p = water.pressure_at(water.edge_joint()[i], 0.5 * (xy[2 * be.vertex] + xy[2 * be.next]),
                                         0.5 * (xy[2 * be.vertex + 1] + xy[2 * be.next + 1]));
      if (p > 0) wet.push_back({p, {at(be.vertex), at(be.next)}});
      water_max = std::max(water_max, p);
    }
    std::vector<std::pair<Vec2, Vec2>> band[5];
    for (const auto& [p, seg] : wet) band[std::min(4, static_cast<int>(5 * p / water_max))].push_back(seg);
    for (int k = 0; k < 5; ++k) svg.segments(band[k], {"none", kCyans[k], 7 * line, 0, 1});
  }
  svg.segments(excavated, {"none", "#999999", line, 6 * line, 1});
  svg.segments(bounds, {"none", "#000000", 1.5 * line, 0, 1});
  svg.segments(joints, {"none", joint_colour, 1.2 * line, 0, 1});
  svg.segments(tensile, {"none", kTensileCrack, 1.8 * line, 0, 1});
  svg.segments(shear, {"none", kShearCrack, 1.8 * line, 0, 1});
  svg.segments(stick_edges, {"none", "#1f77b4", 3 * line, 0, 1});
  svg.segments(slide_edges, {"none", "#ff7f0e", 3 * line, 0, 1});
  // Contact points on top, in the colour of their state, at their vertex's drawn position.
  std::size_t sticking = 0, sliding = 0;
  for (const PictureContact& c : state.contacts) {
    const bool slides = c.state == 2;
    (slides ? sliding : sticking)++;
    const bool known = c.vertex >= 0 && static_cast<std::size_t>(c.vertex) < drawn.size() / 2;
    const Vec2 p = factor != 1 && known ? at(c.vertex) : Vec2{c.x, c.y};
    svg.circle(p, 2.5 * line, {slides ? "#ff7f0e" : "#1f77b4", "none", 0, 0, 1});
  }
  // The flow network by pressure, over the joints (their contact states stay beside it).
  if (field == PictureField::pressure)
    for (const PictureFlowSegment& f : state.flow) {
      const auto drawn_at = [&](Vec2 p, Vec2 p0) {
        return factor == 1 ? p : Vec2{p0.x + factor * (p.x - p0.x), p0.y + factor * (p.y - p0.y)};
      };
      const std::string c = colour_map((0.5e-3 * (f.pa + f.pb) - lo) / (hi - lo));
      svg.segments({{drawn_at(f.a, f.a0), drawn_at(f.b, f.b0)}}, {"none", c, 5 * line, 0, 1});
    }
  // Bolts, over the rock and its joints.
  double bolt_max = 0;
  for (const PictureBolt& b : state.bolts)
    for (double f : b.axial) bolt_max = std::max(bolt_max, std::abs(f));
  for (const PictureBolt& b : state.bolts) {
    const auto drawn_point = [&](std::size_t i) {
      const Vec2 p = b.points[i];
      if (factor == 1 || i >= b.start.size()) return p;
      return Vec2{b.start[i].x + factor * (p.x - b.start[i].x), b.start[i].y + factor * (p.y - b.start[i].y)};
    };
    for (std::size_t i = 0; i + 1 < b.points.size(); ++i) {
      const std::pair<Vec2, Vec2> seg{drawn_point(i), drawn_point(i + 1)};
      if (b.broken) {
        svg.segments({seg}, {"none", "#777777", 3 * line, 3 * line, 1});
        continue;
      }
      const double f = i + 1 < b.axial.size() ? 0.5 * (b.axial[i] + b.axial[i + 1]) : 0.0;
      svg.segments({seg}, {"none", bolt_colour(bolt_max > 0 ? f / bolt_max : 0.0), 4 * line, 0, 1});
    }
  }
  // Supports (rollers and pins along the boundary): a thick green line where they hold, with
  // what they hold ("x", "y", "xy") at the middle of their polyline. Drawn where the scene puts
  // them: a support holds its boundary still (to within its spring's give).
  for (const SupportDef& sp : scene.supports) {
    if (sp.points.size() < 2) continue;
    svg.polyline(sp.points, {"none", "#2ca02c", 4 * line, 0, 1});
    const std::size_t k = sp.points.size() / 2;
    const Vec2 a = sp.points[k - 1], b = sp.points[k];
    svg.text({0.5 * (a.x + b.x) + 0.3 * font, 0.5 * (a.y + b.y) + 0.3 * font},
             sp.fix_x && sp.fix_y ? "xy" : sp.fix_x ? "x" : "y", 0.8 * font, "#2ca02c");
  }
  // Fixed points: black triangles; measure points: magenta rings with their index.
  for (const Vec2& p : scene.fixed_points) {
    const double r = 0.012 * size;
    svg.polygon({{p.x, p.y}, {p.x - r, p.y - 1.6 * r}, {p.x + r, p.y - 1.6 * r}},
                {"#000000", "none", 0, 0, 1});
  }
  for (std::size_t i = 0; i < state.measure_points.size(); ++i) {
    Vec2 p = state.measure_points[i];
    if (factor != 1 && i < state.measure_start.size()) {
      const Vec2& s0 = state.measure_start[i];
      p = {s0.x + factor * (p.x - s0.x), s0.y + factor * (p.y - s0.y)};
    }
    svg.circle(p, 0.01 * size, {"none", "#ff00ff", 2.5 * line, 0, 1});
    svg.text({p.x + 0.013 * size, p.y + 0.008 * size}, "m" + std::to_string(i), font, "#ff00ff");
  }

  // Colour bar to the right of the model, labelled with units.
  const double bx = xmax + 0.05 * size, bw = 0.03 * size, by = ymin, bh = std::max(ymax - ymin, 0.3 * size) * 0.8;
  const int bands = 40;
  for (int i = 0; i < bands; ++i)
    svg.rect({bx, by + bh * i / bands}, bw, bh / bands + 1e-9 * size,
             {colour_map((i + 0.5) / bands), "none", 0, 0, 1});
  double right = bx + bw;  // the picture's right edge, for the wrapped text below
  for (int i = 0; i <= 4; ++i) {
    const double tick = lo + (hi - lo) * i / 4;
    const std::string label = format_rough(std::abs(tick) < 1e-12 ? 0.0 : tick, 3);  // not -0
    svg.text({bx + 1.3 * bw, by + bh * i / 4 - 0.3 * font}, label, font, "#000000");
    right = std::max(right, bx + 1.3 * bw + SvgWriter::text_width(label, font));
  }
  const std::string unit_title =
      field == PictureField::displacement ? "|u| (mm)"
      : field == PictureField::stress_xx  ? "σxx (MPa, tension +)"
      : field == PictureField::stress_yy  ? "σyy (MPa, tension +)"
      : field == PictureField::pressure   ? "water pressure in the joints (kPa)"
                                          : "τxy (MPa)";
  svg.text({bx, by + bh + 1.0 * font}, unit_title, font, "#000000");
  char note[160];
  if (field == PictureField::pressure)
    std::snprintf(note, sizeof note, "bar: the flow network's lowest to highest pressure, %zu segments",
                  state.flow.size());
  else
    std::snprintf(note, sizeof note, "bar: area-weighted %s; %.2g%% of area beyond it",
                  field == PictureField::displacement ? "0–99th pct" : "1st–99th pct",
                  total_area > 0 ? 100 * clamped_area / total_area : 0.0);
  svg.text({bx, by - 1.5 * font}, note, 0.7 * font, "#444444");
  right = std::max(right, bx + SvgWriter::text_width(note, 0.7 * font));

  // Axes in metres along the bottom and the left of the model, round ticks (drawn after the
  // colour bar, whose labels are the first numbers in the document).
  const double tick = 0.4 * font, label_font = 0.8 * font, gap = 0.03 * size;
  const SvgStyle axis_style{"none", "#444444", 0.8 * line, 0, 1};
  auto text_width = &SvgWriter::text_width;
  const double ax_y = ymin - gap, ax_x = xmin - gap;
  svg.polyline({{xmin, ax_y}, {xmax, ax_y}}, axis_style);
  for (double t : nice_ticks(xmin, xmax, 6)) {
    svg.polyline({{t, ax_y}, {t, ax_y - tick}}, axis_style);
    const std::string l = tick_label(t);
    svg.text({t - 0.5 * text_width(l, label_font), ax_y - tick - 1.1 * label_font}, l, label_font,
             "#444444");
  }
  svg.text({0.5 * (xmin + xmax) - 0.5 * text_width("x (m)", label_font),
            ax_y - tick - 2.4 * label_font},
           "x (m)", label_font, "#444444");
  svg.polyline({{ax_x, ymin}, {ax_x, ymax}}, axis_style);
  for (double t : nice_ticks(ymin, ymax, ymax - ymin > 0.3 * size ? 6 : 3)) {
    svg.polyline({{ax_x, t}, {ax_x - tick, t}}, axis_style);
    const std::string l = tick_label(t);
    svg.text({ax_x - tick - 0.3 * label_font - text_width(l, label_font), t - 0.35 * label_font}, l,
             label_font, "#444444");
  }
  svg.text({ax_x - text_width("y (m)", label_font), ymax + 0.8 * label_font}, "y (m)", label_font,
           "#444444");

  // Scale bar under the x axis, at its right end: a round length about a fifth of the model.
  const double bar_len = round_down_125(0.2 * (xmax - xmin > 0 ? xmax - xmin : size));
  const double sb_y = ax_y - tick - 4.4 * label_font, sb_h = 0.35 * font;
  svg.rect({xmax - bar_len, sb_y}, 0.5 * bar_len, sb_h, {"#000000", "#000000", 0.5 * line, 0, 1});
  svg.rect({xmax - 0.5 * bar_len, sb_y}, 0.5 * bar_len, sb_h, {"#ffffff", "#000000", 0.5 * line, 0, 1});
  const std::string bar_label = "scale bar " + tick_label(bar_len) + " m";
  svg.text({xmax - bar_len - 0.5 * font - text_width(bar_label, label_font), sb_y}, bar_label,
           label_font, "#000000");

  // Title and legend above the model; a failure's reason under the scale bar, wrapped.
  const bool failed = state.stop != StopCode::ok && state.stop != StopCode::interrupted;
  const std::string status_word = state.status.empty() ? "ok"
                                  : failed             ? "stopped, reason below"
                                                       : state.status;
  char scale[64];
  if (factor == 1)
    std::snprintf(scale, sizeof scale, "deformation true scale");
  else
    std::snprintf(scale, sizeof scale, factor >= 1 ? "displacement ×%.0f" : "displacement ×%g",
                  factor);
  char title[256];
  std::snprintf(title, sizeof title, "%s  t = %.4g s  (%s)  %s",
                !state.title.empty() ? state.title.c_str()
                : scene.name.empty() ? "scene"
                                     : scene.name.c_str(),
                state.time, status_word.c_str(), scale);
  svg.text({xmin, ymax + 4.2 * font}, title, 1.2 * font, "#000000");
  if (failed) {
    const double width = std::max(right, xmax) - ax_x;
    const double reason_font = 0.9 * font;
    double y = sb_y - 2.0 * reason_font;
    const std::size_t n = svg.text_block({ax_x, y}, "stopped: " + state.status, reason_font,
                                         "#b00000", width);
    y -= 1.3 * reason_font * static_cast<double>(n) + 0.4 * reason_font;
    const std::string cause = likely_failure_cause(mesh, scene, state.stop);
    if (!cause.empty())
      svg.text_block({ax_x, y}, "likely cause: " + cause, reason_font, "#202020", width);
  }

  // Legend: a swatch and a line per state, the counts a user checks against contacts.csv.
  char buf[200];
  double ly = ymax + 2.6 * font;
  // Entries one after the other; the text width is estimated (0.55 em per character), so the
  // next swatch starts after it whatever the counts.
  double lx = xmin;
  auto entry = [&](const std::string& colour, double width, const std::string& text) {
    svg.segments({{{lx, ly + 0.35 * font}, {lx + 1.5 * font, ly + 0.35 * font}}},
                 {"none", colour, width, 0, 1});
    svg.text({lx + 2 * font, ly}, text, 0.8 * font, "#333333");
    std::size_t chars = 0;
    for (unsigned char ch : text) chars += (ch & 0xC0) != 0x80;  // UTF-8 characters
    lx += 2 * font + 0.55 * 0.8 * font * static_cast<double>(chars) + 1.5 * font;
  };
  if (state.contacts_known) {
    std::snprintf(buf, sizeof buf, "sliding: %zu contacts along %.3g m", sliding, len.sliding);
    entry("#ff7f0e", 3 * line, buf);
    std::snprintf(buf, sizeof buf, "sticking: %zu contacts along %.3g m", sticking, len.sticking);
    entry("#1f77b4", 3 * line, buf);
    std::snprintf(buf, sizeof buf, "open joints: %.3g m", len.open);
    entry("#8b0000", 1.2 * line, buf);
    if (!state.joint_crack.empty()) {
      std::snprintf(buf, sizeof buf, "open tensile cracks: %.3g m", tensile_length);
      entry(kTensileCrack, 1.8 * line, buf);
      std::snprintf(buf, sizeof buf, "open shear cracks: %.3g m", shear_length);
      entry(kShearCrack, 1.8 * line, buf);
    }
  } else {
    entry("#888888", 1.2 * line,
          "joints: contact state not recorded at this step (contacts.csv sampled, --contacts-every)");
  }
  if (water_max > 0) {
    std::snprintf(buf, sizeof buf, "water pressure: light to dark cyan, up to %.3g kPa", water_max / 1e3);
    entry("#00bfe6", 7 * line, buf);
  }
  if (!state.bolts.empty()) {
    std::snprintf(buf, sizeof buf, "bolts: axial force, tension red, compression blue, darkest %.3g kN",
                  bolt_max / 1e3);
    entry(bolt_colour(1.0), 4 * line, buf);
  }
  ly -= 1.4 * font;
  std::string excavated_note;
  for (std::size_t b = 0; b < state.excavated_body.size(); ++b)
    if (state.excavated_body[b] != 0)
      excavated_note += (excavated_note.empty() ? "; excavated (dashed grey, not drawn): body " : ", ") +
                        std::to_string(b);
  std::string marks = "boundaries black";
  if (!scene.fixed_points.empty()) marks += "; ▲ fixed points";
  if (!scene.supports.empty()) marks += "; green: supports (x, y or xy held)";
  if (!state.measure_points.empty()) marks += "; ○ measure points";
  // A scene built in a tilted frame (a block on a plane as a horizontal plane under tilted
  // gravity) is drawn in that frame: say so, or the incline looks flat.
  if (scene.has_gravity && scene.gravity.x != 0) {
    char g[96];
    std::snprintf(g, sizeof g, "; gravity %.3g° from −y (model axes)",
                  std::atan2(std::abs(scene.gravity.x), -scene.gravity.y) * 180 / nmm::kPi);
    marks += g;
  }
  svg.text({xmin, ly}, marks + excavated_note, 0.8 * font, "#333333");
  return svg.str(0.03, 1400);
}

}  // namespace nmm::report
