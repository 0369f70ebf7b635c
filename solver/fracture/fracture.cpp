// Which elements an accepted step breaks, and the crack segments through them: see fracture.h.
#include "solver/fracture/fracture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "common/ring_geometry.h"
#include "preprocess/exact_side.h"
#include "solver/contact/cohesive_law.h"
#include "solver/discretisation/state_bytes.h"
#include "solver/discretisation/stress_field.h"
#include "solver/fracture/cohesive_starts.h"
#include "solver/fracture/crack_parting.h"
#include "solver/fracture/element_geometry.h"
#include "solver/fracture/interaction_integral.h"
#include "solver/fracture/tip_drive.h"

namespace nmm::solve {

namespace {

// NMM_TRACE_CRACK_RULES=1: each bridge weighed, each re-armed or in-line crack grown, each new
// crack started and each new block of at most three elements a cut made (debris or not), to
// stderr.
bool trace_rules() {
  static const bool on = std::getenv("NMM_TRACE_CRACK_RULES") != nullptr;
  return on;
}

Vec2 plus(const Vec2& a, double t, const Vec2& d) { return {a.x + t * d.x, a.y + t * d.y}; }
double dot(const Vec2& a, const Vec2& b) { return a.x * b.x + a.y * b.y; }

// Where a crack leaves element e (`exit` from ray_exit), made safe to cut:
// - an exit within kSnap·h of a loop vertex moves onto the vertex, so that a crack passing a
//   node or the end of another crack does not cut off a splinter of rock a hundredth of an
//   element wide (the crack turns by at most about a degree for it);
// - the crack stops there when it reached a body boundary or a joint (a crack's own faces
//   included): the edge it leaves through, or at a vertex either edge meeting there, is one;
// - a stopping crack is cut on by kOvershoot·h past that edge. In doubles its end is not exactly
//   on the edge; cut exactly, it would stop a round-off short — the rock would not part — or
//   cross a round-off beyond near other cuts and leave specks. Overshot, it crosses the edge at
//   one exact point and its hair beyond is a slit of no area.
// - a crack end that does not stop and was not snapped onto a vertex is moved, where it lies a
//   round-off short of its edge, onto or just past it: by steps from an ulp of its coordinates,
//   doubled until the cutter's own exact arithmetic puts it on the edge or beyond
//   (pre::exact_side) — at most kOvershoot·h — and its tip grows on from there (`tip`), so the
//   crack's segments stay one chain. An end a round-off short leaves its element whole (the crack
//   neither parts it nor any star across it) and the crack opens nothing, so whether it parts
//   its element was decided by the last bits of the solution: at cover order 0 the notched beam
//   (h 0.02 m, static, slow) parted the element at step 85 under one OpenBLAS kernel family and
//   not under the other, and its peaks after the crack came out 87.3 / 78.7 kN/m (now 69.4 under
//   both; docs/fracture.md "Robustness matrix"); at n = 1 the 4 m bar started new cracks beside
//   such an end within the step, 22 segments in all (docs/higher-order-covers.md "Fracturing").
//   Every such end cut kOvershoot·h past instead put its kink 1e-8·h inside the next element, and
//   the contact solve on the 2.5e-9 m edges that made failed to converge (the bar at n = 2, a
//   time step cut); the compression specimens cascaded too.
// - before any of this, the exit is rounded to a grid along its edge, kGrid·h apart: the exit
//   follows from a direction read off the solution, whose last bits the BLAS kernel decides, and
//   every decision above (and the exact one) is then taken on a point both kernel families agree
//   on. Without it the notched beam (h 0.02 m, static, fast) cut its meshes of step 46 an element
//   apart under the Haswell and the Prescott kernels (an end on or past its edge as computed
//   under one, moved past it under the other) and its peaks came out 81.0 / 74.1 kN/m. The end
//   moves by at most kGrid·h/2 for it (a segment an element long turns by 5e-7 rad).
constexpr double kSnap = 1e-2, kOvershoot = 1e-8, kGrid = 1e-6;
// `exit` moved along its edge onto the nearest of the points kGrid·h apart from its first vertex
// (a round-off off the edge's line at most: the exact test in crack_end takes it from there).
RayExit on_grid(const Mesh& mesh, std::size_t e, const RayExit& exit) {
  const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
  const std::int32_t v = exit.edge, w = v + 1 < end ? v + 1 : b;
  const Vec2 pv{mesh.loop_xy[2 * v], mesh.loop_xy[2 * v + 1]}, pw{mesh.loop_xy[2 * w], mesh.loop_xy[2 * w + 1]};
  const Vec2 edge{pw.x - pv.x, pw.y - pv.y};
  const double length = std::hypot(edge.x, edge.y);  // m
  RayExit out = exit;
  if (!(length > 0)) return out;
  const double cells = std::ceil(length / (kGrid * mesh.mesh_size));
  const double along = dot({exit.at.x - pv.x, exit.at.y - pv.y}, edge) / (length * length);  // –, 0 at pv
  const double k = std::clamp(std::round(along * cells), 0.0, cells);
  out.at = k == 0 ? pv : k == cells ? pw : plus(pv, k / cells, edge);
  return out;
}
struct CrackEnd {
  Vec2 at;          // m, where the crack leaves the element (as cut)
  Vec2 cut_to;      // m, where its segment ends (past `at` when it stops or lay a round-off short)
  Vec2 tip;         // m, where a tip that grows on from this end starts: cut_to or at
  bool stops = false;
  std::int32_t stop_edge = -1;  // the loop edge (its first vertex) it stops on, where it stops
};
CrackEnd crack_end(const Mesh& mesh, std::size_t e, const Vec2& from, const RayExit& exit) {
  const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
  const std::int32_t v = exit.edge, w = v + 1 < end ? v + 1 : b, u = v > b ? v - 1 : end - 1;
  const double h = mesh.mesh_size;
  auto vertex = [&](std::int32_t k) { return Vec2{mesh.loop_xy[2 * k], mesh.loop_xy[2 * k + 1]}; };
  auto stop_edge = [&](std::int32_t k) { return (mesh.loop_edge_origin[k] & (kEdgeBoundary | kEdgeJoint)) != 0; };
  CrackEnd c;
  c.at = on_grid(mesh, e, exit).at;
  c.stops = stop_edge(v);
  if (c.stops) c.stop_edge = v;
  const Vec2 pv = vertex(v), pw = vertex(w);
  const double dv = std::hypot(c.at.x - pv.x, c.at.y - pv.y), dw = std::hypot(c.at.x - pw.x, c.at.y - pw.y);
  if (std::min(dv, dw) < kSnap * h) {
    const bool at_v = dv <= dw;
    const Vec2 snapped = at_v ? pv : pw;
    if (std::hypot(snapped.x - from.x, snapped.y - from.y) > kSnap * h) {  // not back onto its start
      c.at = snapped;
      if (!c.stops && stop_edge(at_v ? u : w)) c.stops = true, c.stop_edge = at_v ? u : w;
    }
  }
  c.cut_to = c.at;
  const double dx = c.at.x - from.x, dy = c.at.y - from.y, l = std::hypot(dx, dy);
  if (c.stops) {
    if (l > 0) c.cut_to = plus(c.at, kOvershoot * h / l, {dx, dy});
  } else if (l > 0 && !(c.at == pv || c.at == pw)) {
    const int inside = pre::exact_side(pv, pw, from);  // the side of the edge the crack comes from
    double t = std::numeric_limits<double>::epsilon() * std::max({std::abs(c.at.x), std::abs(c.at.y), h});
    while (inside != 0 && pre::exact_side(pv, pw, c.cut_to) == inside && t < kOvershoot * h) {
      c.cut_to = plus(c.at, t / l, {dx, dy});
      t *= 2;
    }
    if (inside != 0 && pre::exact_side(pv, pw, c.cut_to) == inside) c.cut_to = plus(c.at, kOvershoot * h / l, {dx, dy});
  }
  c.tip = c.stops ? c.at : c.cut_to;
  return c;
}

}  // namespace

Fracture::Fracture(const SceneDef& scene) {
  if (!scene.fracture.present) return;
  for (const MaterialDef& m : scene.materials) active_ = active_ || m.strength.present;
}

void Fracture::start_tips(const Mesh& mesh, const SceneDef& scene) {
  // The ends of the scene's joints that lie inside a body (not on its boundary): a crack grows on
  // from them as from its own tips.
  const double tol = 1e-9 * mesh.mesh_size;
  auto inside_a_body = [&](const Vec2& p) {
    for (const BodyDef& b : scene.bodies) {
      if (!point_in_ring(b.outer, p)) continue;
      bool in_hole = false;
      for (const Ring& hole : b.holes) in_hole = in_hole || point_in_ring(hole, p);
      if (in_hole) continue;
      std::vector<double> xy;
      for (const Vec2& q : b.outer) xy.insert(xy.end(), {q.x, q.y});
      return distance_to_loop(xy.data(), b.outer.size(), p.x, p.y) > tol;
    }
    return false;
  };
  for (const JointDef& j : scene.joints) {
    const std::size_t n = j.points.size();
    const Vec2 ends[2][2] = {{j.points[0], j.points[1]}, {j.points[n - 1], j.points[n - 2]}};
    for (const auto& [end, before] : ends) {
      if (!inside_a_body(end)) continue;
      const double dx = end.x - before.x, dy = end.y - before.y, l = std::hypot(dx, dy);
      tips_.push_back({end, {dx / l, dy / l}, -1, true});
    }
  }
  tips_started_ = true;
}

std::vector<CrackSegment> Fracture::find(const Mesh& mesh, const SceneDef& scene, const RunState& s,
                                         const std::vector<std::uint8_t>& removed,
                                         const std::vector<std::uint8_t>& may_start) {
  std::vector<CrackSegment> out;
  if (!active_) return out;
  if (!tips_started_) start_tips(mesh, scene);
  const std::size_t n = mesh.element_count();
  if (armed_.size() != n) armed_.assign(n, 1);
  // Each element's strength check on the accepted state; an element back inside its strength is
  // armed again. The screen settles the elements surely inside their strength; rock_failure
  // checks the others (rock_strength.h: the same decisions as checking all of them).
  std::vector<StrengthScreen> screen(scene.bodies.size());
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const StrengthDef& st = scene.materials[scene.bodies[b].material].strength;
    if (st.present) screen[b] = StrengthScreen(st);
  }
  // The element's stress: at cover order n ≥ 1 its mean ∫σ dA / A (stress_field.h), the value the
  // outputs show: the strength check stays one decision per element, as at n = 0.
  const int order = scene.solver.cover_order;
  const std::vector<double> mean = order == 0 ? std::vector<double>{} : mean_stress(mesh, order, s);
  const std::vector<double>& stress = order == 0 ? s.stress : mean;
  ratio_.resize(n);
  failure_.resize(n);
  over_.clear();
  for (std::size_t e = 0; e < n; ++e) {
    const std::int32_t body = mesh.element_body[e];
    const StrengthDef& st = scene.materials[scene.bodies[body].material].strength;
    if (!st.present || (!removed.empty() && removed[e])) {
      ratio_[e] = -std::numeric_limits<double>::infinity();  // cannot break
      continue;
    }
    const double sxx = stress[3 * e], syy = stress[3 * e + 1], sxy = stress[3 * e + 2];
    if (screen[static_cast<std::size_t>(body)].surely_holds(sxx, syy, sxy)) {
      ratio_[e] = 0;  // below 1: all the rule asks of an element inside its strength
      armed_[e] = 1;
      continue;
    }
    failure_[e] = rock_failure(st, sxx, syy, sxy);
    ratio_[e] = failure_[e].ratio;
    if (ratio_[e] < 1) armed_[e] = 1;
    if (ratio_[e] >= 1) over_.push_back(static_cast<std::int32_t>(e));
  }
  crossed_.assign(n, 0);
  const double h = mesh.mesh_size, tol = 1e-9 * h;
  // The mesh's element grid, built at the first look ahead of a tip on this mesh.
  auto grid = [&]() -> const ElementGrid& {
    if (!grid_ || !grid_->of(mesh)) grid_ = std::make_shared<const ElementGrid>(mesh);
    return *grid_;
  };
  // Rule 7 of cohesive_starts.h at cover order n ≥ 1: an element at a gap's end whose covers reach
  // round it is judged by the stress at the point its crack would leave from (the middle of the
  // gap's end), read from the polynomial of the element there, where its mean would smear the
  // end's concentration over h; the gap's end is the one place it may start a crack (kGapEnd).
  if (order >= 1 && !may_start.empty()) {
    bool added = false;
    for (std::size_t e = 0; e < n; ++e) {
      if (!(may_start[e] & kGapEnd) || !(ratio_[e] > -std::numeric_limits<double>::infinity())) continue;
      Vec2 at, dir;
      if (!gap_end(mesh, scene, e, at, dir)) continue;
      const std::int32_t there = grid().at(plus(at, 1e-6 * h, dir));
      if (there < 0) continue;
      const std::size_t u = static_cast<std::size_t>(there);
      const Vec2 x = current_point(mesh, s, order, u, at);
      const std::array<double, 3> sg = stress_at(mesh, order, s, u, x.x, x.y);
      const RockFailure f = rock_failure(scene.materials[scene.bodies[mesh.element_body[e]].material].strength, sg[0],
                                         sg[1], sg[2]);
      if (!(f.ratio > ratio_[e])) continue;
      if (ratio_[e] < 1 && f.ratio >= 1) {
        over_.push_back(static_cast<std::int32_t>(e));
        added = true;
        if (trace_rules())
          std::fprintf(stderr, "TRACE gap end step %lld element %zu: ratio %.4f at (%.4f,%.4f) in element %zu\n",
                       static_cast<long long>(s.step), e, f.ratio, at.x, at.y, u);
      }
      ratio_[e] = f.ratio;
      failure_[e] = f;
    }
    if (added) std::sort(over_.begin(), over_.end());
  }
  // The crack direction in element e (as cut) closest to `along`.
  auto direction = [&](std::size_t e, const Vec2& along) {
    const RockFailure& f = failure_[e];
    Vec2 best{};
    double best_dot = -2;
    for (const Vec2& d : {f.direction, f.conjugate})
      for (const double sign : {1.0, -1.0}) {
        Vec2 r = direction_as_cut(mesh, s, order, e, {sign * d.x, sign * d.y});
        if (dot(r, along) > best_dot) best_dot = dot(r, along), best = r;
      }
    return best;
  };
  auto add = [&](std::size_t e, const Vec2& a, const Vec2& b, std::int32_t crack, CrackMode mode) {
    if (a == b) {  // a tip that grew by nothing: no segment (the cutter takes none)
      crossed_[e] = 1;
      return;
    }
    CrackSegment seg;
    seg.a = a;
    seg.b = b;
    seg.a_now = current_point(mesh, s, order, e, a);
    seg.b_now = current_point(mesh, s, order, e, b);
    seg.mode = mode;
    seg.crack = crack;
    seg.step = s.step;
    seg.time = s.time;
    out.push_back(seg);
    crossed_[e] = 1;
  };
  // The scene's joints, then one per crack segment cut so far (fracture_effect.cpp).
  const std::int32_t first_crack = static_cast<std::int32_t>(scene.joints.size() - segments_.size());
  // Which cracks are tied to a scene joint (tip_drive.h), worked out when a bridge is first weighed.
  std::vector<std::uint8_t> jointed;
  bool jointed_known = false;
  auto tied = [&](std::int32_t crack) {
    if (crack < 0) return true;  // grown from a joint's own end
    if (!jointed_known) {
      std::vector<Vec2> a, b;
      std::vector<std::int32_t> id;
      for (const CrackSegment& c : segments_) a.push_back(c.a), b.push_back(c.b), id.push_back(c.crack);
      jointed = jointed_cracks(scene.joints, static_cast<std::size_t>(first_crack), a, b, id, cracks_, 1e-6 * h);
      jointed_known = true;
    }
    return static_cast<std::size_t>(crack) < jointed.size() && jointed[static_cast<std::size_t>(crack)] != 0;
  };
  // The holding elements straight ahead of `tip` that its crack crosses as a rock bridge
  // (tip_drive.h): how many there are before the line reaches a joint or a crack face (a joint on
  // one side of the bridge at least), or, from a crack tied to a joint, an element beyond its
  // strength; at most kBridgeElements, each pulled open across the line. −1 where the line does
  // not link so, or where the crack that drives it is a shear one.
  auto bridge = [&](const Tip& tip, CrackMode drive) {
    if (drive != CrackMode::tensile) return -1;  // shear cracks cross no holding rock (tip_drive.h)
    const bool from_joint = tied(tip.crack);
    auto fail = [&](const char* why, double s_nn) {
      if (trace_rules())
        std::fprintf(stderr, "TRACE no bridge step %lld tip (%.4f,%.4f) dir (%.3f,%.3f) crack %d jointed %d: %s %.4g\n",
                     static_cast<long long>(s.step), tip.at.x, tip.at.y, tip.dir.x, tip.dir.y, tip.crack,
                     from_joint ? 1 : 0, why, s_nn);
      return -1;
    };
    Vec2 p = tip.at;
    for (int k = 0; k < kBridgeElements; ++k) {
      const std::int32_t el = grid().at(plus(p, 1e-6 * h, tip.dir));
      if (el < 0 || crossed_[el] || !(ratio_[el] > -std::numeric_limits<double>::infinity()))
        return fail("no rock ahead", 0);
      if (ratio_[el] >= 1) {
        if (!from_joint) return fail("breaking rock ahead of a crack not tied to a joint", 0);
        if (trace_rules())
          std::fprintf(stderr, "TRACE bridge step %lld tip (%.4f,%.4f) crack %d: %d holding to element %d at %.4f\n",
                       static_cast<long long>(s.step), tip.at.x, tip.at.y, tip.crack, k, el, ratio_[el]);
        return k;
      }
      const std::size_t u = static_cast<std::size_t>(el);
      if (!pulls_line_open(stress[3 * u], stress[3 * u + 1], stress[3 * u + 2], tip.dir)) {
        const double nx = -tip.dir.y, ny = tip.dir.x;
        return fail("shut across the line, s_nn (Pa)",
                    stress[3 * u] * nx * nx + stress[3 * u + 1] * ny * ny + 2 * stress[3 * u + 2] * nx * ny);
      }
      RayExit exit;
      if (!ray_exit(mesh, u, p, tip.dir, tol, exit)) return fail("no exit", 0);
      const CrackEnd c = crack_end(mesh, u, p, exit);
      if (c.stops) {
        const std::size_t v = static_cast<std::size_t>(c.stop_edge);
        const std::int32_t j = mesh.loop_edge_joint[v];
        if ((mesh.loop_edge_origin[v] & kEdgeJoint) == 0 || j < 0) return fail("a body boundary", 0);
        const bool to_joint = j < first_crack || tied(segments_[static_cast<std::size_t>(j - first_crack)].crack);
        if (!from_joint && !to_joint) return fail("no joint on either side", 0);
        if (trace_rules())
          std::fprintf(stderr, "TRACE bridge step %lld tip (%.4f,%.4f) crack %d: %d holding to joint %d\n",
                       static_cast<long long>(s.step), tip.at.x, tip.at.y, tip.crack, k + 1, j);
        return k + 1;
      }
      p = c.at;
    }
    return fail("more than kBridgeElements", 0);
  };
  // On from a tip while the element ahead breaks; a tip that reaches a body boundary or a joint,
  // or leaves the bodies, stops growing for good.
  // `forced` > 0: the tip may cross elements that hold (rules 6 and 7 of fracture.h: a crack that
  // has not parted its element, a tip reaching for the element ahead that breaks), straight on and
  // only as a rock bridge (bridge above), in the mode of the element beyond its strength that
  // drives it (`drive`: one that holds has no mode of its own).
  // `band`: a cohesive crack reaching an element in the band ahead of its tip (rule 4 of
  // cohesive_starts.h) crosses the `forced` holding elements between without a bridge.
  // An element of a material with a fracture energy (rock that softens), in a run that weighs
  // cohesive starts.
  auto cohesive_rock = [&](std::size_t e) {
    return !may_start.empty() &&
           cohesive_law(scene.materials[scene.bodies[mesh.element_body[e]].material].strength).on();
  };
  // Rule 8 of cohesive_starts.h: the normal stress across a cohesive tip's line at the tip
  // reaches σt: at cover order n ≥ 1 the element ahead's own stress polynomial read at the tip; at
  // order 0 recovered from the two elements ahead on its line (their stresses at their inside
  // points' distances ahead, extrapolated linearly back to the tip).
  auto tip_stress_breaks = [&](std::size_t e1, const Tip& tip) {
    const double nx = -tip.dir.y, ny = tip.dir.x;
    auto s_nn = [&](std::size_t u) {
      return stress[3 * u] * nx * nx + stress[3 * u + 1] * ny * ny + 2 * stress[3 * u + 2] * nx * ny;
    };
    auto ahead = [&](std::size_t u) {
      const Vec2 c = inside_point(mesh, u);
      return (c.x - tip.at.x) * tip.dir.x + (c.y - tip.at.y) * tip.dir.y;
    };
    const double sigma_t = scene.materials[scene.bodies[mesh.element_body[e1]].material].strength.tensile;
    const double d1 = ahead(e1), s1 = s_nn(e1);
    double at_tip = s1;
    RayExit exit;
    if (order >= 1) {  // the element's own field is linear or better: read it at the tip
      const Vec2 x = current_point(mesh, s, order, e1, tip.at);
      const std::array<double, 3> sg = stress_at(mesh, order, s, e1, x.x, x.y);
      at_tip = sg[0] * nx * nx + sg[1] * ny * ny + 2 * sg[2] * nx * ny;
    } else if (ray_exit(mesh, e1, tip.at, tip.dir, tol, exit)) {
      const std::int32_t e2 = grid().at(plus(exit.at, 1e-6 * h, tip.dir));
      if (e2 >= 0 && !crossed_[static_cast<std::size_t>(e2)] && mesh.element_body[static_cast<std::size_t>(e2)] == mesh.element_body[e1] &&
          ratio_[static_cast<std::size_t>(e2)] > -std::numeric_limits<double>::infinity()) {
        const double d2 = ahead(static_cast<std::size_t>(e2)), s2 = s_nn(static_cast<std::size_t>(e2));
        if (d1 > 0 && d2 > d1 + 0.1 * h) at_tip = s1 + (s1 - s2) * d1 / (d2 - d1);
      }
    }
    if (trace_rules())
      std::fprintf(stderr, "TRACE tip stress step %lld tip (%.4f,%.4f) element %zu s_nn %.4g at the tip %.4g (sigma_t %.4g)\n",
                   static_cast<long long>(s.step), tip.at.x, tip.at.y, e1, s1, at_tip, sigma_t);
    return sigma_t > 0 && at_tip >= sigma_t;
  };
  // Rule 8e of cohesive_starts.h: the holding element ahead of a cohesive tip is the last rock on
  // its line (straight on, the line leaves it through a body boundary edge) and faces cut through
  // it is shut across the line (σ_nn ≤ 0: faces cut through it close and carry its compression by
  // contact) with a shear traction on the line the closed faces carry (|σ_tn| below their least
  // shear strength β·σt, β = 1, friction left out): the cut changes nothing while the rock there
  // holds, and it takes away a hinge one element wide that a bending member's compression zone
  // (the reference's one node, docs/cohesive_beam_reference.py) is not.
  auto last_ligament = [&](std::size_t e1, const Tip& tip) {
    RayExit exit;
    if (!ray_exit(mesh, e1, tip.at, tip.dir, tol, exit)) return false;
    const CrackEnd c = crack_end(mesh, e1, tip.at, exit);
    if (!c.stops || (mesh.loop_edge_origin[static_cast<std::size_t>(c.stop_edge)] & kEdgeBoundary) == 0) return false;
    const double tx = tip.dir.x, ty = tip.dir.y, nx = -ty, ny = tx;
    const double sxx = stress[3 * e1], syy = stress[3 * e1 + 1], sxy = stress[3 * e1 + 2];
    const double s_nn = sxx * nx * nx + syy * ny * ny + 2 * sxy * nx * ny;
    const double s_tn = sxx * tx * nx + syy * ty * ny + sxy * (tx * ny + ty * nx);
    const double sigma_t = scene.materials[scene.bodies[mesh.element_body[e1]].material].strength.tensile;
    if (trace_rules())
      std::fprintf(stderr, "TRACE last ligament step %lld tip (%.4f,%.4f) element %zu to (%.4f,%.4f) s_nn %.4g s_tn %.4g\n",
                   static_cast<long long>(s.step), tip.at.x, tip.at.y, e1, c.cut_to.x, c.cut_to.y, s_nn, s_tn);
    return s_nn <= 0 && std::abs(s_tn) < sigma_t;
  };
  auto grow = [&](Tip& tip, int forced, CrackMode drive, bool band = false) {
    bool bridged = band;  // the holding elements ahead were weighed (bridge) once this growth
    bool recovered = false;  // rule 8 let it cross one holding element
    for (std::size_t guard = 0; guard < n; ++guard) {
      const std::int32_t e = grid().at(plus(tip.at, 1e-6 * h, tip.dir));
      if (e < 0) {
        tip.active = false;
        return;
      }
      if (crossed_[e] || !(ratio_[e] > -std::numeric_limits<double>::infinity())) return;
      const bool holds = ratio_[e] < 1;
      if (holds && forced <= 0 && !may_start.empty() && trace_rules())
        std::fprintf(stderr, "TRACE holds step %lld tip (%.4f,%.4f) dir (%.3f,%.3f) crack %d element %d ratio %.4f snn %.4g area %.3g h2\n",
                     static_cast<long long>(s.step), tip.at.x, tip.at.y, tip.dir.x, tip.dir.y, tip.crack, e, ratio_[e],
                     stress[3 * e] * tip.dir.y * tip.dir.y + stress[3 * e + 1] * tip.dir.x * tip.dir.x -
                         2 * stress[3 * e + 2] * tip.dir.x * tip.dir.y,
                     element_area(mesh, static_cast<std::size_t>(e)) / (h * h));
      if (holds && forced <= 0 && !band && !recovered && cohesive_rock(static_cast<std::size_t>(e)) &&
          (tip_stress_breaks(static_cast<std::size_t>(e), tip) || last_ligament(static_cast<std::size_t>(e), tip))) {
        // Rule 8 of cohesive_starts.h: straight on through it, as rule 4's band crosses, one
        // element a solution (the next is weighed on the solution with this one cut).
        forced = 1;
        bridged = recovered = true;
      }
      if (holds && forced <= 0) return;
      if (holds && !bridged) {  // only as a rock bridge to a stop (tip_drive.h)
        const int span = bridge(tip, drive);
        if (span < 0) return;
        forced = span;
        bridged = true;
      }
      if (holds) --forced;
      // In a material with a toughness the tip's own field decides (tip_growth.h), not the
      // element ahead's stress: the strength rule only starts cracks there.
      const MaterialDef& ahead = scene.materials[scene.bodies[mesh.element_body[e]].material];
      if (ahead.strength.toughness > 0) return;
      Vec2 d = holds ? tip.dir : direction(static_cast<std::size_t>(e), tip.dir);
      // In rock that softens a tensile tip kinks by Erdogan & Sih's rule read from the element's
      // traction on the tip's line (rule 8d of cohesive_starts.h), not along the element's own σ1,
      // where the element is pulled open across that line; one shut across it keeps its own.
      const std::size_t u = static_cast<std::size_t>(e);
      const double tx = tip.dir.x, ty = tip.dir.y, nx = -ty, ny = tx;
      const double s_nn = stress[3 * u] * nx * nx + stress[3 * u + 1] * ny * ny + 2 * stress[3 * u + 2] * nx * ny;
      if (!holds && cohesive_rock(u) && failure_[u].mode == CrackMode::tensile && s_nn > 0) {
        const double s_tn = stress[3 * u] * tx * nx + stress[3 * u + 1] * ty * ny + stress[3 * u + 2] * (tx * ny + ty * nx);
        const double kink = mts_angle(s_nn, s_tn), c = std::cos(kink), sn = std::sin(kink);
        d = Vec2{c * tx - sn * ty, sn * tx + c * ty};
      }
      // In rock that softens a tip that only clips an element's corner (straight on it would
      // leave within kCornerClip·h) or crosses a sliver (rule 5 of cohesive_starts.h) goes on
      // straight: the element's constant stress belongs to rock mostly off the crack's line.
      // Petersson's beam at h 0.0167 m: a tip passing a lattice node turned with each triangle
      // round it, curled through five pieces 0.1–0.2 mm long and stopped on its own face.
      if (!may_start.empty() && !holds) {
        RayExit straight;
        if (element_area(mesh, static_cast<std::size_t>(e)) < kDebrisArea * h * h ||
            (ray_exit(mesh, static_cast<std::size_t>(e), tip.at, tip.dir, tol, straight) &&
             std::hypot(straight.at.x - tip.at.x, straight.at.y - tip.at.y) < kCornerClip * h))
          d = tip.dir;
      }
      RayExit exit;
      if (!ray_exit(mesh, static_cast<std::size_t>(e), tip.at, d, tol, exit)) {
        // A band's crack whose element's own direction leaves it at once from the tip (a tip at
        // its vertex) goes on straight, as it came to it (rule 4 of cohesive_starts.h), instead
        // of stopping there for good (Petersson's beam at h 0.0125 m: 500 steps).
        if (!(band || cohesive_rock(static_cast<std::size_t>(e))) || holds ||
            !ray_exit(mesh, static_cast<std::size_t>(e), tip.at, tip.dir, tol, exit))
          return;
        d = tip.dir;
      }
      const CrackEnd c = crack_end(mesh, static_cast<std::size_t>(e), tip.at, exit);
      add(static_cast<std::size_t>(e), tip.at, c.cut_to, tip.crack, holds ? drive : failure_[e].mode);
      const double dx = c.at.x - tip.at.x, dy = c.at.y - tip.at.y, l = std::hypot(dx, dy);
      tip.at = c.tip;
      tip.dir = l > 0 ? Vec2{dx / l, dy / l} : d;
      if (c.stops) {
        tip.active = false;
        return;
      }
    }
  };
  for (std::size_t t = 0; t < tips_.size(); ++t)
    if (tips_[t].active) grow(tips_[t], 0, CrackMode::tensile);
  // At most one new crack, and only where no crack grew: the step is solved again with what grew
  // (time_stepper.cpp attempt), and the stress a grown crack relieves must not start another.
  if (!out.empty()) return out;
  // The candidates: armed elements beyond their strength (a new crack through the element), and
  // disarmed ones whose crack has not parted them (rule 4: its tips grow on instead), each with
  // the active tips at the ends of the crack cut through its triangle.
  std::vector<std::int32_t> candidates;
  std::vector<std::vector<std::size_t>> regrow(over_.size());
  {
    std::vector<Vec2> ends_a, ends_b;
    std::unique_ptr<CrackEnds> ends;  // once, for every element below that needs it
    for (std::size_t i = 0; i < over_.size(); ++i) {
      const std::size_t e = static_cast<std::size_t>(over_[i]);
      if (crossed_[e]) continue;
      if (armed_[e]) {
        candidates.push_back(over_[i]);
        continue;
      }
      if (!parted_ || !parted_->of(mesh)) parted_ = std::make_shared<const TriangleElements>(mesh);
      if (!parted_->shares_a_cover(mesh, e, first_crack)) continue;
      if (!ends) {
        for (const CrackSegment& c : segments_) ends_a.push_back(c.a), ends_b.push_back(c.b);
        ends = std::make_unique<CrackEnds>(ends_a, ends_b);
      }
      const std::vector<std::size_t> chain =
          cracks_through_triangle(mesh, static_cast<std::size_t>(mesh.element_triangle[e]), *ends);
      for (std::size_t t = 0; t < tips_.size(); ++t) {
        if (!tips_[t].active) continue;
        for (const std::size_t k : chain)
          if (tips_[t].at == ends_a[k] || tips_[t].at == ends_b[k]) {
            regrow[i].push_back(t);
            break;
          }
      }
      if (!regrow[i].empty()) candidates.push_back(over_[i]);
    }
  }
  // The highest ratio, and of the ratios within kTie of it the lowest index: in a uniform field
  // the ratios differ in their last bits, which the BLAS kernel decides. A re-armed element whose
  // crack's tips cannot grow (the element ahead cannot break, or is crossed) yields to the next.
  constexpr double kTie = 1e-9;
  constexpr int kReach = 3;
  std::int32_t best = -1;
  for (;;) {
    best = -1;
    double highest = 0;
    for (const std::int32_t e : candidates) highest = std::max(highest, ratio_[static_cast<std::size_t>(e)]);
    for (const std::int32_t e : candidates)  // ascending
      if (ratio_[static_cast<std::size_t>(e)] >= highest / (1 + kTie)) {
        best = e;
        break;
      }
    if (best >= 0 && armed_[static_cast<std::size_t>(best)]) {
      // An element straight ahead of an active tip, within kReach elements of it, is that
      // crack's to break: the tip grows on to it through the elements between, even where they
      // hold (their stress averages the tip's concentration away), instead of a second crack
      // starting in line with the first (rule 5; the 4 m bar of tests/test_fracture.cpp on the
      // Prescott kernels started one two elements ahead of its first crack's tip).
      std::size_t tip = tips_.size();
      int between = kReach;
      for (std::size_t t = 0; t < tips_.size(); ++t) {
        if (!tips_[t].active) continue;
        Vec2 p = tips_[t].at;
        for (int k = 0; k < between; ++k) {
          const std::int32_t el = grid().at(plus(p, 1e-6 * h, tips_[t].dir));
          if (el < 0 || crossed_[el]) break;
          if (el == best) {
            tip = t, between = k;
            break;
          }
          RayExit exit;
          if (!ray_exit(mesh, static_cast<std::size_t>(el), p, tips_[t].dir, tol, exit)) break;
          p = exit.at;
        }
      }
      if (tip < tips_.size()) {
        grow(tips_[tip], between, failure_[static_cast<std::size_t>(best)].mode);
        if (trace_rules())
          std::fprintf(stderr, "TRACE in line step %lld element %d tip %zu crack %d between %d: %zu segments\n",
                       static_cast<long long>(s.step), best, tip, tips_[tip].crack, between, out.size());
        if (!out.empty()) return out;
      }
    }
    // In rock that softens, an element in the band ahead of an active tip is that crack's
    // (rule 4 of cohesive_starts.h): the nearest such tip grows straight on to its level across
    // the elements between that hold, then on through those that break.
    if (best >= 0 && armed_[static_cast<std::size_t>(best)] && !may_start.empty() &&
        (may_start[static_cast<std::size_t>(best)] & kMayBeReached)) {
      const std::size_t e = static_cast<std::size_t>(best);
      const MaterialDef& m = scene.materials[scene.bodies[mesh.element_body[e]].material];
      const double reach = characteristic_length(m.young, m.strength);  // m, l_ch
      std::size_t tip = tips_.size();
      double nearest = std::numeric_limits<double>::infinity(), along = 0;
      for (std::size_t t = 0; t < tips_.size(); ++t)
        if (tips_[t].active && in_crack_band(mesh, e, tips_[t].at, tips_[t].dir, 0.5 * h, reach, along) &&
            along < nearest)
          tip = t, nearest = along;
      if (tip < tips_.size()) {
        // The holding elements on the tip's line up to the one that spans best's level.
        int holding = 0;
        Vec2 p = tips_[tip].at;
        for (std::size_t guard = 0; guard < n; ++guard) {
          const std::int32_t el = grid().at(plus(p, 1e-6 * h, tips_[tip].dir));
          if (el < 0 || crossed_[el] || !(ratio_[el] > -std::numeric_limits<double>::infinity())) break;
          RayExit exit;
          if (!ray_exit(mesh, static_cast<std::size_t>(el), p, tips_[tip].dir, tol, exit)) break;
          if (ratio_[el] < 1) ++holding;
          p = exit.at;
          const double travelled = (p.x - tips_[tip].at.x) * tips_[tip].dir.x + (p.y - tips_[tip].at.y) * tips_[tip].dir.y;
          if (travelled >= nearest) break;
        }
        grow(tips_[tip], holding, failure_[e].mode, true);
        // The element's failure is this crack's from now on, wherever across the band the crack
        // passed it: disarmed as a crossed element is (rule 5 of fracture.h), not left to start a
        // crack of its own beside the one that reached it.
        if (!out.empty()) crossed_[e] = 1;
        if (trace_rules())
          std::fprintf(stderr, "TRACE band step %lld element %d ratio %.5f tip %zu crack %d %.4f m ahead, %d holding: %zu segments\n",
                       static_cast<long long>(s.step), best, ratio_[e], tip, tips_[tip].crack, nearest, holding,
                       out.size());
        if (!out.empty()) return out;
      }
    }
    // An armed element no tip took that may not start a crack (may_start) yields to the next.
    if (best >= 0 && armed_[static_cast<std::size_t>(best)] && !may_start.empty() &&
        !(may_start[static_cast<std::size_t>(best)] & kMayStart)) {
      candidates.erase(std::find(candidates.begin(), candidates.end(), best));
      continue;
    }
    if (best < 0 || armed_[static_cast<std::size_t>(best)]) break;
    // Its crack grows on from its tips, through one element each even where it holds, then on
    // through those that break: the step is solved again on it.
    const std::size_t i = static_cast<std::size_t>(std::find(over_.begin(), over_.end(), best) - over_.begin());
    // In rock that softens, a tip that lies inside the star of a node whose cover the crack has
    // not parted at `best` (crack_parting.h) crosses the holding element ahead without a bridge
    // (rule 8 of cohesive_starts.h): a crack that ends inside a star cannot open, and a cohesive
    // face cut through rock that holds carries its stress on its elastic branch. Not where that
    // element is shut across the tip's line (σ_nn ≤ 0, tip_drive.h): a tensile crack does not run
    // into rock its bending compresses — Petersson's beam at cover order 1, h 0.0167 m, crossed
    // the compressed top (σ_nn −2.8 to −9.6 MPa) to 1.3 mm below the top edge in one step, a piece
    // a solution, and the contact solve on it failed (the run stopped at 0.682 mm).
    auto ahead_opens = [&](const Tip& tip) {
      const std::int32_t el = grid().at(plus(tip.at, 1e-6 * h, tip.dir));
      if (el < 0) return true;  // grow() ends the tip there
      const std::size_t u = static_cast<std::size_t>(el);
      return ratio_[u] >= 1 || pulls_line_open(stress[3 * u], stress[3 * u + 1], stress[3 * u + 2], tip.dir);
    };
    const unsigned tying = cohesive_rock(static_cast<std::size_t>(best))
                               ? parted_->shared_nodes(mesh, static_cast<std::size_t>(best), first_crack)
                               : 0u;
    for (const std::size_t t : regrow[i])
      grow(tips_[t], 1, failure_[static_cast<std::size_t>(best)].mode,
           tying != 0 && inside_star(mesh, static_cast<std::size_t>(best), tying, tips_[t].at) &&
               ahead_opens(tips_[t]));
    if (trace_rules())
      std::fprintf(stderr, "TRACE re-armed step %lld element %d ratio %.4f tips %zu: %zu segments\n",
                   static_cast<long long>(s.step), best, ratio_[static_cast<std::size_t>(best)], regrow[i].size(),
                   out.size());
    if (!out.empty()) return out;
    candidates.erase(std::find(candidates.begin(), candidates.end(), best));
  }
  if (best >= 0) {
    std::size_t e = static_cast<std::size_t>(best);
    Vec2 p = inside_point(mesh, e);
    Vec2 d = direction_as_cut(mesh, s, order, e, failure_[e].direction);
    // At a gap's end whose covers reach round it (rule 7 of cohesive_starts.h) the element's
    // stress is the gap's opening smeared over it, not the tip's field: the crack leaves from the
    // gap's end along its bisector, in the element there, through the middle of the chord it cuts.
    Vec2 gap_at, gap_dir;
    if (!may_start.empty() && (may_start[e] & kGapEnd) && gap_end(mesh, scene, e, gap_at, gap_dir)) {
      const std::int32_t there = grid().at(plus(gap_at, 1e-6 * h, gap_dir));
      RayExit probe;
      if (there >= 0 && !crossed_[static_cast<std::size_t>(there)] && may_start[static_cast<std::size_t>(there)] != 0 &&
          ray_exit(mesh, static_cast<std::size_t>(there), plus(gap_at, 1e-6 * h, gap_dir), gap_dir, 0, probe)) {
        e = static_cast<std::size_t>(there);
        p = {0.5 * (gap_at.x + probe.at.x), 0.5 * (gap_at.y + probe.at.y)};
        d = gap_dir;
      } else if (may_start[e] & kGapOnly) {
        return out;  // the gap's end is cracked or holds a face already: a piece tied round it starts nothing
      }
    }
    RayExit fwd, back;
    if (ray_exit(mesh, e, p, d, 0, fwd) && ray_exit(mesh, e, p, {-d.x, -d.y}, 0, back)) {
      const std::int32_t crack = cracks_++;
      if (trace_rules())
        std::fprintf(stderr, "TRACE start step %lld crack %d in element %zu ratio %.5f\n", static_cast<long long>(s.step),
                     crack, e, ratio_[e]);
      // Each end as a crack leaving the element from the other end (on its edge's grid, so that
      // the forward end's overshoot is taken along a line both kernel families agree on).
      const CrackEnd f = crack_end(mesh, e, on_grid(mesh, e, back).at, fwd), r = crack_end(mesh, e, f.at, back);
      add(e, r.cut_to, f.cut_to, crack, failure_[static_cast<std::size_t>(best)].mode);
      const std::size_t first = tips_.size();
      for (const auto& [end, dir] : {std::make_pair(f, d), std::make_pair(r, Vec2{-d.x, -d.y})})
        tips_.push_back({end.tip, dir, crack, !end.stops});
      for (std::size_t t = first; t < tips_.size(); ++t)
        if (tips_[t].active) grow(tips_[t], 0, CrackMode::tensile);
    }
  }
  return out;
}

