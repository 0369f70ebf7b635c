// Water in the joints (scene key "water"): a pressure p on both faces of each joint and on every
// body boundary, pushing each face into its rock. The contact springs then carry the effective
// normal stress σn' = σn − p, which is what the friction (and the Barton–Bandis strength) uses.
// Equations in joint_water.cpp; docs/contact.md "Water in the joints".
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "solver/discretisation/boundary_conditions.h"
#include "solver/discretisation/effect_energy.h"
#include "common/mesh.h"
#include "common/scene.h"

namespace nmm::solve {

class JointWater : public EffectEnergy {
 public:
  JointWater(const Mesh& mesh, const SceneDef& scene);

  /// True if the scene has water.
  bool active() const { return active_; }
  /// The faces water may act on: loop edges on a joint or a body boundary (bridges excluded).
  const std::vector<BoundaryEdge>& edges() const { return edges_; }
  /// [edge] joint of edges()[i], or -1 (a body boundary).
  const std::vector<std::int32_t>& edge_joint() const { return edge_joint_; }

  /// Water pressure (Pa, ≥ 0) at the point (x, y) (m) of a face on `joint` (-1: not on a joint).
  double pressure_at(int joint, double x, double y) const;

  /// The pieces [t0, t1] ⊂ [0, 1] of the segment a → b on which the pressure is linear in t
  /// (the phreatic surface's vertices, a table's rows and the water line split it); a Gauss
  /// rule on each integrates the face force exactly.
  std::vector<std::pair<double, double>> linear_pieces(int joint, const double a[2], const double b[2]) const;

  /// Energy (effect_energy.h): the work of the pressure on the wet faces in the step, into t.work
  /// (joint_water.cpp: W_water).
  void energy_step(const EnergyStep& e, EnergyTerms& t) const override;

 private:
  // Height above the origin against gravity and position across it, m.
  double height(double x, double y) const { return -(x * gx_ + y * gy_); }
  double across(double x, double y) const { return -x * gy_ + y * gx_; }
  double phreatic_height(double s) const;
  double along_joint(int joint, double x, double y) const;

  bool active_ = false;
  double gamma_ = 0;          // N/m³, ρw·|g|
  double gx_ = 0, gy_ = -1;   // –, unit gravity direction
  std::vector<double> ph_s_, ph_z_;  // m, phreatic surface: across-gravity position (ascending), height
  const SceneDef* scene_ = nullptr;
  std::vector<int> entry_;         // [joint] index into scene.water.joints, or -1
  std::vector<double> fill_top_;   // [entry] m, water height of a filled joint (fill_depth ≥ 0)
  std::vector<BoundaryEdge> edges_;
  std::vector<std::int32_t> edge_joint_;
};

/// Adds the water's face forces to the step's right-hand side: for each wetted face edge of a
/// present element, edge_traction_forces() of t = −p·n on each piece where p is linear.
/// frame_of(element) gives its EdgeFrame, add_force(element, forces, 1.0) adds them.
template <class FrameOf, class AddForce>
void add_water_forces(const JointWater& water, const double* xy, const std::vector<std::uint8_t>& removed,
                      FrameOf frame_of, AddForce add_force) {
  if (!water.active()) return;
  for (std::size_t i = 0; i < water.edges().size(); ++i) {
    const BoundaryEdge& be = water.edges()[i];
    if (!removed.empty() && removed[static_cast<std::size_t>(be.element)]) continue;
    const int joint = water.edge_joint()[i];
    const double* a = xy + 2 * be.vertex;
    const double* b = xy + 2 * be.next;
    for (const auto& [t0, t1] : water.linear_pieces(joint, a, b)) {
      const double p0[2] = {a[0] + t0 * (b[0] - a[0]), a[1] + t0 * (b[1] - a[1])};
      const double p1[2] = {a[0] + t1 * (b[0] - a[0]), a[1] + t1 * (b[1] - a[1])};
      const double mid[2] = {0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1])};
      if (water.pressure_at(joint, p0[0], p0[1]) == 0 && water.pressure_at(joint, p1[0], p1[1]) == 0 &&
          water.pressure_at(joint, mid[0], mid[1]) == 0)
        continue;  // dry
      add_force(be.element,
                edge_traction_forces(frame_of(be.element), p0, p1,
                                     [&](double x, double y, double nx, double ny, double* t) {
                                       const double p = water.pressure_at(joint, x, y);
                                       t[0] = -p * nx;
                                       t[1] = -p * ny;
                                     }),
                1.0);
    }
  }
}

}  // namespace nmm::solve
