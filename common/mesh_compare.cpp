// Two meshes compared as cuts, numbering aside: see mesh_compare.h.
#include "common/mesh_compare.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <iterator>
#include <cstdint>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

namespace nmm {

namespace {

// Two coordinates of one point as two cuts rounded it. A point the cut constructs (a joint across
// a mesh edge, two joints crossing) is exact inside CGAL; its double is the midpoint of whatever
// interval the construction left (CGAL::to_double of a lazy number), so a region re-cut and a
// whole cut that build the same exact point by different constructions may round it a few ulps
// apart (docs/fracture.md "Re-cutting": the step-path slope's joint across a mesh edge, 16.785144270341430
// against 16.785144270341434). kUlps bounds that: far below any distance a cut decides (a vertex
// snaps to another within 1e-2·h), far above the rounding.
constexpr double kUlps = 64;
bool same_coordinate(double x, double y) {
  return std::abs(x - y) <= kUlps * std::numeric_limits<double>::epsilon() * std::max(std::abs(x), std::abs(y));
}

// Whether element ea of a and eb of b have the same loop (vertices within kUlps, the same edge
// origins and joints), the loop of b starting `offset` vertices on from a's.
bool same_loop(const Mesh& a, std::size_t ea, const Mesh& b, std::size_t eb, std::int32_t& offset) {
  const std::int32_t fa = a.element_loop_offset[ea], n = a.element_loop_offset[ea + 1] - fa;
  const std::int32_t fb = b.element_loop_offset[eb];
  if (b.element_loop_offset[eb + 1] - fb != n) return false;
  for (std::int32_t r = 0; r < n; ++r) {
    bool all = true;
    for (std::int32_t k = 0; k < n && all; ++k) {
      const std::int32_t va = fa + k, vb = fb + (k + r) % n;
      all = a.loop_edge_origin[va] == b.loop_edge_origin[vb] && a.loop_edge_joint[va] == b.loop_edge_joint[vb] &&
            same_coordinate(a.loop_xy[2 * va], b.loop_xy[2 * vb]) &&
            same_coordinate(a.loop_xy[2 * va + 1], b.loop_xy[2 * vb + 1]);
    }
    if (all) {
      offset = r;
      return true;
    }
  }
  return false;
}

std::string where(const Mesh& m, std::size_t e) {
  std::ostringstream os;
  const std::int32_t v = m.element_loop_offset[e];
  os.precision(17);
  os << "element " << e << " (triangle " << m.element_triangle[e] << ", block " << m.element_block[e] << ", loop";
  for (std::int32_t w = v; w < m.element_loop_offset[e + 1]; ++w)
    os << " (" << m.loop_xy[2 * w] << ", " << m.loop_xy[2 * w + 1] << ")" << int{m.loop_edge_origin[w]} << "/"
       << m.loop_edge_joint[w];
  os << ")";
  return os.str();
}

// Whether labels la[i] (of a) and lb[map[i]] (of b) partition alike: one to one.
bool same_partition(const std::vector<std::int32_t>& la, const std::vector<std::int32_t>& lb,
                    const std::vector<std::int32_t>& map, std::size_t& bad) {
  std::map<std::int32_t, std::int32_t> ab, ba;
  for (std::size_t i = 0; i < la.size(); ++i) {
    const std::int32_t x = la[i], y = lb[static_cast<std::size_t>(map[i])];
    const auto [it, fresh] = ab.emplace(x, y);
    const auto [jt, fresh2] = ba.emplace(y, x);
    if (it->second != y || jt->second != x) {
      bad = i;
      return false;
    }
  }
  return true;
}

}  // namespace

std::string mesh_difference(const Mesh& a, const Mesh& b) {
  std::ostringstream os;
  if (a.node_xy != b.node_xy) return "the mesh nodes differ";
  if (a.triangle_nodes != b.triangle_nodes) return "the mesh triangles differ";
  const std::size_t ne = a.element_count();
  if (ne != b.element_count())
    return std::to_string(ne) + " elements against " + std::to_string(b.element_count());
  // Elements: matched within their triangle and body (a triangle holds a few), loop by loop.
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<std::int32_t>> in_b;  // (triangle, body) → b's MEs
  for (std::size_t e = 0; e < ne; ++e)
    in_b[{b.element_triangle[e], b.element_body[e]}].push_back(static_cast<std::int32_t>(e));
  std::vector<std::int32_t> to_b(ne, -1), offset(ne, 0);  // [a's me] b's me, its loop's start
  std::vector<std::uint8_t> taken(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto it = in_b.find({a.element_triangle[e], a.element_body[e]});
    if (it != in_b.end())
      for (const std::int32_t f : it->second)
        if (!taken[static_cast<std::size_t>(f)] && same_loop(a, e, b, static_cast<std::size_t>(f), offset[e])) {
          to_b[e] = f;
          taken[static_cast<std::size_t>(f)] = 1;
          break;
        }
    if (to_b[e] < 0) {
      os << where(a, e) << " has no equal";
      if (it != in_b.end()) os << "; its triangle's first is " << where(b, static_cast<std::size_t>(it->second.front()));
      return os.str();
    }
  }
  // Covers: as sets of element corners (element, corner), one to one, on the same node and body.
  if (a.cover_count() != b.cover_count())
    return std::to_string(a.cover_count()) + " covers against " + std::to_string(b.cover_count());
  {
    std::vector<std::int32_t> slot_map(3 * ne);
    for (std::size_t s = 0; s < 3 * ne; ++s) slot_map[s] = 3 * to_b[s / 3] + static_cast<std::int32_t>(s % 3);
    std::size_t bad = 0;
    if (!same_partition(a.element_covers, b.element_covers, slot_map, bad)) {
      os << "the covers differ at corner " << bad % 3 << " of " << where(a, bad / 3) << ": cover "
         << a.element_covers[bad] << " (node " << a.cover_node[static_cast<std::size_t>(a.element_covers[bad])]
         << ") against cover " << b.element_covers[static_cast<std::size_t>(slot_map[bad])];
      return os.str();
    }
    for (std::size_t s = 0; s < 3 * ne; ++s) {
      const auto x = static_cast<std::size_t>(a.element_covers[s]);
      const auto y = static_cast<std::size_t>(b.element_covers[static_cast<std::size_t>(slot_map[s])]);
      if (a.cover_node[x] != b.cover_node[y] || a.cover_body[x] != b.cover_body[y])
        return "cover " + std::to_string(x) + " lies on another node or body than its match";
    }
  }
  // Blocks: as sets of elements.
  if (a.block_count() != b.block_count())
    return std::to_string(a.block_count()) + " blocks against " + std::to_string(b.block_count());
  {
    std::size_t bad = 0;
    if (!same_partition(a.element_block, b.element_block, to_b, bad)) {
      os << "the blocks differ at " << where(a, bad) << ": block " << a.element_block[bad] << " against block "
         << b.element_block[static_cast<std::size_t>(to_b[bad])];
      return os.str();
    }
  }
  // Contact edges: (element, its loop edge, the element across), a's in b's numbering.
  auto edges = [](const Mesh& m, const std::vector<std::int32_t>* to, const std::vector<std::int32_t>* start) {
    std::vector<std::tuple<std::int32_t, std::int32_t, std::int32_t>> out;
    for (std::size_t i = 0; i < m.contact_edge.size(); ++i) {
      const auto e = static_cast<std::size_t>(m.contact_edge_element[i]);
      const std::int32_t first = m.element_loop_offset[e], n = m.element_loop_offset[e + 1] - first;
      const std::int32_t local = (m.contact_edge[i] - first + (start ? (*start)[e] : 0)) % n;
      const std::int32_t opp = m.contact_edge_opposite[i];
      out.emplace_back(to ? (*to)[e] : static_cast<std::int32_t>(e), local, opp < 0 || !to ? opp : (*to)[static_cast<std::size_t>(opp)]);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto ea = edges(a, &to_b, &offset), eb = edges(b, nullptr, nullptr);
  if (ea != eb) {
    std::vector<std::tuple<std::int32_t, std::int32_t, std::int32_t>> only_a, only_b;
    std::set_difference(ea.begin(), ea.end(), eb.begin(), eb.end(), std::back_inserter(only_a));
    std::set_difference(eb.begin(), eb.end(), ea.begin(), ea.end(), std::back_inserter(only_b));
    os << ea.size() << " contact edges against " << eb.size();
    for (const auto& [list, name] : {std::make_pair(&only_a, "only the first"), std::make_pair(&only_b, "only the second")})
      if (!list->empty()) {
        const auto& [e, local, opp] = list->front();
        os << "; " << list->size() << " in " << name << ", e.g. loop edge " << local << " of " << where(b, static_cast<std::size_t>(e))
           << " across element " << opp;
      }
    return os.str();
  }
  return "";
}

}  // namespace nmm