std::vector<CrackSegment> Fracture::growing_segments() const {
  std::vector<std::uint8_t> growing(static_cast<std::size_t>(cracks_), 0);
  for (const Tip& t : tips_)
    if (t.active && t.crack >= 0 && t.crack < cracks_) growing[static_cast<std::size_t>(t.crack)] = 1;
  std::vector<CrackSegment> out;
  for (const CrackSegment& c : segments_)
    if (c.crack >= 0 && c.crack < cracks_ && growing[static_cast<std::size_t>(c.crack)]) out.push_back(c);
  return out;
}

void Fracture::cut(const std::vector<CrackSegment>& segments, const Mesh& mesh, const pre::RecutMap& map) {
  segments_.insert(segments_.end(), segments.begin(), segments.end());
  const std::size_t n = mesh.element_count();
  std::vector<std::uint8_t> armed(n, 1), debris(n, 0);
  // Blocks holding an element in a triangle the segments touched are new (a segment's overshoot
  // past the edge it stops on may clip a corner off the element beyond: a crossed element's
  // neighbour): those below kDebrisArea·h² are debris.
  std::vector<std::uint8_t> touched(mesh.triangle_count(), 0);
  for (const std::int32_t t : map.cut_triangles) touched[static_cast<std::size_t>(t)] = 1;
  std::vector<double> block_area(mesh.block_count(), 0.0);
  std::vector<std::int32_t> block_elements(mesh.block_count(), 0);
  std::vector<std::uint8_t> block_new(mesh.block_count(), 0), block_old_debris(mesh.block_count(), 1);
  for (std::size_t e = 0; e < n; ++e) {
    const std::size_t p = static_cast<std::size_t>(map.element_parent[e]);
    armed[e] = crossed_[p] ? 0 : armed_[p];
    debris[e] = debris_.empty() ? 0 : debris_[p];
    const std::size_t b = static_cast<std::size_t>(mesh.element_block[e]);
    block_area[b] += element_area(mesh, e);
    ++block_elements[b];
    block_new[b] = block_new[b] || crossed_[p] || touched[static_cast<std::size_t>(mesh.element_triangle[e])];
    block_old_debris[b] = block_old_debris[b] && debris[e];
  }
  const double limit = kDebrisArea * mesh.mesh_size * mesh.mesh_size;
  const double sliver = kSliverArea * mesh.mesh_size * mesh.mesh_size;
  std::vector<std::uint8_t> block_debris(mesh.block_count(), 0);
  for (std::size_t b = 0; b < block_area.size(); ++b) {
    if (block_new[b] && !block_old_debris[b] && block_elements[b] <= 3 && trace_rules())
      std::fprintf(stderr, "TRACE new block %zu: %d elements, %.4g m2 = %.4g h2%s\n", b, block_elements[b],
                   block_area[b], block_area[b] / (mesh.mesh_size * mesh.mesh_size),
                   block_area[b] < limit || (block_elements[b] == 1 && block_area[b] < sliver) ? ": debris" : "");
    if (block_new[b] && !block_old_debris[b] &&
        (block_area[b] < limit || (block_elements[b] == 1 && block_area[b] < sliver))) {
      block_debris[b] = 1;
      ++debris_blocks_;
      debris_area_ += block_area[b];
    }
  }
  for (std::size_t e = 0; e < n; ++e)
    debris[e] = debris[e] || block_debris[static_cast<std::size_t>(mesh.element_block[e])];
  // An element of next to no area none of whose covers reaches beyond a speck is debris too,
  // whatever its block: nothing significant moves it (cover_unknowns.cpp ties a small cover to a
  // significant one of its element, and it has none), so its covers would be left with no
  // stiffness or mass of any size (a needle of 7.8e-20 m² whose edges to the rest round to
  // points stopped a dynamic uniaxial run as "not positive definite").
  {
    std::vector<double> support(mesh.cover_count(), 0.0);
    std::vector<double> area(n);
    for (std::size_t e = 0; e < n; ++e) {
      area[e] = element_area(mesh, e);
      for (int k = 0; k < 3; ++k) support[static_cast<std::size_t>(mesh.element_covers[3 * e + k])] += area[e];
    }
    const double least = kLeastCoverSupport * mesh.mesh_size * mesh.mesh_size;
    for (std::size_t e = 0; e < n; ++e) {
      if (debris[e] || area[e] >= limit) continue;
      bool held = false;
      for (int k = 0; k < 3; ++k) held = held || support[static_cast<std::size_t>(mesh.element_covers[3 * e + k])] >= least;
      if (held) continue;
      debris[e] = 1;
      debris_area_ += area[e];
    }
  }
  armed_ = std::move(armed);
  debris_ = std::move(debris);
  crossed_.clear();
  grid_.reset();  // of the mesh before the cut
  parted_.reset();
}

