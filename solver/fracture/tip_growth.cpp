// Crack tips that grow by their toughness (tip_growth.h). The rule, Erdogan & Sih (1963):
//     θ = 2·atan((K_I − √(K_I² + 8K_II²)) / (4K_II))            (interaction_integral.cpp)
//     K_eq = cos(θ/2)·(K_I·cos²(θ/2) − 3/2·K_II·sin θ)          grows when K_eq ≥ K_Ic
// with K_I ← max(K_I, 0) (K_eq is the tangential stress σθθ·√(2πr) in the direction θ, where
// it is largest; pure mode II: θ = ∓70.53°, K_eq = (2/√3)·|K_II|), by
// fracture.tip_step from the tip in the direction θ from the crack's own.
//
// A fluid-driven tip (fracture.viscous_tip, a scene with flow): near a tip moving at V through
// rock of negligible toughness, the viscous fluid's pressure drop gives the opening the
// M-asymptote (Desroches et al. 1994, Proc. R. Soc. A 447, 39–48; Garagash & Detournay 2000,
// J. Appl. Mech. 67, 183–192)
//     w(s) = β_m·(μ′V/E′)^(1/3)·s^(2/3),   β_m = 2^(1/3)·3^(5/6),   μ′ = 12μ,
// s the distance behind the tip, where LEFM gives w(s) = (K′/E′)·s^(1/2), K′ = √(32/π)·K_I. An
// element of one tip step cannot resolve the 2/3 power (the viscous suction sits within it), so
// the K the interaction integral reads there is the K that opens the crack by w at s = tip_step:
//     K_app = √(π/32)·β_m·E′^(2/3)·(μ′V)^(1/3)·s^(1/6),
// the apparent toughness of the moving tip. The tip grows when K_eq ≥ max(K_Ic, K_app), with
// V = tip_step/(t − t_last) the speed one more step at t would give (t_last when the tip last
// grew, the run's start for the end of a scene joint): a tip that just grew waits until the
// speed the fluid can sustain lets it go on. β_m is the M-vertex's own (reference/kgd.h: its
// tip coefficient Σ A_j·C_{2j−2}(1)·2^(2/3)·(3/2)^(1/3) = 3.10, within 1.4 % of β_m).
#include "solver/fracture/tip_growth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "common/math_constants.h"
#include "solver/discretisation/stress_field.h"
#include "solver/fracture/crack_tips.h"
#include "solver/fracture/interaction_integral.h"

