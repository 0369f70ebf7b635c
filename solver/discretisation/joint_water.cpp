// Water pressure in the joints (docs/contact.md "Water in the joints", docs/physics.md §4).
//
// Heights are measured against gravity, z = −ĝ·x, and positions across it, s = x·(−ĝy) + y·ĝx
// (gravity straight down: z = y, s = x), so a scene built in a turned frame (gravity turned by a
// dip) keeps its water level horizontal. γw = ρw·|g|.
//   phreatic surface  p(x) = γw·max(0, z_w(s) − z),  z_w the polyline's height at s (held at its
//                     end heights beyond its ends): hydrostatic below the water table;
//   joint filled      p(x) = γw·max(0, z_min + d − z),  z_min the joint's lowest point, d the
//                     fill depth (a tension crack filled to a depth);
//   pressure table    p = the table's value at the distance along the joint from its first
//                     point (linear between rows, held beyond them; one row: uniform).
// A per-joint entry replaces the phreatic surface on that joint's faces. Water acts on both
// faces of a joint and on every body boundary (outer faces under the water table, faces between
// bodies): on a face with outward normal n the traction is t = −p·n, integrated over the face
// with the element's shape functions like a boundary traction (boundary_conditions.h), at the
// face's current position. The two faces of a closed joint get equal and opposite forces, so
// the contact spring between them carries σn − p: the effective normal stress of the friction
// law (Terzaghi). Water is a load: strength reduction (nmm-fos) keeps it.
// Its work on the rock in a step (energy.csv load_work): W_water = Σ_wet faces ∫ −p·n·Δu ds, p at
// the step's end on the face's current position, Δu the step's displacement, linear along the
// edge; the two-point Gauss rule on each piece where p is linear is exact.
#include "solver/discretisation/joint_water.h"

#include "solver/discretisation/model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nmm::solve {

JointWater::JointWater(const Mesh& mesh, const SceneDef& scene) : scene_(&scene) {
  const WaterDef& w = scene.water;
  active_ = w.present && (!w.phreatic.empty() || !w.joints.empty());
  if (!active_) return;
  const double g = scene.has_gravity ? std::hypot(scene.gravity.x, scene.gravity.y) : 0.0;
  if (g > 0) {
    gx_ = scene.gravity.x / g;
    gy_ = scene.gravity.y / g;
  }
  gamma_ = w.density * g;
  for (const Vec2& p : w.phreatic) {
    ph_s_.push_back(across(p.x, p.y));
    ph_z_.push_back(height(p.x, p.y));
  }
  if (ph_s_.size() > 1 && ph_s_.front() > ph_s_.back()) {  // ascending in s (monotone: common/scene/water.cpp)
    std::reverse(ph_s_.begin(), ph_s_.end());
    std::reverse(ph_z_.begin(), ph_z_.end());
  }
  entry_.assign(scene.joints.size(), -1);
  for (std::size_t i = 0; i < w.joints.size(); ++i) {
    const JointWaterDef& e = w.joints[i];
    entry_[static_cast<std::size_t>(e.joint)] = static_cast<int>(i);
    double low = std::numeric_limits<double>::infinity();
    for (const Vec2& p : scene.joints[static_cast<std::size_t>(e.joint)].points)
      low = std::min(low, height(p.x, p.y));
    fill_top_.push_back(low + e.fill_depth);
  }
  const std::size_t ne = mesh.element_count();
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t first = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    for (std::int32_t v = first; v < end; ++v) {
      const std::uint8_t o = mesh.loop_edge_origin[v];
      if ((o & (kEdgeJoint | kEdgeBoundary)) == 0 || (o & kEdgeBridge) != 0) continue;
      const std::int32_t next = v + 1 < end ? v + 1 : first;
      edges_.push_back({static_cast<std::int32_t>(e), v, next, 0, 0});
      edge_joint_.push_back((o & kEdgeJoint) != 0 ? mesh.loop_edge_joint[v] : -1);
    }
  }
}

double JointWater::phreatic_height(double s) const {
  if (s <= ph_s_.front()) return ph_z_.front();
  if (s >= ph_s_.back()) return ph_z_.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(ph_s_.begin(), ph_s_.end(), s) - ph_s_.begin());
  const double t = (s - ph_s_[k - 1]) / (ph_s_[k] - ph_s_[k - 1]);
  return ph_z_[k - 1] + t * (ph_z_[k] - ph_z_[k - 1]);
}

double JointWater::along_joint(int joint, double x, double y) const {
  // Distance from the joint's first point to the point's projection on its nearest segment.
  const std::vector<Vec2>& p = scene_->joints[static_cast<std::size_t>(joint)].points;
  double best = std::numeric_limits<double>::infinity(), at = 0, before = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = p[i + 1].x - p[i].x, dy = p[i + 1].y - p[i].y, l = std::hypot(dx, dy);
    const double t = std::clamp(((x - p[i].x) * dx + (y - p[i].y) * dy) / (l * l), 0.0, 1.0);
    const double d = std::hypot(p[i].x + t * dx - x, p[i].y + t * dy - y);
    if (d < best) {
      best = d;
      at = before + t * l;
    }
    before += l;
  }
  return at;
}