std::string Fracture::save() const {
  ByteWriter w;
  w.put<std::uint8_t>(tips_started_ ? 1 : 0);
  w.put<std::int32_t>(cracks_);
  w.put<std::uint64_t>(tips_.size());
  for (const Tip& t : tips_) {
    w.put(t.at.x), w.put(t.at.y), w.put(t.dir.x), w.put(t.dir.y);
    w.put<std::int32_t>(t.crack);
    w.put<std::uint8_t>(t.active ? 1 : 0);
  }
  w.put_vector(armed_);
  w.put_vector(debris_);
  w.put<std::int32_t>(debris_blocks_);
  w.put(debris_area_);
  w.put<std::uint64_t>(segments_.size());
  for (const CrackSegment& c : segments_) {
    for (const Vec2& p : {c.a, c.b, c.a_now, c.b_now}) w.put(p.x), w.put(p.y);
    w.put<std::uint8_t>(c.mode == CrackMode::tensile ? 0 : 1);
    w.put<std::int32_t>(c.crack);
    w.put<std::int64_t>(c.step);
    w.put(c.time);
  }
  return w.take();
}

void Fracture::load(const std::string& bytes, const Mesh& mesh, const std::string& name) {
  ByteReader r(bytes, name, "FRACTURE");
  tips_started_ = r.get<std::uint8_t>() != 0;
  cracks_ = r.get<std::int32_t>();
  const std::uint64_t tips = r.get<std::uint64_t>();
  if (tips > bytes.size()) r.fail("too many tips");
  tips_.clear();
  for (std::uint64_t i = 0; i < tips; ++i) {
    Tip t;
    t.at.x = r.get<double>(), t.at.y = r.get<double>(), t.dir.x = r.get<double>(), t.dir.y = r.get<double>();
    t.crack = r.get<std::int32_t>();
    t.active = r.get<std::uint8_t>() != 0;
    tips_.push_back(t);
  }
  armed_ = r.get_vector<std::uint8_t>(mesh.element_count(), "armed elements");
  debris_ = r.get_vector<std::uint8_t>(mesh.element_count(), "debris elements");
  for (const std::uint8_t d : debris_)
    if (d > 1) r.fail("a debris flag is neither 0 nor 1");
  debris_blocks_ = r.get<std::int32_t>();
  debris_area_ = r.get<double>();
  const std::uint64_t segments = r.get<std::uint64_t>();
  if (segments > bytes.size()) r.fail("too many crack segments");
  segments_.clear();
  for (std::uint64_t i = 0; i < segments; ++i) {
    CrackSegment c;
    for (Vec2* p : {&c.a, &c.b, &c.a_now, &c.b_now}) p->x = r.get<double>(), p->y = r.get<double>();
    const std::uint8_t mode = r.get<std::uint8_t>();
    if (mode > 1) r.fail("crack mode " + std::to_string(mode) + " is neither tensile (0) nor shear (1)");
    c.mode = mode == 0 ? CrackMode::tensile : CrackMode::shear;
    c.crack = r.get<std::int32_t>();
    c.step = r.get<std::int64_t>();
    c.time = r.get<double>();
    segments_.push_back(c);
  }
  r.expect_end();
  active_ = true;
  grid_.reset();
  parted_.reset();
}

}  // namespace nmm::solve
