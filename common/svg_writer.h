// A small SVG writer for pictures of meshes, and the mesh picture of `nmm-inspect --svg`.
//
// Shapes are given in model coordinates (m, +y up). The writer flips y itself (SVG's y axis
// points down) instead of using a scale(1,-1) transform, so text is not drawn upside down, and it
// fits the viewBox to everything drawn, plus a margin. Stroke widths and font sizes are in model
// units, so the caller picks them relative to the model (see write_mesh_svg); text is drawn at
// font size 100 scaled down to its size (a transform), which renderers lay out exactly.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"

namespace nmm {

/// Fill and stroke of a shape. Colours are any SVG colour ("#rrggbb", "none").
struct SvgStyle {
  std::string fill = "none";
  std::string stroke = "none";
  double stroke_width = 0;  ///< m (model units)
  double dash = 0;          ///< m, dash and gap length; 0 = solid
  double opacity = 1;       ///< fill opacity, in [0, 1]
};

class SvgWriter {
 public:
  /// Closed polygon through `pts` (not repeated at the end).
  void polygon(const std::vector<Vec2>& pts, const SvgStyle& style);
  /// Open polyline through `pts`.
  void polyline(const std::vector<Vec2>& pts, const SvgStyle& style);
  /// Many separate segments a→b in one <path>: one element instead of thousands keeps large
  /// meshes small and fast to render.
  void segments(const std::vector<std::pair<Vec2, Vec2>>& segs, const SvgStyle& style);
  void circle(Vec2 centre, double radius, const SvgStyle& style);
  /// Axis-aligned rectangle with lower-left corner `lo`, m.
  void rect(Vec2 lo, double width, double height, const SvgStyle& style);
  /// Text with its baseline starting at `at`; `size` is the font size in m.
  void text(Vec2 at, const std::string& text, double size, const std::string& colour);
  /// The width the writer reserves for `text` at font size `size` (0.6 em per character), m.
  static double text_width(const std::string& text, double size);
  /// `text` wrapped at word boundaries to lines no wider than `width` (m, at the writer's
  /// estimate of 0.6 em per character), the first baseline at `at`, the next ones 1.3 em below.
  /// Returns the number of lines.
  std::size_t text_block(Vec2 at, const std::string& text, double size, const std::string& colour,
                         double width);

  /// The document: the viewBox is the bounding box of everything drawn, widened by
  /// `margin_fraction` of its larger side; `pixel_width` sets the width attribute.
  std::string str(double margin_fraction = 0.03, double pixel_width = 1000) const;

  bool empty() const { return shapes_.empty(); }

 private:
  // Shapes are kept unserialised until str(): the number of decimals printed depends on the
  // extent of the whole picture, which is known only at the end.
  enum class Kind { polygon, polyline, segments, circle, rect, text };
  struct Shape {
    Kind kind;
    std::vector<Vec2> pts;  // segments: pairs a, b; circle: centre; rect: lo, (w, h); text: at
    SvgStyle style;
    double size = 0;   // circle radius or font size, m
    std::string text;  // text: the string; also its colour in style.fill
  };
  void extend(double x, double y);

  std::vector<Shape> shapes_;
  double xmin_ = 0, xmax_ = 0, ymin_ = 0, ymax_ = 0;
  bool have_box_ = false;
};

/// `text` split at spaces into lines of at most `max_chars` characters (UTF-8 code points); a
/// word longer than that gets a line of its own.
std::vector<std::string> wrap_words(const std::string& text, std::size_t max_chars);

/// Colour of block b in the mesh picture: a fixed pastel palette cycled by block index, so the
/// same mesh always gives the same picture.
std::string block_colour(std::size_t block);

/// Fill of the elements of the highlighted physical cover (strong, not in the block palette).
inline constexpr const char* kSvgHighlightColour = "#ff00ff";

/// The mesh picture: mathematical triangles thin light grey; elements filled per block; loop
/// edges on joints red, on body boundaries black and thicker; the scene's joints (when `scene`
/// is given) as thin dark-red dashed polylines, so parts outside every body show too; with
/// highlight_cover >= 0 that cover's elements in kSvgHighlightColour and its node marked; a
/// title with the scene name and counts. Throws InputError if highlight_cover is out of range.
std::string mesh_svg(const Mesh& mesh, const SceneDef* scene, int highlight_cover);

/// mesh_svg written atomically to `path`.
void write_mesh_svg(const Mesh& mesh, const SceneDef* scene, int highlight_cover,
                    const std::string& path);

}  // namespace nmm
