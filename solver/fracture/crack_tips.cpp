// The tips of cracks inside a body: see crack_tips.h.
#include "solver/fracture/crack_tips.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/ring_geometry.h"

namespace nmm::solve {

namespace {

struct Piece {
  Vec2 a, b;
  int line = -1;  // the scene joint (polyline) or crack segment it belongs to
};

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0, 1.0) : 0.0;
  return length(a.x + t * dx - p.x, a.y + t * dy - p.y);
}

double distance_to_ring(const Ring& ring, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    best = std::min(best, distance_to_segment(p, ring[j], ring[i]));
  return best;
}

// The body p lies in, farther than tol from its boundary, or -1.
std::int32_t body_holding(const SceneDef& scene, const Vec2& p, double tol, double& boundary_distance) {
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodyDef& body = scene.bodies[b];
    if (!point_in_ring(body.outer, p)) continue;
    bool in_hole = false;
    for (const Ring& hole : body.holes) in_hole = in_hole || point_in_ring(hole, p);
    if (in_hole) continue;
    double d = distance_to_ring(body.outer, p);
    for (const Ring& hole : body.holes) d = std::min(d, distance_to_ring(hole, p));
    if (d <= tol) return -1;
    boundary_distance = d;
    return static_cast<std::int32_t>(b);
  }
  return -1;
}

int root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
  return i;
}

}  // namespace

