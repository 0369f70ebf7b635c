// Joint network statistics and pictures; definitions at the top of network_report.h.
#include "preprocess/network_report.h"

#include <algorithm>
#include <cmath>

#include "preprocess/joint_network.h"
#include "common/math_constants.h"
#include "common/number_format.h"
#include "common/ring_geometry.h"
#include "common/svg_plot.h"
#include "common/svg_writer.h"

namespace nmm::pre {

namespace {

constexpr int kScanlines = 50;
constexpr int kRoseBins = 18;  // 10° each over [0°, 180°)

double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
double dist(Vec2 a, Vec2 b) { return std::hypot(b.x - a.x, b.y - a.y); }

/// Parameter along a–b of its crossing with c–d, or -1 (parallel or no crossing).
double crossing(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const Vec2 r = sub(b, a), s = sub(d, c);
  const double den = cross(r, s);
  if (den == 0) return -1;
  const Vec2 ca = sub(c, a);
  const double t = cross(ca, s) / den, u = cross(ca, r) / den;
  if (t < 0 || t > 1 || u < 0 || u > 1) return -1;
  return t;
}

// Six significant digits throughout the report.
std::string num(double v) { return format_rough(v, 6); }

Ring bodies_box_ring(const SceneDef& scene) {
  if (scene.bodies.empty()) return {};
  return box_ring(bodies_box(scene.bodies));
}

}  // namespace

double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0;
  const double r = std::clamp(p, 0.0, 1.0) * static_cast<double>(sorted.size() - 1);
  const std::size_t i = static_cast<std::size_t>(std::floor(r));
  if (i + 1 >= sorted.size()) return sorted.back();
  return sorted[i] + (r - static_cast<double>(i)) * (sorted[i + 1] - sorted[i]);
}

SampleStats sample_stats(std::vector<double> v) {
  SampleStats s;
  s.count = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  for (double x : v) s.total += x;
  s.mean = s.total / static_cast<double>(v.size());
  double ss = 0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  // Sample standard deviation (n − 1); 0 for a single value.
  s.std_dev = v.size() > 1 ? std::sqrt(ss / static_cast<double>(v.size() - 1)) : 0;
  s.min = v.front();
  s.max = v.back();
  s.median = percentile(v, 0.5);
  return s;
}

