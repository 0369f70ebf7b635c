#include "common/svg_writer.h"

#include "common/xml_text.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include "common/error.h"
#include "common/atomic_file.h"
#include "common/number_format.h"

namespace nmm {

namespace {


// Code points, not bytes: used to guess how wide a text line is.
std::size_t utf8_length(const std::string& s) {
  std::size_t n = 0;
  for (char c : s)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
  return n;
}

// Fixed-point with `decimals` digits, trailing zeros trimmed: short, and exact enough at the
// picture's scale.
std::string fmt(double v, int decimals) {
  std::string s = format_fixed(v, decimals);
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

}  // namespace

void SvgWriter::extend(double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  if (!have_box_) {
    xmin_ = xmax_ = x;
    ymin_ = ymax_ = y;
    have_box_ = true;
    return;
  }
  xmin_ = std::min(xmin_, x);
  xmax_ = std::max(xmax_, x);
  ymin_ = std::min(ymin_, y);
  ymax_ = std::max(ymax_, y);
}

void SvgWriter::polygon(const std::vector<Vec2>& pts, const SvgStyle& style) {
  for (const Vec2& p : pts) extend(p.x, p.y);
  shapes_.push_back({Kind::polygon, pts, style, 0, {}});
}

void SvgWriter::polyline(const std::vector<Vec2>& pts, const SvgStyle& style) {
  for (const Vec2& p : pts) extend(p.x, p.y);
  shapes_.push_back({Kind::polyline, pts, style, 0, {}});
}

void SvgWriter::segments(const std::vector<std::pair<Vec2, Vec2>>& segs, const SvgStyle& style) {
  if (segs.empty()) return;
  Shape s{Kind::segments, {}, style, 0, {}};
  s.pts.reserve(2 * segs.size());
  for (const auto& [a, b] : segs) {
    extend(a.x, a.y);
    extend(b.x, b.y);
    s.pts.push_back(a);
    s.pts.push_back(b);
  }
  shapes_.push_back(std::move(s));
}

void SvgWriter::circle(Vec2 centre, double radius, const SvgStyle& style) {
  extend(centre.x - radius, centre.y - radius);
  extend(centre.x + radius, centre.y + radius);
  shapes_.push_back({Kind::circle, {centre}, style, radius, {}});
}

void SvgWriter::rect(Vec2 lo, double width, double height, const SvgStyle& style) {
  extend(lo.x, lo.y);
  extend(lo.x + width, lo.y + height);
  shapes_.push_back({Kind::rect, {lo, Vec2{width, height}}, style, 0, {}});
}

void SvgWriter::text(Vec2 at, const std::string& text, double size, const std::string& colour) {
  // The box must hold the text too; 0.6 em per character is a fair guess for sans-serif.
  extend(at.x, at.y - 0.25 * size);
  extend(at.x + text_width(text, size), at.y + size);
  SvgStyle st;
  st.fill = colour;
  shapes_.push_back({Kind::text, {at}, st, size, text});
}

double SvgWriter::text_width(const std::string& text, double size) {
  return 0.6 * size * static_cast<double>(utf8_length(text));
}

std::size_t SvgWriter::text_block(Vec2 at, const std::string& text, double size,
                                  const std::string& colour, double width) {
  const auto chars = static_cast<std::size_t>(std::max(1.0, std::floor(width / (0.6 * size))));
  const std::vector<std::string> lines = wrap_words(text, chars);
  for (std::size_t i = 0; i < lines.size(); ++i)
    this->text({at.x, at.y - 1.3 * size * static_cast<double>(i)}, lines[i], size, colour);
  return lines.size();
}

std::vector<std::string> wrap_words(const std::string& text, std::size_t max_chars) {
  std::vector<std::string> lines;
  std::string line, word;
  auto flush_word = [&] {
    if (word.empty()) return;
    if (!line.empty() && utf8_length(line) + 1 + utf8_length(word) > max_chars) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    word.clear();
  };
  for (char c : text) {
    if (c == ' ' || c == '\n') flush_word();
    else word += c;
  }
  flush_word();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string SvgWriter::str(double margin_fraction, double pixel_width) const {
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (have_box_) {
    x0 = xmin_, x1 = xmax_, y0 = ymin_, y1 = ymax_;
  }
  double extent = std::max(x1 - x0, y1 - y0);
  if (!(extent > 0)) extent = std::max(1.0, std::abs(x0));  // a single point still gets a box
  const double margin = margin_fraction * extent;
  x0 -= margin, x1 += margin, y0 -= margin, y1 += margin;
  if (x1 - x0 < extent * 1e-3) x0 -= extent * 0.5, x1 += extent * 0.5;
  if (y1 - y0 < extent * 1e-3) y0 -= extent * 0.5, y1 += extent * 0.5;

  // About 1e-6 of the extent: far below a pixel, and short numbers.
  const int decimals = std::clamp(6 - static_cast<int>(std::floor(std::log10(extent))), 0, 15);
  auto num = [&](double v) { return fmt(v, decimals); };
  // y is flipped here, once: model +y up becomes SVG -y.
  auto xy = [&](const Vec2& p) { return num(p.x) + "," + num(-p.y); };
  auto style = [&](const SvgStyle& s) {
    std::string a = " fill=\"" + s.fill + "\"";
    if (s.fill != "none" && s.opacity < 1) a += " fill-opacity=\"" + fmt(s.opacity, 3) + "\"";
    a += " stroke=\"" + s.stroke + "\"";
    if (s.stroke != "none") {
      a += " stroke-width=\"" + num(s.stroke_width) + "\"";
      if (s.dash > 0) a += " stroke-dasharray=\"" + num(s.dash) + " " + num(s.dash) + "\"";
    }
    return a;
  };

  const double w = x1 - x0, h = y1 - y0;
  std::string out;
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" +
         fmt(pixel_width, 0) + "\" height=\"" + fmt(pixel_width * h / w, 0) + "\" viewBox=\"" +
         num(x0) + " " + num(-y1) + " " + num(w) + " " + num(h) + "\"" +
         " stroke-linejoin=\"round\" stroke-linecap=\"round\">\n";
  out += "<rect x=\"" + num(x0) + "\" y=\"" + num(-y1) + "\" width=\"" + num(w) + "\" height=\"" +
         num(h) + "\" fill=\"white\"/>\n";
  for (const Shape& s : shapes_) {
    switch (s.kind) {
      case Kind::polygon:
      case Kind::polyline: {
        out += s.kind == Kind::polygon ? "<polygon points=\"" : "<polyline points=\"";
        for (std::size_t i = 0; i < s.pts.size(); ++i) {
          if (i) out += ' ';
          out += xy(s.pts[i]);
        }
        out += "\"" + style(s.style) + "/>\n";
        break;
      }
      case Kind::segments: {
        out += "<path d=\"";
        for (std::size_t i = 0; i + 1 < s.pts.size(); i += 2) {
          if (i) out += ' ';
          out += "M" + xy(s.pts[i]) + "L" + xy(s.pts[i + 1]);
        }
        out += "\"" + style(s.style) + "/>\n";
        break;
      }
      case Kind::circle:
        out += "<circle cx=\"" + num(s.pts[0].x) + "\" cy=\"" + num(-s.pts[0].y) + "\" r=\"" +
               num(s.size) + "\"" + style(s.style) + "/>\n";
        break;
      case Kind::rect:
        out += "<rect x=\"" + num(s.pts[0].x) + "\" y=\"" + num(-(s.pts[0].y + s.pts[1].y)) +
               "\" width=\"" + num(s.pts[1].x) + "\" height=\"" + num(s.pts[1].y) + "\"" +
               style(s.style) + "/>\n";
        break;
      case Kind::text: {
        // The font is set at 100 units and scaled down to its size in model units: a font
        // size of 0.1 (a 5 m model) is laid out by Pango (rsvg-convert) in whole 1/1024 pt
        // steps, which garbles the letter spacing; at 100 the layout is exact.
        out += "<text transform=\"translate(" + num(s.pts[0].x) + "," + num(-s.pts[0].y) +
               ") scale(" + format_rough(s.size / 100, 6) + ")\" font-size=\"100\" font-family=\"sans-serif\" fill=\"" +
               s.style.fill + "\">" + xml_escape(s.text) + "</text>\n";
        break;
      }
    }
  }
  out += "</svg>\n";
  return out;
}

std::string block_colour(std::size_t block) {
  // ColorBrewer Set3 without its grey (the mesh lines are grey): light enough that the red
  // joint and black boundary lines stay readable on top, distinct enough for neighbours.
  static const char* const kPalette[] = {"#8dd3c7", "#ffffb3", "#bebada", "#fb8072",
                                         "#80b1d3", "#fdb462", "#b3de69", "#fccde5",
                                         "#bc80bd", "#ccebc5", "#ffed6f"};
  constexpr std::size_t n = sizeof kPalette / sizeof kPalette[0];
  return kPalette[block % n];
}

std::string mesh_svg(const Mesh& mesh, const SceneDef* scene, int highlight_cover) {
  if (highlight_cover >= 0 && static_cast<std::size_t>(highlight_cover) >= mesh.cover_count())
    throw InputError("", "--cover",
                     "physical cover " + std::to_string(highlight_cover) +
                         " does not exist (the "
                         "mesh has " +
                         std::to_string(mesh.cover_count()) + " physical covers)");

  auto node = [&](std::int32_t n) {
    const auto i = static_cast<std::size_t>(n);
    return Vec2{mesh.node_xy[2 * i], mesh.node_xy[2 * i + 1]};
  };
  auto loop_pt = [&](std::size_t v) { return Vec2{mesh.loop_xy[2 * v], mesh.loop_xy[2 * v + 1]}; };

  // Extent of the model, to size lines and text before anything is drawn.
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  bool any = false;
  auto grow = [&](Vec2 p) {
    if (!any) x0 = x1 = p.x, y0 = y1 = p.y, any = true;
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  };
  for (std::size_t i = 0; i < mesh.node_count(); ++i) grow(node(static_cast<std::int32_t>(i)));
  for (std::size_t v = 0; v < mesh.loop_vertex_count(); ++v) grow(loop_pt(v));
  if (scene)
    for (const JointDef& j : scene->joints)
      for (const Vec2& p : j.points) grow(p);
  double extent = std::max(x1 - x0, y1 - y0);
  if (!(extent > 0)) extent = mesh.mesh_size > 0 ? mesh.mesh_size : 1.0;
  const double h = mesh.mesh_size > 0 ? mesh.mesh_size : extent / 20;

  // Line widths: a fixed share of the picture (px ≈ one pixel of a 1000 px wide picture), so a
  // 100 m and a 1 m model look alike, but capped by a share of the mesh size, so on a coarse
  // picture of a fine mesh the lines never bury the triangles.
  const double px = extent / 1000;
  const double w_tri = std::min(0.6 * px, 0.03 * h);
  const double w_scene_joint = std::min(1.0 * px, 0.05 * h);
  const double w_joint = std::min(2.0 * px, 0.10 * h);
  const double w_boundary = std::min(3.0 * px, 0.15 * h);

  SvgWriter svg;

  // Which elements belong to the highlighted cover: their fill changes, so the picture still
  // holds exactly one <polygon> per element.
  std::vector<char> lit(mesh.element_count(), 0);
  if (highlight_cover >= 0)
    for (std::size_t i = 0; i < mesh.element_covers.size(); ++i)
      if (mesh.element_covers[i] == highlight_cover) lit[i / 3] = 1;

  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const auto b = static_cast<std::size_t>(mesh.element_loop_offset[e]);
    const auto end = static_cast<std::size_t>(mesh.element_loop_offset[e + 1]);
    std::vector<Vec2> pts;
    pts.reserve(end - b);
    for (std::size_t v = b; v < end; ++v) pts.push_back(loop_pt(v));
    SvgStyle st;
    st.fill = lit[e] ? std::string(kSvgHighlightColour)
                     : block_colour(static_cast<std::size_t>(std::max(0, mesh.element_block[e])));
    // A hairline in the fill colour hides the anti-aliasing seams between neighbours.
    st.stroke = st.fill;
    st.stroke_width = w_tri;
    svg.polygon(pts, st);
  }

  // Mathematical triangles, each shared edge once, on top of the fills so the mesh shows.
  {
    std::set<std::pair<std::int32_t, std::int32_t>> edges;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
      for (int k = 0; k < 3; ++k) {
        std::int32_t a = mesh.triangle_nodes[3 * t + static_cast<std::size_t>(k)];
        std::int32_t b = mesh.triangle_nodes[3 * t + static_cast<std::size_t>((k + 1) % 3)];
        edges.insert({std::min(a, b), std::max(a, b)});
      }
    std::vector<std::pair<Vec2, Vec2>> segs;
    segs.reserve(edges.size());
    for (const auto& [a, b] : edges) segs.push_back({node(a), node(b)});
    SvgStyle st;
    st.stroke = "#c0c0c0";
    st.stroke_width = w_tri;
    svg.segments(segs, st);
  }

  // The scene's joints under the element edges: where a joint crosses a body the red loop edges
  // cover it, and the dashes show only where it runs outside every body.
  if (scene) {
    SvgStyle st;
    st.stroke = "#8b0000";
    st.stroke_width = w_scene_joint;
    st.dash = 6 * w_scene_joint;
    for (const JointDef& j : scene->joints) svg.polyline(j.points, st);
  }

  // Loop edges on body boundaries (black, thick), then on joints (red, on top, so a joint
  // running along a boundary still shows). Bridges have zero width and are not drawn.
  {
    std::vector<std::pair<Vec2, Vec2>> boundary, joint;
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
      const auto b = static_cast<std::size_t>(mesh.element_loop_offset[e]);
      const auto end = static_cast<std::size_t>(mesh.element_loop_offset[e + 1]);
      for (std::size_t v = b; v < end; ++v) {
        const std::uint8_t o = mesh.loop_edge_origin[v];
        if (o & kEdgeBridge) continue;
        const std::size_t next = v + 1 < end ? v + 1 : b;
        if (o & kEdgeBoundary) boundary.push_back({loop_pt(v), loop_pt(next)});
        if (o & kEdgeJoint) joint.push_back({loop_pt(v), loop_pt(next)});
      }
    }
    SvgStyle st;
    st.stroke = "#000000";
    st.stroke_width = w_boundary;
    svg.segments(boundary, st);
    st.stroke = "#e00000";
    st.stroke_width = w_joint;
    svg.segments(joint, st);
  }