std::vector<CrackTip> CrackTipFinder::find(const Mesh& mesh, const SceneDef& scene,
                                           const std::vector<std::array<Vec2, 2>>& cracks) {
  const double h = mesh.mesh_size, tol = 1e-6 * h;
  // Every joint and crack as pieces, and the ends of each line with the point before it.
  std::vector<Piece> pieces;
  struct End {
    Vec2 at, before;
    int line;
  };
  std::vector<End> ends;
  int lines = 0;
  for (const JointDef& j : scene.joints) {
    const std::size_t n = j.points.size();
    // A run's scene after a re-cut holds its cracks as joints too (stepping/fracture_effect.cpp):
    // they are taken from `cracks`, once.
    if (n == 2 && std::any_of(cracks.begin(), cracks.end(), [&](const std::array<Vec2, 2>& c) {
          return c[0] == j.points[0] && c[1] == j.points[1];
        }))
      continue;
    for (std::size_t i = 0; i + 1 < n; ++i) pieces.push_back({j.points[i], j.points[i + 1], lines});
    ends.push_back({j.points[0], j.points[1], lines});
    ends.push_back({j.points[n - 1], j.points[n - 2], lines});
    ++lines;
  }
  for (const auto& c : cracks) {
    if (c[0] == c[1]) continue;
    pieces.push_back({c[0], c[1], lines});
    ends.push_back({c[0], c[1], lines});
    ends.push_back({c[1], c[0], lines});
    ++lines;
  }
  // Lines that meet are one crack (a crack grown from a joint's end, a crack's segments).
  std::vector<int> parent(static_cast<std::size_t>(lines));
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<std::uint8_t> meets(ends.size(), 0);
  for (std::size_t k = 0; k < ends.size(); ++k)
    for (const Piece& p : pieces)
      if (p.line != ends[k].line && distance_to_segment(ends[k].at, p.a, p.b) <= tol) {
        meets[k] = 1;
        parent[static_cast<std::size_t>(root(parent, ends[k].line))] = root(parent, p.line);
      }
  // The tips: ends inside a body that meet nothing.
  std::vector<CrackTip> tips;
  std::vector<int> tip_group;
  std::vector<double> limit;  // m, the nearest boundary, other crack or other tip
  for (std::size_t k = 0; k < ends.size(); ++k) {
    if (meets[k]) continue;
    double boundary = 0;
    const std::int32_t body = body_holding(scene, ends[k].at, tol, boundary);
    if (body < 0) continue;
    const double dx = ends[k].at.x - ends[k].before.x, dy = ends[k].at.y - ends[k].before.y;
    const double l = length(dx, dy);
    CrackTip t;
    t.at = ends[k].at;
    t.direction = {dx / l, dy / l};
    t.body = body;
    tips.push_back(t);
    const int group = root(parent, ends[k].line);
    tip_group.push_back(group);
    double d = boundary;
    for (const Piece& p : pieces)
      if (root(parent, p.line) != group) d = std::min(d, distance_to_segment(t.at, p.a, p.b));
    limit.push_back(d);
  }
  for (std::size_t i = 0; i < tips.size(); ++i) {
    double d = limit[i];
    for (std::size_t j = 0; j < tips.size(); ++j)
      if (j != i) d = std::min(d, length(tips[j].at.x - tips[i].at.x, tips[j].at.y - tips[i].at.y));
    // q reaches one triangle beyond the radius: keep that ring clear of what limits it, and at
    // least one triangle from the tip so that the tip's own element is not in it.
    tips[i].radius = std::max(std::min(kDomainRadius * h, d - 1.1 * h), std::min(1.1 * h, 0.5 * d));
  }
  // Each tip's crack backwards, piece by piece, as far as the ring reaches (radius + one
  // triangle): from each point the piece of its crack that goes on with the least turn (a crack
  // grown from a joint's side goes on along the joint).
  for (std::size_t i = 0; i < tips.size(); ++i) {
    CrackTip& t = tips[i];
    const double reach = t.radius + 2 * h;
    std::vector<std::uint8_t> used(pieces.size(), 0);
    Vec2 at = t.at, heading{-t.direction.x, -t.direction.y};
    t.behind = {at};
    while (length(at.x - t.at.x, at.y - t.at.y) <= reach && t.behind.size() < 10000) {
      std::size_t best = pieces.size();
      Vec2 next{};
      double best_turn = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < pieces.size(); ++k) {
        const Piece& p = pieces[k];
        if (used[k] || root(parent, p.line) != tip_group[i] || distance_to_segment(at, p.a, p.b) > tol) continue;
        for (const Vec2& end : {p.a, p.b}) {
          const double dx = end.x - at.x, dy = end.y - at.y, l = length(dx, dy);
          if (l <= tol) continue;
          const double turn = std::acos(std::clamp((dx * heading.x + dy * heading.y) / l, -1.0, 1.0));
          if (turn < best_turn) best_turn = turn, best = k, next = end;
        }
      }
      if (best == pieces.size()) break;  // the crack ends here
      used[best] = 1;
      const double l = length(next.x - at.x, next.y - at.y);
      heading = {(next.x - at.x) / l, (next.y - at.y) / l};
      at = next;
      t.behind.push_back(at);
    }
  }
  // Numbers: a tip where a known one was keeps its number; a tip whose crack runs through a known
  // tip's place (it grew from there) takes the nearest such; any other is new.
  std::vector<std::uint8_t> taken(known_.size(), 0);
  auto on_group = [&](const Vec2& p, int group) {
    for (const Piece& piece : pieces)
      if (root(parent, piece.line) == group && distance_to_segment(p, piece.a, piece.b) <= tol) return true;
    return false;
  };
  for (std::size_t i = 0; i < tips.size(); ++i)
    for (std::size_t k = 0; k < known_.size(); ++k)
      if (!taken[k] && length(known_[k].at.x - tips[i].at.x, known_[k].at.y - tips[i].at.y) <= tol) {
        tips[i].id = known_[k].id;
        taken[k] = 1;
        break;
      }
  for (std::size_t i = 0; i < tips.size(); ++i) {
    if (tips[i].id >= 0) continue;
    std::size_t best = known_.size();
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < known_.size(); ++k) {
      if (taken[k] || !on_group(known_[k].at, tip_group[i])) continue;
      const double d = length(known_[k].at.x - tips[i].at.x, known_[k].at.y - tips[i].at.y);
      if (d < best_d) best_d = d, best = k;
    }
    if (best < known_.size()) {
      tips[i].id = known_[best].id;
      taken[best] = 1;
    } else {
      tips[i].id = next_id_++;
    }
  }
  known_ = tips;
  return tips;
}

}  // namespace nmm::solve