std::vector<JointSetNetworkReport> joint_set_reports(const SceneDef& scene) {
  std::vector<JointSetNetworkReport> out;
  const Ring box = bodies_box_ring(scene);
  if (box.empty()) return out;
  for (std::size_t si = 0; si < scene.joint_sets.size(); ++si) {
    const JointSetDef& set = scene.joint_sets[si];
    JointSetNetworkReport r;
    r.name = set.name;
    r.generated = set.generated || set.expanded;
    const JointGenerationDef& g = set.generate;
    if (r.generated) {
      // As the generator reads it (joint_network.cpp): without p21, P21 = 1 / mean spacing
      // (spacing sets are then persistent).
      r.requested_p21 = g.p21 > 0 ? g.p21 : 1 / g.mean_spacing;
    }
    // Measuring domain: a generated set's own region ∩ the box (where the generator meets its
    // request); a set typed by hand: the rock itself, the bodies without their holes.
    const Ring region = r.generated && !g.region.empty() ? g.region : box;
    const bool by_bodies = !r.generated;
    auto inside = [&](Vec2 a, Vec2 b) {
      std::vector<std::pair<Vec2, Vec2>> pieces;
      if (!by_bodies) {
        for (const auto& p : clip_segment_to_polygon(a, b, region))
          for (const auto& q : clip_segment_to_polygon(p.first, p.second, box)) pieces.push_back(q);
        return pieces;
      }
      for (const BodyDef& body : scene.bodies)
        for (const auto& p : clip_segment_to_polygon(a, b, body.outer)) {
          // Subtract the holes: cut p at every hole piece and keep the rest.
          std::vector<std::pair<double, double>> gone;  // parameter ranges along p inside holes
          const double len = dist(p.first, p.second);
          if (len <= 0) continue;
          for (const Ring& hole : body.holes)
            for (const auto& h : clip_segment_to_polygon(p.first, p.second, hole))
              gone.emplace_back(dist(p.first, h.first) / len, dist(p.first, h.second) / len);
          std::sort(gone.begin(), gone.end());
          double t = 0;
          auto at = [&](double u) {
            return Vec2{p.first.x + u * (p.second.x - p.first.x),
                        p.first.y + u * (p.second.y - p.first.y)};
          };
          for (const auto& [u0, u1] : gone) {
            if (u0 > t) pieces.emplace_back(at(t), at(u0));
            t = std::max(t, u1);
          }
          if (t < 1) pieces.emplace_back(at(t), p.second);
        }
      return pieces;
    };
    if (by_bodies) {
      for (const BodyDef& body : scene.bodies) r.region_area += body_area(body);
    } else {
      r.region_area = std::abs(
          ring_signed_area(clip_polygon_to_box(region, box[0].x, box[0].y, box[2].x, box[2].y)));
    }

    // The set's segments, clipped to the measuring region and the box.
    std::vector<std::pair<Vec2, Vec2>> segs;
    double inside_length = 0, sx = 0, sy = 0;
    for (const JointDef& j : scene.joints) {
      if (j.set != static_cast<int>(si)) continue;
      double len = 0;
      for (std::size_t k = 0; k + 1 < j.points.size(); ++k) {
        const Vec2 a = j.points[k], b = j.points[k + 1];
        len += dist(a, b);
        double th = std::atan2(b.y - a.y, b.x - a.x);
        if (th < 0) th += kPi;
        if (th >= kPi) th -= kPi;
        r.angles_deg.push_back(th * 180 / kPi);
        r.angle_weights.push_back(dist(a, b));
        for (const auto& q : inside(a, b)) {
          segs.push_back(q);
          const double l = dist(q.first, q.second);
          inside_length += l;
          sx += l * std::cos(2 * th);
          sy += l * std::sin(2 * th);
        }
      }
      r.lengths.push_back(len);
    }
    r.trace_lengths = sample_stats(r.lengths);
    r.measured_p21 = r.region_area > 0 ? inside_length / r.region_area : 0;
    // Axial mean, shown in [0°, 180°), or for a generated set within ±90° of its request.
    const double ref = r.generated ? g.mean_angle_deg : 90.0;
    r.requested_angle_deg = ref;
    if (inside_length > 0) {
      r.mean_angle_deg = 0.5 * std::atan2(sy, sx) * 180 / kPi;
      r.resultant_length = std::hypot(sx, sy) / inside_length;
    } else {
      r.mean_angle_deg = ref;
    }
    while (r.mean_angle_deg < ref - 90) r.mean_angle_deg += 180;
    while (r.mean_angle_deg >= ref + 90) r.mean_angle_deg -= 180;
    const double th0 = r.mean_angle_deg * kPi / 180;
    const Vec2 d{std::cos(th0), std::sin(th0)}, n{-d.y, d.x};
    r.scanline_angle_deg = std::fmod(r.mean_angle_deg + 90 + 720, 180.0);  // in [0, 180)
    double cos_sum = 0;
    for (const auto& s : segs) {
      const Vec2 v = sub(s.second, s.first);
      cos_sum += std::abs(v.x * d.x + v.y * d.y);  // L |cos(θ − θ̄)|
    }
    r.p10_expected = r.region_area > 0 ? cos_sum / r.region_area : 0;

    // Scanlines along n, spread evenly across the region along d: the region's box in the
    // frame (d, n).
    std::vector<Vec2> extent = region;
    if (by_bodies) {
      extent.clear();
      for (const BodyDef& body : scene.bodies)
        extent.insert(extent.end(), body.outer.begin(), body.outer.end());
    }
    Box frame = Box::empty();
    for (const Vec2& p : extent) frame.add(p.x * d.x + p.y * d.y, p.x * n.x + p.y * n.y);
    const double d0 = frame.x0, d1 = frame.x1;
    const double n0 = frame.y0 - 1, n1 = frame.y1 + 1;  // lines start and end outside the region;
                                                        // clipping trims them
    r.scanlines = kScanlines;
    double gap_sum = 0;
    for (int k = 0; k < kScanlines; ++k) {
      const double off = d0 + (k + 0.5) * (d1 - d0) / kScanlines;
      const Vec2 a{off * d.x + n0 * n.x, off * d.y + n0 * n.y};
      const Vec2 b{off * d.x + n1 * n.x, off * d.y + n1 * n.y};
      for (const auto& q : inside(a, b)) {
        const double len = dist(q.first, q.second);
        r.scanline_length += len;
        std::vector<double> ts;
        for (const auto& s : segs) {
          const double t = crossing(q.first, q.second, s.first, s.second);
          if (t >= 0) ts.push_back(t * len);
        }
        std::sort(ts.begin(), ts.end());
        r.crossings += ts.size();
        for (std::size_t i = 1; i < ts.size(); ++i) {
          gap_sum += ts[i] - ts[i - 1];
          ++r.spacings;
        }
      }
    }
    r.p10 = r.scanline_length > 0 ? static_cast<double>(r.crossings) / r.scanline_length : 0;
    r.mean_spacing = r.spacings > 0 ? gap_sum / static_cast<double>(r.spacings) : 0;
    out.push_back(std::move(r));
  }
  return out;
}

