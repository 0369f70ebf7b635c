// Two meshes compared as cuts, numbering aside: see mesh_compare.h.
#include "common/mesh_compare.h"

#include <algorithm>
#include <iterator>
#include <cstdint>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

namespace nmm {

namespace {

// One loop edge as compared: its start vertex, origin flags and joint.
using EdgeKey = std::tuple<double, double, std::uint8_t, std::int32_t>;

// An element as compared: its triangle, body and loop, rotated to its least rotation (a loop may
// start at any of its vertices; a bridged loop repeats vertices, so the whole sequence decides).
struct ElementKey {
  std::int32_t triangle = -1, body = -1;
  std::vector<EdgeKey> loop;
  bool operator<(const ElementKey& o) const {
    return std::tie(triangle, body, loop) < std::tie(o.triangle, o.body, o.loop);
  }
  bool operator==(const ElementKey& o) const {
    return triangle == o.triangle && body == o.body && loop == o.loop;
  }
};

struct Canonical {
  std::vector<ElementKey> key;       // [me]
  std::vector<std::int32_t> shift;   // [me] the loop vertex (local) the least rotation starts at
};

Canonical canonical(const Mesh& m) {
  Canonical c;
  const std::size_t ne = m.element_count();
  c.key.resize(ne);
  c.shift.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t b = m.element_loop_offset[e], n = m.element_loop_offset[e + 1] - b;
    std::vector<EdgeKey> loop;
    for (std::int32_t v = b; v < b + n; ++v)
      loop.emplace_back(m.loop_xy[2 * v], m.loop_xy[2 * v + 1], m.loop_edge_origin[v], m.loop_edge_joint[v]);
    std::int32_t best = 0;
    for (std::int32_t r = 1; r < n; ++r)
      for (std::int32_t k = 0; k < n; ++k) {
        const EdgeKey &x = loop[(r + k) % n], &y = loop[(best + k) % n];
        if (x == y) continue;
        if (x < y) best = r;
        break;
      }
    std::rotate(loop.begin(), loop.begin() + best, loop.end());
    c.key[e] = {m.element_triangle[e], m.element_body[e], std::move(loop)};
    c.shift[e] = best;
  }
  return c;
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
  const Canonical ca = canonical(a), cb = canonical(b);
  std::vector<std::int32_t> oa(ne), ob(ne);
  for (std::size_t e = 0; e < ne; ++e) oa[e] = ob[e] = static_cast<std::int32_t>(e);
  std::sort(oa.begin(), oa.end(), [&](std::int32_t x, std::int32_t y) { return ca.key[x] < ca.key[y]; });
  std::sort(ob.begin(), ob.end(), [&](std::int32_t x, std::int32_t y) { return cb.key[x] < cb.key[y]; });
  std::vector<std::int32_t> to_b(ne);  // [a's me] b's me
  for (std::size_t k = 0; k < ne; ++k) {
    if (!(ca.key[oa[k]] == cb.key[ob[k]])) {
      os << where(a, static_cast<std::size_t>(oa[k])) << " has no equal; the nearest is "
         << where(b, static_cast<std::size_t>(ob[k]));
      return os.str();
    }
    to_b[oa[k]] = ob[k];
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
  // Contact edges: (element, its loop edge counted from the least rotation, the element across).
  auto edges = [](const Mesh& m, const Canonical& c, const std::vector<std::int32_t>* to) {
    std::vector<std::tuple<std::int32_t, std::int32_t, std::int32_t>> out;
    for (std::size_t i = 0; i < m.contact_edge.size(); ++i) {
      const auto e = static_cast<std::size_t>(m.contact_edge_element[i]);
      const std::int32_t first = m.element_loop_offset[e], n = m.element_loop_offset[e + 1] - first;
      const std::int32_t local = ((m.contact_edge[i] - first - c.shift[e]) % n + n) % n;
      const std::int32_t opp = m.contact_edge_opposite[i];
      out.emplace_back(to ? (*to)[e] : static_cast<std::int32_t>(e), local, opp < 0 || !to ? opp : (*to)[static_cast<std::size_t>(opp)]);
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto ea = edges(a, ca, &to_b), eb = edges(b, cb, nullptr);
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
