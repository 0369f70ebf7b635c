// Laboratory rock tests that break the rock (closed forms in the header).
//
// Every specimen is loaded at a rate that brings its closed-form first crack (the notched beam:
// its net-section load; elastic estimates) after kStepsToCrack[rate] steps of Δt, and ends
// kPastCrack later: a few steps past the peak, which keeps the matrix within its CI budget.
#include "reference/rock_tests.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/math_constants.h"
#include "common/ring_geometry.h"

namespace nmm::reference {

namespace {

constexpr double kStepsToCrack[2] = {150, 75};  // steps of Δt to the closed-form load, slow / fast
constexpr double kPastCrack = 1.2;              // the run ends at 1.2× that time

// The rock of the compression test: E 20 GPa, ν 0.2, c 10 MPa, φ 30°, σt 10 MPa.
constexpr double kE = 20e9, kNu = 0.2, kRho = 2600, kSt = 10e6, kC = 10e6, kPhiDeg = 30;

double rad(double deg) { return deg * kPi / 180; }

nlohmann::json ring(const std::vector<Vec2>& pts) {
  nlohmann::json r = nlohmann::json::array();
  for (const Vec2& p : pts) r.push_back({p.x, p.y});
  return r;
}

nlohmann::json rect(double x0, double y0, double x1, double y1) { return ring({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}); }

nlohmann::json rock(double E, double nu, double rho, double st, double c, double phi_deg) {
  return {{"density", rho}, {"young", E}, {"poisson", nu},
          {"strength", {{"tensile", st}, {"cohesion", c}, {"friction_deg", phi_deg}}}};
}

// Constant springs kn = 10·E/h (a face as stiff as ten elements in series), ks = kn/2.5.
nlohmann::json springs(double E, double h, double friction_deg) {
  const double kn = 10 * E / h;
  return {{"friction_deg", friction_deg},
          {"normal", {{"model", "constant"}, {"kn", kn}}},
          {"shear", {{"model", "constant"}, {"ks", kn / 2.5}}}};
}

// The scene of a specimen of the laboratory rock (kE, kNu, kRho, kSt, kC, kPhiDeg) in plane
// strain, named after its case, whose new cracks are springs(kE, h, 30): the document to add its
// bodies and loading to.
nlohmann::json& lab_rock_scene(RockTestSpecimen& s, const RockTestCase& c, double h) {
  nlohmann::json& d = s.scene;
  d["name"] = rock_test_case_name(c);
  d["plane"] = "strain";
  d["materials"]["rock"] = rock(kE, kNu, kRho, kSt, kC, kPhiDeg);
  d["joint_sets"]["crack"] = springs(kE, h, 30);
  return d;
}

nlohmann::json support(const std::vector<Vec2>& pts, const char* fix, Vec2 velocity = {0, 0}) {
  nlohmann::json s = {{"points", ring(pts)}, {"fix", fix}};
  if (velocity.x != 0 || velocity.y != 0) s["velocity"] = {velocity.x, velocity.y};
  return s;
}

// The solver block: Δt, static or dynamic, steps to the end time (the stepper runs to end_time).
void solver(RockTestSpecimen& s, double dt, bool dynamic) {
  s.scene["solver"] = {{"time_step", dt},
                       {"steps", static_cast<long long>(std::ceil(s.end_time / dt - 1e-9))},
                       {"dynamic", dynamic},
                       {"output_every", 1000}};
}

// A disc of diameter D centred at (cx, cy), its rim a polygon of 10° sides, with two flats of
// 2α centred on the vertical diameter (the flat's ends are vertices: α a multiple of 5°).
std::vector<Vec2> flattened_disc(double D, double alpha_deg, double cx, double cy) {
  std::vector<Vec2> p;
  const double R = D / 2;
  // From the bottom flat's right end counter-clockwise to its left end.
  const double start = -90 + alpha_deg, stop = 270 - alpha_deg;
  for (double a = start; a <= stop + 1e-9;) {
    p.push_back({cx + R * std::cos(rad(a)), cy + R * std::sin(rad(a))});
    if (std::abs(a - (90 - alpha_deg)) < 1e-9) {
      a = 90 + alpha_deg;  // across the top flat
      continue;
    }
    double next = std::floor(a / 10 + 1e-9) * 10 + 10;
    if (a < 90 - alpha_deg - 1e-9 && next > 90 - alpha_deg) next = 90 - alpha_deg;
    if (next > stop) next = stop;
    if (std::abs(next - a) < 1e-9) break;
    a = next;
  }
  return p;
}

// Tension bar, uniaxial and biaxial compression: a rectangle of the rock in plane strain,
// its ends held on rollers, one end moved by a support.
RockTestSpecimen rectangle_test(const RockTestCase& c) {
  RockTestSpecimen s;
  const bool bar = c.test == RockTest::tension_bar;
  const bool biaxial = c.test == RockTest::biaxial;
  const double sizes_bar[3] = {0.25, 0.2, 0.125};
  const double sizes_ucs[3] = {0.125, 0.1, 0.0625};
  const double h = bar ? sizes_bar[c.size] : sizes_ucs[c.size];
  const double w = bar ? 4 : 1, ht = bar ? 1 : 2;  // m: extent along x, along y
  const double length = bar ? w : ht;              // m, along the loading axis
  const double Ep = kE / (1 - kNu * kNu);          // Pa, plane strain with free sides
  const double Nphi = (1 + std::sin(rad(kPhiDeg))) / (1 - std::sin(rad(kPhiDeg)));
  const double ucs = 2 * kC * std::cos(rad(kPhiDeg)) / (1 - std::sin(rad(kPhiDeg)));
  const double sigma3 = 5e6;  // Pa, the biaxial's lateral pressure
  s.mesh_size = h;
  s.load_unit = "Pa";
  s.load_body = 0;
  s.load_component = bar ? 0 : 1;
  s.load_lever = w * ht;  // ∫σ dA / area: the mean stress, the platen's load per unit area
  if (bar) {
    s.closed_form = kSt;
    s.closed_form_name = "σt";
  } else if (biaxial) {
    s.closed_form = ucs + Nphi * sigma3;
    s.closed_form_name = "σ1 = UCS + σ3(1+sinφ)/(1−sinφ)";
    s.initial_load = sigma3;
  } else {
    s.closed_form = ucs;
    s.closed_form_name = "UCS = 2c·cosφ/(1−sinφ)";
  }
  const double dt = 1e-3;
  const double t_crack = kStepsToCrack[c.rate] * dt;
  const double travel = (s.closed_form - s.initial_load) / Ep * length;  // m, to the closed form
  const double v = travel / t_crack;
  s.load_rate = (s.closed_form - s.initial_load) / t_crack;
  s.end_time = kPastCrack * t_crack;

  nlohmann::json& d = lab_rock_scene(s, c, h);
  d["bodies"] = {{{"material", "rock"}, {"outer", rect(0, 0, w, ht)}}};
  d["fracture"] = {{"crack_set", "crack"}};
  d["mesh"]["size"] = h;
  if (bar) {
    d["supports"] = {support({{0, 0}, {0, ht}}, "x"), support({{w, 0}, {w, ht}}, "x", {v, 0})};
    d["fixed_points"] = {{0, ht / 2}};  // on the held end: no stress of its own
  } else {
    d["supports"] = {support({{0, 0}, {w, 0}}, "y"), support({{0, ht}, {w, ht}}, "y", {0, -v})};
    d["fixed_points"] = {{w / 2, 0}};  // on the held end, on the axis of symmetry
  }
  if (biaxial) {
    // Starts in equilibrium under σ3 all round: the sides carry it as a traction, the rollers
    // as their locked-in reaction; the top then moves down.
    d["insitu_stress"] = {{"sxx", -sigma3}, {"syy", -sigma3}, {"sxy", 0}, {"y_ref", 0}, {"gradient", {0, 0, 0}}};
    d["tractions"] = {{{"points", ring({{0, ht}, {0, 0}})}, {"from_insitu", true}},
                      {{"points", ring({{w, 0}, {w, ht}})}, {"from_insitu", true}}};
  }
  solver(s, dt, c.dynamic);
  return s;
}

// The Brazilian disc. Without platens: data/brazilian_disc.json's set-up (D 1 m, σt 5 MPa, E 10
// GPa, plane stress), the flats themselves held by supports. With platens: the (D 0.2 m,
// the rock, 2α = 20°), squeezed between two steel platens that are bodies of their own
// (contacts of the interface set), the bottom platen held, the top one moved.
RockTestSpecimen disc_test(const RockTestCase& c) {
  RockTestSpecimen s;
  const bool platens = c.test == RockTest::disc_platens;
  const double D = platens ? 0.2 : 1.0, R = D / 2, alpha_deg = 10, alpha = rad(alpha_deg);
  const double E = platens ? kE : 1e10, nu = platens ? kNu : 0.25, st = platens ? kSt : 5e6;
  const double sizes_over_d[3] = {1.0 / 12, 1.0 / 16, 1.0 / 20};  // h / D
  const double h = D * sizes_over_d[c.size];
  const double H = D * std::cos(alpha);  // m, between the flats
  s.mesh_size = h;
  s.load_unit = "N/m";
  s.load_body = 0;
  s.load_component = 1;
  s.load_lever = H;  // ∫σyy dA over the disc = P·H
  // A rigid flat presses the flat as a flat punch (header): P = D·t·σt·E(sinα)/cos2α, 1.86 %
  // above Hondros' uniform pressure at 2α = 20°.
  s.closed_form = D * st * std::comp_ellint_2(std::sin(alpha)) / std::cos(2 * alpha);
  s.closed_form_name = "rigid flat: Dσt·E(sinα)/cos2α";
  // N/m per m of travel: the disc's stiffness between the flats, 0.41·E (measured on
  // data/brazilian_disc.json: 8.57 MN/m at 2.1 mm with E = 10 GPa; in 2D it does not depend on D).
  const double k = 0.41 * E;
  const double dt = 1e-3;
  const double t_crack = kStepsToCrack[c.rate] * dt;
  const double v = s.closed_form / k / t_crack;
  s.load_rate = s.closed_form / t_crack;
  s.end_time = kPastCrack * t_crack;

  nlohmann::json& d = s.scene;
  d["name"] = rock_test_case_name(c);
  d["plane"] = "stress";
  // Between platens the rock is a strong one (UCS 156 MPa, 15.6·σt, as granite): the flats press
  // it at P/(D·sinα) ≈ 94 MPa at the centre's cracking load, which with the uniaxial specimens'
  // cohesion (UCS 34.6 MPa) crushed the rock under the flats at half that load instead.
  d["materials"]["rock"] = platens ? rock(E, nu, kRho, st, 4.5 * kC, kPhiDeg) : rock(E, nu, 2600, st, 15e6, 35);
  d["joint_sets"]["crack"] = springs(E, h, 30);
  d["bodies"] = {{{"material", "rock"}, {"outer", ring(flattened_disc(D, alpha_deg, R, R))}}};
  d["fracture"] = {{"crack_set", "crack"}};
  d["mesh"]["size"] = h;
  const double yb = R - R * std::cos(alpha), yt = R + R * std::cos(alpha);  // the flats
  if (platens) {
    // Steel platens 0.4·D wide and 0.1·D thick, their faces smooth (frictionless, as the closed
    // form assumes: with 10° of friction they held the flats' ends in and the centre's tension was
    // 1.9 % lower at every mesh size).
    const double pw = 0.2 * D, pt = 0.1 * D;
    d["materials"]["steel"] = {{"density", 7850}, {"young", 200e9}, {"poisson", 0.3}};
    d["joint_sets"]["platen"] = springs(E, h, 0);
    d["interface_set"] = "platen";
    d["bodies"].push_back({{"material", "steel"}, {"outer", rect(R - pw, yb - pt, R + pw, yb)}});
    d["bodies"].push_back({{"material", "steel"}, {"outer", rect(R - pw, yt, R + pw, yt + pt)}});
    d["supports"] = {support({{R - pw, yb - pt}, {R + pw, yb - pt}}, "xy"),
                     support({{R + pw, yt + pt}, {R - pw, yt + pt}}, "xy", {0, -v})};
  } else {
    const double xa = R - R * std::sin(alpha), xb = R + R * std::sin(alpha);
    d["supports"] = {support({{xa, yb}, {xb, yb}}, "y"), support({{xb, yt}, {xa, yt}}, "y", {0, -v})};
    d["fixed_points"] = {{R, yb + 0.02 * D}};
  }
  solver(s, dt, c.dynamic);
  return s;
}

// m²: ∫0^d Y(x)² dx, Y(x) = (3S/(2W²))·√(πx)·F(x/W) (header), Simpson on 200 intervals (F is
// smooth, F(0) = 1.122).
double notch_integral(double S, double W, double d) {
  double sum = 0;
  const int n = 200;
  for (int i = 0; i <= n; ++i) {
    const double x = d * i / n;
    const double Y = 3 * S / (2 * W * W) * std::sqrt(kPi * x) * edge_crack_bending_factor(std::max(x, 1e-12) / W);
    sum += ((i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2)) * Y * Y;
  }
  return sum * d / n / 3;
}

// The notched beam: span S 2 m between supports, depth W 0.2 m, 0.1 m overhangs, a notch of
// a = 0.1 m up from the tension face at midspan (a slot 2 mm wide), loaded at midspan on top by a pad 2h wide moving down; the supports are pads 2h wide
// under the beam held in y, and a fixed point at the left one's centre holds x. All reactions
// act at y = 0 and the load at y = W, so ∫σyy dA = −P·W whatever their spread. The pads'
// penalty is soft (0.1·E per m of boundary, solver.support_stiffness): a pad of width b then
// resists a rotation with 0.1·E·b³/12 (2e4 N·m/rad at b = 5 cm, 1e-3 of the beam's own end
// stiffness 3EI/S), so that the pads do not clamp the beam's ends or the notch. The issue's
// rock in plane strain.
RockTestSpecimen beam_test(const RockTestCase& c) {
  RockTestSpecimen s;
  const double S = 2, W = 0.2, a = 0.1, over = 0.1, L = S + 2 * over, xm = L / 2;
  const double sizes[3] = {0.025, 0.02, 0.0167};
  const double h = sizes[c.size];
  const double Ep = kE / (1 - kNu * kNu), G = kE / (2 * (1 + kNu)), I = W * W * W / 12, kappa = 5.0 / 6;
  const double ks = 0.1 * kE, pad = 2 * h;  // N/m², m
  // m per N/m at the quarter points (bending, shear, a notch of depth d) and at the pad.
  const double bending = 11 * S * S * S / (768 * Ep * I), shear = S / (8 * kappa * G * W);
  const double c_quarter = bending + shear + notch_integral(S, W, a) / Ep;
  const double c_pad = S * S * S / (48 * Ep * I) + S / (4 * kappa * G * W) + 2 * notch_integral(S, W, a) / Ep +
                       2 / (ks * pad);
  // A physical cover of order 0 whose star reaches round the notch's tip has one displacement on
  // both faces: a node within h of the tip ties the faces over its star, up to 2h from the tip,
  // so the notch the model carries lies between a − 2h and a deep; its compliance and
  // net-section load lie between those of the two.
  s.compliance = c_quarter;
  s.compliance_low = bending + shear + notch_integral(S, W, a - 2 * h) / Ep;
  s.net_section_load = 2 * kSt * (W - a + 2 * h) * (W - a + 2 * h) / (3 * S);
  s.mesh_size = h;
  s.load_unit = "N/m";
  s.load_body = 0;
  s.load_component = 1;
  s.load_lever = W;  // ∫σyy dA = −P·W: the load on top at y = W, the reactions at y = 0
  s.closed_form = 0;
  s.closed_form_name = "none (sharp notch)";
  s.notch_tip = {xm, a};
  s.tips = {s.notch_tip};
  const double dt = 1e-3;
  const double t_crack = kStepsToCrack[c.rate] * dt;  // to P_net(a − 2h), elastically
  const double v = s.net_section_load * c_pad / t_crack;
  s.load_rate = s.net_section_load / t_crack;
  s.end_time = kPastCrack * t_crack;

  nlohmann::json& d = lab_rock_scene(s, c, h);
  const double e = 2e-3;  // m, the notch's width: a slot sawn into the beam
  d["bodies"] = {{{"material", "rock"},
                  {"outer", ring({{0, 0}, {xm - e / 2, 0}, {xm - e / 2, a}, {xm + e / 2, a}, {xm + e / 2, 0}, {L, 0},
                                  {L, W}, {0, W}})}}};
  d["fracture"] = {{"crack_set", "crack"}};
  d["mesh"]["size"] = h;
  d["supports"] = {support({{over - pad / 2, 0}, {over + pad / 2, 0}}, "y"),
                   support({{L - over - pad / 2, 0}, {L - over + pad / 2, 0}}, "y"),
                   support({{xm + pad / 2, W}, {xm - pad / 2, W}}, "y", {0, -v})};
  d["fixed_points"] = {{over, 0}};
  // The deflection line: above the supports and at the quarter points, at mid-depth.
  d["measure_points"] = {{over, W / 2}, {L - over, W / 2}, {over + S / 4, W / 2}, {L - over - S / 4, W / 2}};
  solver(s, dt, c.dynamic);
  s.scene["solver"]["support_stiffness"] = ks;
  return s;
}

// data/step_path_slope.json's set-up at another mesh size and step: gravity in full from the
// first step; Δt 0.01 s (slow) or 0.02 s (fast); 1 s of it.
// The sizes resolve the rock bridges (b = 0.6 m between one joint's end and the next one's start,
// across the dip): the wedge pulls each bridge open along dip, so the intact slope's first
// elastic step must put every bridge in tension (σ_ss > 0), or the tips' lines stay shut and the
// bridges never break. At cover order 0 a joint's faces are tied within a star of each end (a
// node within h of the tip): at h ≤ b/2 = 0.3 m the two tips' tied stars no longer meet and
// all three bridges are in tension at every h tried (0.3, 0.25 m: +78 … +95, +26 … +42,
// +8.5 … +18 kPa); between b/2 and b it depends on where the mesh's nodes fall against the tips:
// all three in tension at h 0.5 and 0.35 m, one or more compressed at 0.6 (−32, −31, −9 kPa),
// 0.55, 0.45 and 0.4 m (docs/notes/2026-11-fracture-robustness.md, 2026-11-30). So 0.5, 0.35
// and 0.3 m: the coarsest the largest h whose bridges are all in tension.
RockTestSpecimen slope_test(const RockTestCase& c) {
  RockTestSpecimen s;
  const double sizes[3] = {0.5, 0.35, 0.3};
  const double h = sizes[c.size];
  s.mesh_size = h;
  s.load_unit = "m";  // compared across kernels (static steps): the wedge's travel at the end
  s.closed_form = 0;
  s.closed_form_name = "none (gravity in full)";
  s.end_time = 1.0;
  nlohmann::json& d = s.scene;
  d["name"] = rock_test_case_name(c);
  d["gravity"] = {0, -9.81};
  d["plane"] = "strain";
  d["materials"]["rock"] = rock(5e9, 0.25, 2600, 1e5, 3e5, 35);
  const double bedding_friction_deg = 15;
  d["joint_sets"]["bedding"] = {{"friction_deg", bedding_friction_deg},
                                {"normal", {{"model", "constant"}, {"kn", 5e10}}},
                                {"shear", {{"model", "constant"}, {"ks", 2e10}}}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 5e10}}},
                              {"shear", {{"model", "constant"}, {"ks", 2e10}}}};
  const Ring outer = {{0, 0}, {40, 0}, {40, 14}, {17, 14}, {13, 2}, {0, 2}};
  d["bodies"] = {{{"material", "rock"}, {"outer", ring(outer)}}};
  const std::vector<std::vector<Vec2>> joints = {{{13.1212, 2.7879}, {16.1618, 5.8284}},
                                                 {{15.7375, 6.2527}, {18.5659, 9.0811}},
                                                 {{18.1417, 9.5054}, {20.9701, 12.3338}},
                                                 {{20.5458, 12.7581}, {22.0877, 14.3}}};
  d["joints"] = nlohmann::json::array();
  for (const auto& j : joints) {
    d["joints"].push_back({{"set", "bedding"}, {"points", ring(j)}});
    for (const Vec2& p : j)
      if (point_in_ring(outer, p)) s.tips.push_back(p);
  }
  d["fracture"] = {{"crack_set", "crack"}};
  d["mesh"]["size"] = h;
  d["supports"] = {support({{0, 0}, {40, 0}}, "xy"), support({{40, 0}, {40, 14}}, "x"), support({{0, 0}, {0, 2}}, "x")};
  d["measure_points"] = {{17.5, 13.5}, {25, 13.5}};  // on the wedge, behind the crest
  // The free slide: the step path dips at β along the first joint, the bedding's φ 15°; the toe is
  // where that joint leaves the face (outer[4] → outer[3]) and falls to the platform (outer[5].y)
  // after d = (y_toe − y_platform)/sinβ along the dip (1.414 m; a = 5.078 m/s², t = 0.746 s).
  const Vec2 j0 = joints[0][0], j1 = joints[0][1], f0 = outer[4], f1 = outer[3];
  const Vec2 dj = {j1.x - j0.x, j1.y - j0.y}, df = {f1.x - f0.x, f1.y - f0.y};
  const double along = ((f0.x - j0.x) * df.y - (f0.y - j0.y) * df.x) / (dj.x * df.y - dj.y * df.x);
  const double dip = std::atan2(dj.y, dj.x), toe_y = j0.y + along * dj.y;
  s.slide_acceleration = 9.81 * (std::sin(dip) - std::cos(dip) * std::tan(rad(bedding_friction_deg)));
  s.slide_distance = (toe_y - outer[5].y) / std::sin(dip);
  if (c.dynamic) s.load_unit = "s";  // compared across kernels: the time the toe reaches the platform
  solver(s, c.rate ? 0.02 : 0.01, c.dynamic);
  return s;
}

