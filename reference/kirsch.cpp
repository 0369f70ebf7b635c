// The Kirsch opening: scene and closed form (kirsch.h has the equations).
#include "reference/kirsch.h"

#include <cmath>
#include <vector>

#include "common/math_constants.h"

namespace nmm::reference {

namespace {
constexpr int kArcSides = 48;  // polygon sides per quarter circle
}  // namespace

SceneDef kirsch_scene(const KirschSetup& k) {
  const double a = kKirschRadius, b = k.b_over_a * a, py = kKirschPressure, px = k.k0 * py;
  SceneDef s;
  s.materials.push_back({"rock", 2500, kKirschYoung, kKirschPoisson, {}});
  s.mesh_size = k.h;
  s.plane = PlaneKind::strain;
  std::vector<Vec2> arc;  // from (a, 0) to (0, a)
  for (int i = 0; i <= kArcSides; ++i) {
    const double t = 0.5 * kPi * i / kArcSides;
    arc.push_back({a * std::cos(t), a * std::sin(t)});
  }
  arc.front() = {a, 0};
  arc.back() = {0, a};
  BodyDef rock;
  rock.material = 0;
  rock.outer = {{a, 0}, {b, 0}, {b, b}, {0, b}};
  for (int i = kArcSides; i >= 0; --i) rock.outer.push_back(arc[i]);
  rock.outer.pop_back();  // (a, 0) is already the first point
  s.bodies = {rock};
  if (k.with_core) {
    JointSetDef js;
    js.name = "interface";
    js.friction_deg = 30;
    js.normal.kn = 1e12;
    js.shear.ks = 4e11;
    s.joint_sets = {js};
    s.interface_set = 0;
    BodyDef core;
    core.material = 0;
    core.outer = {{0, 0}};
    for (const Vec2& q : arc) core.outer.push_back(q);
    s.bodies.push_back(core);
    s.excavate = {1};
  }
  s.insitu_stress.present = true;
  s.insitu_stress.sxx = -px;
  s.insitu_stress.syy = -py;
  TractionDef t;
  t.points = {{b, 0}, {b, b}, {0, b}};
  t.from_insitu = true;
  s.tractions = {t};
  // Rollers on the symmetry lines, stiff enough that their give (σ/k_s) is far below the error.
  SupportDef left, base;
  left.points = {{0, a}, {0, b}};
  left.fix_x = true;
  base.points = {{a, 0}, {b, 0}};
  base.fix_y = true;
  s.supports = {left, base};
  s.solver.support_stiffness = 1e4 * kKirschYoung / k.h;
  s.solver.dynamic = false;
  s.solver.static_mode = StaticMode::equilibrium;  // K d = F: the elastic answer in one step
  s.solver.cover_order = k.order;
  return s;
}

double kirsch_hoop(double px, double py, double r, double theta) {
  const double a = kKirschRadius, P = 0.5 * (px + py), Q = 0.5 * (px - py), ar2 = a * a / (r * r);
  return P * (1 + ar2) - Q * (1 + 3 * ar2 * ar2) * std::cos(2 * theta);
}

double kirsch_radial_displacement(double px, double py, double g, double nu, double r, double theta) {
  const double a = kKirschRadius;
  return a * a / (4 * g * r) * ((px + py) + (px - py) * (4 * (1 - nu) - a * a / (r * r)) * std::cos(2 * theta));
}

}  // namespace nmm::reference