double JointWater::pressure_at(int joint, double x, double y) const {
  if (!active_) return 0;
  const int e = joint >= 0 && static_cast<std::size_t>(joint) < entry_.size() ? entry_[joint] : -1;
  if (e < 0) return ph_s_.empty() ? 0.0 : gamma_ * std::max(0.0, phreatic_height(across(x, y)) - height(x, y));
  const JointWaterDef& d = scene_->water.joints[static_cast<std::size_t>(e)];
  if (d.fill_depth >= 0) return gamma_ * std::max(0.0, fill_top_[static_cast<std::size_t>(e)] - height(x, y));
  const double s = along_joint(joint, x, y);
  if (s <= d.at.front()) return d.pressure.front();
  if (s >= d.at.back()) return d.pressure.back();
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(d.at.begin(), d.at.end(), s) - d.at.begin());
  const double t = (s - d.at[k - 1]) / (d.at[k] - d.at[k - 1]);
  return d.pressure[k - 1] + t * (d.pressure[k] - d.pressure[k - 1]);
}

std::vector<std::pair<double, double>> JointWater::linear_pieces(int joint, const double a[2],
                                                                 const double b[2]) const {
  // Break points in t: where a coordinate linear in t (s across gravity, or the distance along
  // the joint) passes a vertex of the piecewise linear level or table; then where the head
  // changes sign inside a piece (the water line).
  std::vector<double> t{0.0, 1.0};
  auto crossings = [&](double v0, double v1, const std::vector<double>& at) {
    if (v0 == v1) return;
    for (double v : at) {
      const double u = (v - v0) / (v1 - v0);
      if (u > 0 && u < 1) t.push_back(u);
    }
  };
  const int e = joint >= 0 && static_cast<std::size_t>(joint) < entry_.size() ? entry_[joint] : -1;
  if (e < 0) {
    crossings(across(a[0], a[1]), across(b[0], b[1]), ph_s_);
  } else if (scene_->water.joints[static_cast<std::size_t>(e)].fill_depth < 0) {
    crossings(along_joint(joint, a[0], a[1]), along_joint(joint, b[0], b[1]),
              scene_->water.joints[static_cast<std::size_t>(e)].at);
  }
  std::sort(t.begin(), t.end());
  std::vector<std::pair<double, double>> pieces;
  auto head = [&](double u) {
    const double x = a[0] + u * (b[0] - a[0]), y = a[1] + u * (b[1] - a[1]);
    if (e >= 0 && scene_->water.joints[static_cast<std::size_t>(e)].fill_depth >= 0)
      return fill_top_[static_cast<std::size_t>(e)] - height(x, y);
    return e < 0 && !ph_s_.empty() ? phreatic_height(across(x, y)) - height(x, y) : 1.0;
  };
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const double t0 = t[i], t1 = t[i + 1];
    if (!(t1 > t0)) continue;
    const double h0 = head(t0), h1 = head(t1);
    if ((h0 > 0) != (h1 > 0) && h0 != h1) {
      const double u = t0 + (t1 - t0) * h0 / (h0 - h1);
      if (u > t0 && u < t1) {
        pieces.emplace_back(t0, u);
        pieces.emplace_back(u, t1);
        continue;
      }
    }
    pieces.emplace_back(t0, t1);
  }
  return pieces;
}

void JointWater::energy_step(const EnergyStep& e, EnergyTerms& t) const {
  // ∫ −p·n·Δu ds on each wet face, per piece where p is linear: the two-point Gauss rule is exact
  // for p times the linear Δu.
  static constexpr double kGauss[2] = {0.21132486540518711775, 0.78867513459481288225};
  const RunState& s = e.s;
  const std::vector<double>& prev = e.last_loop_u;
  if (!active() || prev.size() != s.loop_u.size()) return;
  const Mesh& mesh = e.model.mesh();
  double w = 0;
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const BoundaryEdge& be = edges_[i];
    if (element_removed(mesh, s, be.element)) continue;
    const int joint = edge_joint_[i];
    const double* a = s.loop_xy.data() + 2 * be.vertex;
    const double* b = s.loop_xy.data() + 2 * be.next;
    const double dx = b[0] - a[0], dy = b[1] - a[1], len = std::hypot(dx, dy);
    if (!(len > 0)) continue;
    const double nx = dy / len, ny = -dx / len;  // CCW loop: outside on the right
    for (const auto& [t0, t1] : linear_pieces(joint, a, b))
      for (double xi : kGauss) {
        const double u = t0 + xi * (t1 - t0);
        const double p = pressure_at(joint, a[0] + u * dx, a[1] + u * dy);
        for (int d = 0; d < 2; ++d) {
          const double du_a = s.loop_u[2 * be.vertex + d] - prev[2 * be.vertex + d];
          const double du_b = s.loop_u[2 * be.next + d] - prev[2 * be.next + d];
          w += 0.5 * (t1 - t0) * len * (-p) * (d == 0 ? nx : ny) * ((1 - u) * du_a + u * du_b);
        }
      }
  }
  t.work += w;
}

}  // namespace nmm::solve