const char* const kNames[] = {"tension_bar", "uniaxial", "biaxial", "disc_flats", "disc_platens", "notched_beam",
                              "step_path_slope"};

}  // namespace

std::vector<RockTest> all_rock_tests() {
  return {RockTest::tension_bar,  RockTest::uniaxial,     RockTest::biaxial,        RockTest::disc_flats,
          RockTest::disc_platens, RockTest::notched_beam, RockTest::step_path_slope};
}

std::string rock_test_name(RockTest t) { return kNames[static_cast<int>(t)]; }

bool rock_test_from_name(const std::string& name, RockTest& t) {
  for (const RockTest r : all_rock_tests())
    if (rock_test_name(r) == name) {
      t = r;
      return true;
    }
  return false;
}

std::string rock_test_case_name(const RockTestCase& c) {
  return rock_test_name(c.test) + ".h" + std::to_string(c.size) + (c.dynamic ? ".dynamic" : ".static") +
         (c.rate ? ".fast" : ".slow");
}

bool rock_test_case_from_name(const std::string& name, RockTestCase& c) {
  std::stringstream ss(name);
  std::string part[4];
  for (std::string& p : part)
    if (!std::getline(ss, p, '.')) return false;
  std::string rest;
  if (std::getline(ss, rest)) return false;
  if (!rock_test_from_name(part[0], c.test)) return false;
  if (part[1].size() != 2 || part[1][0] != 'h' || part[1][1] < '0' || part[1][1] > '2') return false;
  c.size = part[1][1] - '0';
  if (part[2] != "static" && part[2] != "dynamic") return false;
  c.dynamic = part[2] == "dynamic";
  if (part[3] != "slow" && part[3] != "fast") return false;
  c.rate = part[3] == "fast";
  return true;
}

RockTestSpecimen rock_test(const RockTestCase& c) {
  switch (c.test) {
    case RockTest::tension_bar:
    case RockTest::uniaxial:
    case RockTest::biaxial: return rectangle_test(c);
    case RockTest::disc_flats:
    case RockTest::disc_platens: return disc_test(c);
    case RockTest::notched_beam: return beam_test(c);
    case RockTest::step_path_slope: return slope_test(c);
  }
  return {};
}

double edge_crack_bending_factor(double r) {
  const double t = kPi * r / 2;
  const double s = 1 - std::sin(t);
  return std::sqrt(2 / (kPi * r) * std::tan(t)) * (0.923 + 0.199 * s * s * s * s) / std::cos(t);
}

}  // namespace nmm::reference