namespace nmm::solve {

namespace {

// The parameter t in (t_min, 1] along p → q where it meets the segment a–b, or +∞.
double crossing(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, double t_min) {
  const double rx = q.x - p.x, ry = q.y - p.y, sx = b.x - a.x, sy = b.y - a.y;
  const double den = rx * sy - ry * sx;
  if (den == 0) return std::numeric_limits<double>::infinity();
  const double t = ((a.x - p.x) * sy - (a.y - p.y) * sx) / den;
  const double u = ((a.x - p.x) * ry - (a.y - p.y) * rx) / den;
  if (t <= t_min || t > 1 || u < 0 || u > 1) return std::numeric_limits<double>::infinity();
  return t;
}

}  // namespace

double apparent_toughness(double e_prime, double viscosity, double speed, double distance) {
  const double beta_m = std::cbrt(2.0) * std::pow(3.0, 5.0 / 6.0);
  return std::sqrt(kPi / 32) * beta_m * std::pow(e_prime, 2.0 / 3.0) * std::cbrt(12 * viscosity * speed) *
         std::pow(distance, 1.0 / 6.0);
}

double mts_equivalent_k(double k1, double k2, double theta) {
  const double c = std::cos(theta / 2);
  return c * (k1 * c * c - 1.5 * k2 * std::sin(theta));
}

bool any_toughness(const SceneDef& scene) {
  return std::any_of(scene.materials.begin(), scene.materials.end(),
                     [](const MaterialDef& m) { return m.strength.present && m.strength.toughness > 0; });
}

std::vector<CrackSegment> grow_by_toughness(const Mesh& mesh, const SceneDef& scene,
                                            const std::vector<CrackSegment>& cracks, const RunState& s,
                                            const std::vector<std::uint8_t>& skip,
                                            const std::vector<double>* face_pressure,
                                            const std::vector<std::uint8_t>* loaded) {
  std::vector<CrackSegment> out;
  if (!any_toughness(scene)) return out;
  const double h = mesh.mesh_size;
  const double step = scene.fracture.tip_step > 0 ? scene.fracture.tip_step : h;
  const bool viscous = scene.fracture.viscous_tip && scene.flow.present && face_pressure != nullptr;
  std::vector<std::array<Vec2, 2>> lines;
  for (const CrackSegment& c : cracks) lines.push_back({c.a, c.b});
  CrackTipFinder finder;
  const std::vector<CrackTip> tips = finder.find(mesh, scene, lines);
  // The elements' stresses the integral reads: at cover order n ≥ 1 their means (stress_field.h),
  // as crack_tips.csv reads them (crack_tip_readout.cpp).
  const std::vector<double> stress =
      scene.solver.cover_order == 0 ? std::vector<double>{} : mean_stress(mesh, scene.solver.cover_order, s);
  for (const CrackTip& t : tips) {
    const MaterialDef& m = scene.materials[static_cast<std::size_t>(scene.bodies[static_cast<std::size_t>(t.body)].material)];
    if (!m.strength.present || m.strength.toughness <= 0) continue;
    const StressIntensity k =
        interaction_integral(mesh, {t.at, t.direction, t.radius, t.body, &t.behind}, tip_elasticity(m, scene.plane),
                             scene.solver.cover_order == 0 ? s.stress : stress,
                             s.loop_u, skip, nullptr, loaded, face_pressure);
    // Faces pressed together do not open: K_I < 0 is what is left of the closing field where
    // the contacts' traction stands in for it (docs/crack-tips.md "Closed faces": −0.07·σ√(πa)
    // at a/10), outside the criterion's K_I ≥ 0, and would turn a closed flaw's wing from the
    // pure mode II 70.5° (to 79° at −0.08·σ√(πa) against K_II −0.19·σ√(πa)).
    const double k1 = std::max(k.k1, 0.0);
    const double theta = mts_angle(k1, k.k2);
    double toughness = m.strength.toughness;
    if (viscous) {
      double t_last = 0;  // s, when the tip last grew (the run's start for a scene joint's end)
      for (const CrackSegment& c : cracks)
        if (std::hypot(c.b.x - t.at.x, c.b.y - t.at.y) < 1e-6 * h || std::hypot(c.a.x - t.at.x, c.a.y - t.at.y) < 1e-6 * h)
          t_last = std::max(t_last, c.time);
      if (!(s.time > t_last)) continue;  // grew in this step: one tip step a step
      toughness = std::max(toughness, apparent_toughness(tip_elasticity(m, scene.plane).e_prime, scene.flow.viscosity,
                                                         step / (s.time - t_last), step));
    }
    if (mts_equivalent_k(k1, k.k2, theta) < toughness) continue;
    const double c = std::cos(theta), sn = std::sin(theta);
    const Vec2 d{c * t.direction.x - sn * t.direction.y, sn * t.direction.x + c * t.direction.y};
    // Where it first meets the body's boundary, a joint or a crack within 1.5 steps (its own last
    // segment ends at a: only crossings beyond a round-off of it count): a tip that would stop
    // short of it by less than half a step goes on to it, leaving no sliver of a ligament (a
    // centre crack grown to a plate's sides in steps of h stopped 7e-5 m short, and that
    // ligament held the two halves).
    const double probe = 1.5 * step;
    const Vec2 a = t.at, b{a.x + probe * d.x, a.y + probe * d.y};
    double hit = std::numeric_limits<double>::infinity();
    const double t_min = 1e-9 * h / probe;
    const BodyDef& body = scene.bodies[static_cast<std::size_t>(t.body)];
    auto ring = [&](const Ring& r) {
      for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) hit = std::min(hit, crossing(a, b, r[j], r[i], t_min));
    };
    ring(body.outer);
    for (const Ring& hole : body.holes) ring(hole);
    for (const JointDef& j : scene.joints)
      for (std::size_t i = 0; i + 1 < j.points.size(); ++i) hit = std::min(hit, crossing(a, b, j.points[i], j.points[i + 1], t_min));
    for (const auto& l : lines) hit = std::min(hit, crossing(a, b, l[0], l[1], t_min));
    for (const CrackSegment& o : out) hit = std::min(hit, crossing(a, b, o.a, o.b, t_min));
    const double reach = hit <= 1 ? hit * probe + 1e-8 * h : step;  // overshoot what it meets
    CrackSegment seg;
    seg.a = a;
    seg.b = {a.x + reach * d.x, a.y + reach * d.y};
    seg.a_now = {a.x + k.tip_u.x, a.y + k.tip_u.y};
    seg.b_now = {seg.b.x + k.tip_u.x, seg.b.y + k.tip_u.y};
    seg.mode = CrackMode::tensile;
    seg.step = s.step;
    seg.time = s.time;
    out.push_back(seg);
  }
  return out;
}

}  // namespace nmm::solve