NetworkReport network_report(const Mesh& mesh, const SceneDef& scene) {
  NetworkReport rep;
  rep.sets = joint_set_reports(scene);
  rep.blocks = mesh.block_count();
  std::vector<double> area(mesh.block_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::int32_t b = mesh.element_block[e];
    if (b >= 0 && static_cast<std::size_t>(b) < area.size()) area[b] += element_area(mesh, e);
  }
  std::sort(area.begin(), area.end());
  for (double a : area) rep.block_area_total += a;
  if (!area.empty()) rep.block_area_mean = rep.block_area_total / static_cast<double>(area.size());
  rep.block_areas = std::move(area);
  return rep;
}

nlohmann::json network_report_json(const NetworkReport& rep) {
  nlohmann::json sets = nlohmann::json::array();
  for (const auto& r : rep.sets) {
    const SampleStats& t = r.trace_lengths;
    sets.push_back({
        {"name", r.name},
        {"generated", r.generated},
        {"requested_p21", r.generated ? nlohmann::json(r.requested_p21) : nlohmann::json()},
        {"measured_p21", r.measured_p21},
        {"region_area", r.region_area},
        {"mean_angle_deg", r.mean_angle_deg},
        {"requested_mean_angle_deg",
         r.generated ? nlohmann::json(r.requested_angle_deg) : nlohmann::json()},
        {"resultant_length", r.resultant_length},
        {"scanlines", {{"count", r.scanlines}, {"angle_deg", r.scanline_angle_deg},
                       {"length", r.scanline_length}, {"crossings", r.crossings}}},
        {"p10", r.p10},
        {"p10_expected", r.p10_expected},
        {"mean_spacing", r.spacings > 0 ? nlohmann::json(r.mean_spacing) : nlohmann::json()},
        {"trace_length", {{"count", t.count}, {"total", t.total}, {"mean", t.mean},
                          {"median", t.median}, {"min", t.min}, {"max", t.max},
                          {"std", t.std_dev}}},
    });
  }
  const auto& a = rep.block_areas;
  nlohmann::json blocks = {{"count", rep.blocks},
                           {"total_area", rep.block_area_total},
                           {"mean_area", rep.block_area_mean}};
  nlohmann::json pct = nlohmann::json::object();
  for (int p : {0, 5, 10, 25, 50, 75, 90, 95, 100})
    pct["p" + std::to_string(p)] = percentile(a, p / 100.0);
  blocks["area_percentiles"] = pct;
  return {{"joint_sets", sets}, {"blocks", blocks}};
}