  // The highlighted cover: its mathematical cover (the star of its node) outlined, its node
  // marked with a dot large enough to find on a fine mesh.
  std::int32_t lit_node = -1;
  if (highlight_cover >= 0) {
    lit_node = mesh.cover_node[static_cast<std::size_t>(highlight_cover)];
    std::vector<std::pair<Vec2, Vec2>> star;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const std::int32_t* tn = &mesh.triangle_nodes[3 * t];
      for (int k = 0; k < 3; ++k)
        if (tn[k] == lit_node) star.push_back({node(tn[(k + 1) % 3]), node(tn[(k + 2) % 3])});
    }
    SvgStyle st;
    st.stroke = kSvgHighlightColour;
    st.stroke_width = w_joint;
    st.dash = 3 * w_joint;
    svg.segments(star, st);
    SvgStyle dot;
    dot.fill = kSvgHighlightColour;
    dot.stroke = "#000000";
    dot.stroke_width = w_joint / 2;
    svg.circle(node(lit_node), std::max(0.12 * h, 4 * px), dot);
  }

  // Title and key above the drawing, sized to the picture: the key just above the model, the
  // text lines above it, the title on top.
  const double fs = 0.022 * extent;
  const double line = 1.4 * fs;
  {
    double kx = x0;
    const double ky = y1 + 1.0 * fs;
    auto key = [&](const std::string& colour, double width, bool dashed, const std::string& label) {
      SvgStyle st;
      st.stroke = colour;
      st.stroke_width = std::max(width, 0.15 * fs);
      st.dash = dashed ? 0.4 * fs : 0;
      svg.polyline({{kx, ky}, {kx + 2 * fs, ky}}, st);
      svg.text({kx + 2.4 * fs, ky - 0.3 * fs}, label, fs, "#202020");
      kx += 2.4 * fs + 0.6 * fs * static_cast<double>(utf8_length(label)) + 1.5 * fs;
    };
    // Only the line kinds the picture holds, so the key does not promise what is not there.
    bool joint_edges = false;
    for (std::uint8_t o : mesh.loop_edge_origin) joint_edges = joint_edges || (o & kEdgeJoint);
    if (joint_edges) key("#e00000", w_joint, false, "joint");
    key("#000000", w_boundary, false, "body boundary");
    if (scene && !scene->joints.empty()) key("#8b0000", w_scene_joint, true, "scene joint");
    key("#c0c0c0", w_tri, false, "triangle");
    if (highlight_cover >= 0) key(kSvgHighlightColour, w_joint, true, "highlighted cover");
  }
  std::vector<std::string> lines;
  std::string title = scene && !scene->name.empty() ? scene->name : mesh.scene_file;
  if (title.empty()) title = "mesh";
  lines.push_back(title + "  (mesh size " + format_rough(mesh.mesh_size, 6) + " m)");
  lines.push_back(
      std::to_string(mesh.node_count()) + " nodes, " + std::to_string(mesh.triangle_count()) +
      " triangles, " + std::to_string(mesh.cover_count()) + " physical covers, " +
      std::to_string(mesh.element_count()) + " elements, " + std::to_string(mesh.block_count()) +
      " blocks" + (scene ? ", " + std::to_string(scene->joints.size()) + " joints" : ""));
  if (highlight_cover >= 0)
    lines.push_back("physical cover " + std::to_string(highlight_cover) + " (node " +
                    std::to_string(lit_node) + ", body " +
                    std::to_string(mesh.cover_body[static_cast<std::size_t>(highlight_cover)]) +
                    ") highlighted");
  double ty = y1 + 1.0 * fs + line;
  // Drawn bottom-up so the first line ends up on top.
  for (auto it = lines.rbegin(); it != lines.rend(); ++it, ty += line)
    svg.text({x0, ty}, *it, fs, "#202020");
  return svg.str();
}

void write_mesh_svg(const Mesh& mesh, const SceneDef* scene, int highlight_cover,
                    const std::string& path) {
  write_file_atomically(path, mesh_svg(mesh, scene, highlight_cover));
}

}  // namespace nmm