std::string network_report_text(const NetworkReport& rep) {
  std::string s = "joint network:\n";
  for (const auto& r : rep.sets) {
    const SampleStats& t = r.trace_lengths;
    s += "  set " + r.name + ": " + std::to_string(t.count) + " joints";
    s += r.generated ? " (generated)\n" : "\n";
    s += "    P21 " + num(r.measured_p21) + " m/m² measured";
    if (r.generated) s += ", " + num(r.requested_p21) + " requested";
    s += " (region " + num(r.region_area) + " m²)\n";
    s += "    orientation: mean " + num(r.mean_angle_deg) + "°";
    if (r.generated) s += " (" + num(r.requested_angle_deg) + "° requested)";
    s += ", resultant length " + num(r.resultant_length) + "\n";
    s += "    P10 " + num(r.p10) + " 1/m on " + std::to_string(r.scanlines) +
         " scanlines at " + num(r.scanline_angle_deg) + "° (normal to the set), " +
         std::to_string(r.crossings) + " crossings over " + num(r.scanline_length) +
         " m; expected from P21 " + num(r.p10_expected) + " 1/m\n";
    s += "    mean spacing " + (r.spacings > 0 ? num(r.mean_spacing) + " m" : std::string("-")) +
         " (" + std::to_string(r.spacings) + " gaps)\n";
    s += "    trace length (m): mean " + num(t.mean) + ", median " + num(t.median) + ", min " +
         num(t.min) + ", max " + num(t.max) + ", std " + num(t.std_dev) + "\n";
  }
  const auto& a = rep.block_areas;
  s += "  blocks: " + std::to_string(rep.blocks) + ", area (m²): mean " +
       num(rep.block_area_mean) + ", p10 " + num(percentile(a, 0.1)) + ", p50 " +
       num(percentile(a, 0.5)) + ", p90 " + num(percentile(a, 0.9)) + ", max " +
       num(percentile(a, 1.0)) + "\n";
  return s;
}

std::string set_colour(std::size_t set) {
  static const char* const kColours[] = {"#d62728", "#1f77b4", "#2ca02c", "#ff7f0e",
                                         "#9467bd", "#8c564b", "#e377c2", "#17becf"};
  return kColours[set % (sizeof kColours / sizeof kColours[0])];
}

std::string rose_svg(const NetworkReport& rep) {
  SvgWriter svg;
  const double R = 1.0, pitch = 2.8 * R;
  std::size_t panel = 0;
  for (std::size_t si = 0; si < rep.sets.size(); ++si) {
    const auto& r = rep.sets[si];
    if (r.angles_deg.empty()) continue;
    const Vec2 c{pitch * static_cast<double>(panel++), 0};
    std::vector<int> bins(kRoseBins, 0);
    for (double a : r.angles_deg)
      ++bins[std::min(kRoseBins - 1, static_cast<int>(a / (180.0 / kRoseBins)))];
    const int most = *std::max_element(bins.begin(), bins.end());
    std::vector<Vec2> rim;
    for (int k = 0; k <= 72; ++k)
      rim.push_back({c.x + R * std::cos(k * kPi / 36), c.y + R * std::sin(k * kPi / 36)});
    rim.pop_back();
    svg.polygon(rim, {"none", "#999999", 0.01, 0, 1});
    svg.segments({{{c.x - R, c.y}, {c.x + R, c.y}}, {{c.x, c.y - R}, {c.x, c.y + R}}},
                 {"none", "#cccccc", 0.005, 0, 1});
    SvgStyle wedge{set_colour(si), "#333333", 0.004, 0, 0.8};
    for (int k = 0; k < kRoseBins; ++k) {
      if (bins[k] == 0) continue;
      const double rr = R * bins[k] / most;
      for (double turn : {0.0, kPi}) {  // θ and θ + 180°
        const double a0 = k * kPi / kRoseBins + turn, a1 = (k + 1) * kPi / kRoseBins + turn;
        std::vector<Vec2> w = {c};
        for (int m = 0; m <= 4; ++m) {
          const double a = a0 + (a1 - a0) * m / 4;
          w.push_back({c.x + rr * std::cos(a), c.y + rr * std::sin(a)});
        }
        svg.polygon(w, wedge);
      }
    }
    svg.text({c.x - R, c.y + 1.25 * R}, "set " + r.name + " (" + std::to_string(r.angles_deg.size()) +
                                            " segments, max bin " + std::to_string(most) + ")",
             0.12, "#000000");
    svg.text({c.x + 1.02 * R, c.y - 0.04}, "0°", 0.1, "#555555");
    svg.text({c.x - 0.1, c.y + 1.03 * R}, "90°", 0.1, "#555555");
  }
  if (svg.empty()) svg.text({0, 0}, "no joints", 0.2, "#000000");
  else
    svg.text({-R, 1.55 * R},
             "Rose diagram of trace directions (counter-clockwise from +x, 10° bins, radius ∝ count)",
             0.12, "#000000");
  return svg.str(0.05, 360 * static_cast<double>(std::max<std::size_t>(panel, 1)));
}

std::string trace_length_histogram_svg(const NetworkReport& rep) {
  PlotSpec spec;
  spec.title = "Trace length histogram (20 bins)";
  spec.xlabel = "trace length (m)";
  spec.ylabel = "joints per bin";
  double longest = 0;
  for (const auto& r : rep.sets) longest = std::max(longest, r.trace_lengths.max);
  if (longest <= 0) longest = 1;
  const int nb = 20;
  const double w = longest / nb;
  for (std::size_t si = 0; si < rep.sets.size(); ++si) {
    const auto& r = rep.sets[si];
    if (r.lengths.empty()) continue;
    std::vector<int> bins(nb, 0);
    for (double l : r.lengths) ++bins[std::min(nb - 1, static_cast<int>(l / w))];
    PlotSeries s;
    s.name = "set " + r.name + " (" + std::to_string(r.lengths.size()) + " joints)";
    s.colour = set_colour(si);
    s.x.push_back(0);
    s.y.push_back(0);
    for (int k = 0; k < nb; ++k) {  // steps: up the bin's left edge, across, down at its right
      s.x.push_back(k * w); s.y.push_back(bins[k]);
      s.x.push_back((k + 1) * w); s.y.push_back(bins[k]);
    }
    s.x.push_back(longest);
    s.y.push_back(0);
    spec.series.push_back(std::move(s));
  }
  return svg_plot(spec);
}

std::string block_area_cdf_svg(const NetworkReport& rep) {
  PlotSpec spec;
  spec.title = "Block area distribution (" + std::to_string(rep.blocks) + " blocks)";
  spec.xlabel = "block area a (m², log)";
  spec.ylabel = "fraction of blocks with area <= a";
  spec.log_x = true;
  PlotSeries s;
  s.name = "blocks";
  const auto& a = rep.block_areas;
  for (std::size_t i = 0; i < a.size(); ++i) {
    s.x.push_back(a[i]);
    s.y.push_back(static_cast<double>(i + 1) / static_cast<double>(a.size()));
  }
  s.markers = a.size() <= 200;
  spec.series.push_back(std::move(s));
  return svg_plot(spec);
}

std::string network_svg(const SceneDef& scene) {
  const Box box = bodies_box(scene.bodies);
  const double x0 = box.x0, x1 = box.x1, y1 = box.y1;
  SvgWriter out;
  if (scene.bodies.empty()) {
    out.text({0, 0}, "no bodies", 1, "#000000");
    return out.str();
  }
  const double size = x1 - x0, lw = 2e-3 * size;  // stroke widths are in model units
  for (const BodyDef& b : scene.bodies) {
    out.polygon(b.outer, {"#e8e8e8", "#000000", 2 * lw, 0, 1});
  }
  std::vector<std::size_t> counts(scene.joint_sets.size(), 0);
  for (std::size_t si = 0; si < scene.joint_sets.size(); ++si) {
    std::vector<std::pair<Vec2, Vec2>> segs;
    for (const JointDef& j : scene.joints) {
      if (j.set != static_cast<int>(si)) continue;
      ++counts[si];
      for (std::size_t k = 0; k + 1 < j.points.size(); ++k)
        segs.emplace_back(j.points[k], j.points[k + 1]);
    }
    if (!segs.empty()) out.segments(segs, {"none", set_colour(si), lw, 0, 1});
  }
  // Holes last: joint parts inside an opening are not in the rock (the cutter ignores them).
  for (const BodyDef& b : scene.bodies)
    for (const Ring& h : b.holes) out.polygon(h, {"#ffffff", "#000000", 2 * lw, 0, 1});
  const double fs = 0.025 * size;
  double y = y1 + 1.5 * fs * static_cast<double>(scene.joint_sets.size() + 1);
  out.text({x0, y}, "Joint network" + (scene.name.empty() ? std::string() : ": " + scene.name),
           1.2 * fs, "#000000");
  for (std::size_t si = 0; si < scene.joint_sets.size(); ++si) {
    y -= 1.5 * fs;
    out.text({x0, y}, "set " + scene.joint_sets[si].name + ": " + std::to_string(counts[si]) +
                          " joints", fs, set_colour(si));
  }
  return out.str();
}

}  // namespace nmm::pre
