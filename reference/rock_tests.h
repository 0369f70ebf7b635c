// Laboratory rock tests that break the rock (docs/fracture.md), as scene documents with the
// closed form of their first crack: the fracturing robustness matrix (tests/fracture_matrix.cpp)
// runs each at three mesh sizes, static and dynamic, at two loading rates; tests and benches may
// take any of them. Every specimen is loaded by a support that moves (displacement control) and
// the load is read as the support's reaction through the mean stress of one body: in equilibrium
// without body force ∫_body σ dA = ∮ t ⊗ x ds, so with the loads acting on two lines a lever L
// apart, P = |∫_body σ_kk dA| / L (N/m); with L = the body's area / width it is the mean platen
// stress (Pa).
//
// Closed forms of the first crack (σt tensile strength, c cohesion, φ friction angle of the
// intact rock, Nφ = (1 + sinφ)/(1 − sinφ); tension positive):
// - tension bar: the uniform σxx reaches σt.
// - uniaxial compression (smooth platens: rollers): UCS = 2c·cosφ/(1 − sinφ) = 2c·√Nφ.
// - biaxial compression at a lateral pressure σ3 (held from the start by an in-situ stress with
//   matching tractions): σ1 = UCS + Nφ·σ3.
// - Brazilian disc of diameter D loaded over two flats of 2α of arc: a radial pressure p spread
//   uniformly over 2α (Hondros 1959, "The evaluation of Poisson's ratio and the modulus of
//   materials of a low tensile resistance by the Brazilian (indirect tensile) test", Aust. J.
//   Appl. Sci. 10) gives along the loaded diameter, at r = 0,
//     σxx(0) = (2p/π)·(sin2α − α)   [p·α·D in Hondros' notation is P for small α],
//   and the resultant of that pressure in y is P = p·D·t·sinα, so
//     σxx(0) = 2P/(πDt) · (sin2α − α)/sinα   (0.9645 of the line load's 2P/(πDt) at 2α = 20°);
//   the centre cracks when σxx(0) = σt: P = πDtσt/2 · sinα/(sin2α − α).
//   The matrix's discs are pressed by rigid flats (supports on the flats, or steel platens ten
//   times stiffer than the rock, frictionless), and a rigid flat does not press uniformly: to
//   leading order in α the flat is a half-plane under a rigid flat punch of half-width
//   a = R·sinα, p(x) = P/(π·t·√(a² − x²)) (Sadowsky 1928; Johnson, Contact Mechanics, 1985,
//   §5.8). Hondros' superposition with that distribution (the flat taken as its arc, x = R·sinθ):
//   a radial force F at θ from the loaded diameter adds F/(πDt)·(1 − 4sin²θ) to σxx(0), so
//     σxx(0) = 2P/(πDt) · ∫w(1 − 4sin²θ)dθ / ∫w·cosθ dθ,  w dθ = dφ for sinθ = sinα·sinφ,
//            = 2P/(πDt) · π·cos2α / (2·E(sinα))     (E: complete elliptic integral, 2nd kind),
//   0.9469 of the line load's at 2α = 20° (uniform: 0.9645), and the centre cracks at
//     P = D·t·σt · E(sinα) / cos2α,   1.86 % above Hondros' uniform pressure.
//   (Measured, elastic, frictionless platens: the end contacts of the flat carry 36 % of the load
//   over its outer 16 %, the punch's share 36.5 %; friction of 10° at the platens lowers σxx(0)
//   by a further 1.9 %, which no closed form here covers.)
// - notched beam in three-point bending (span S, depth W, notch a from the tension face): a
//   sharp notch is a crack, its tip stress is singular and the element stress there grows as
//   h^(−1/2) (K_I = σ√(πa)·F(a/W)), so the first-crack load depends on the mesh and has no
//   closed form. What does: the elastic compliance before cracking, read as the deflection of
//   the quarter points on the mid-depth line against the points above the supports,
//     δ_q / P = 11·S³/(768·E'·I) + S/(8·κ·G·W) + (1/E')·∫0^a Y(x)² dx,
//   bending (Euler–Bernoulli at x = S/4), shear (Timoshenko, κ = 5/6) and the notch (the
//   compliance a crack adds, dC/da = 2K²/(E'P²), Irwin–Kies; at the quarter points half the
//   midspan's), with K = P·Y(a), Y(a) = (3S/(2W²))·√(πa)·F(a/W) and F for pure bending (Tada,
//   Paris & Irwin, The Stress Analysis of Cracks Handbook, 2.13: within 0.5 %):
//     F(α) = √(2/(πα)·tan(πα/2)) · (0.923 + 0.199·(1 − sin(πα/2))⁴) / cos(πα/2);
//   E' = E/(1 − ν²) in plane strain, I = W³/12 per metre. And the peak cannot pass the load at
//   which the uncracked ligament's bending stress reaches σt: P_net = 2σt(W − a)²/(3S).
//   At cover order 0 a physical cover whose star reaches round the notch's tip carries one
//   displacement on both faces (a node within h of the tip, its star up to 2h from it), so the
//   model's notch is between a − 2h and a deep: the compliance lies between the two depths',
//   and P_net is the shallower notch's.
// - the step-path slope of data/step_path_slope.json: gravity loads it in full from the first
//   step, so there is no load to reach; its rock bridges crack at the joint tips in the first
//   steps (a tip is where the stress concentrates) and the wedge slides on the step path.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/vec2.h"

namespace nmm::reference {

enum class RockTest { tension_bar, uniaxial, biaxial, disc_flats, disc_platens, notched_beam, step_path_slope };

/// All of them, in the matrix's order.
std::vector<RockTest> all_rock_tests();
/// "tension_bar", "uniaxial", ...: the matrix's names.
std::string rock_test_name(RockTest t);
/// The test of that name; false if there is none.
bool rock_test_from_name(const std::string& name, RockTest& t);

/// One cell of the matrix: a test, its mesh size (0 coarse, 1, 2 fine), static or dynamic steps,
/// the loading rate (0: the first crack after about 120 steps; 1: twice as fast).
struct RockTestCase {
  RockTest test = RockTest::tension_bar;
  int size = 0;          ///< 0, 1, 2: coarse to fine (rock_test() says the sizes)
  bool dynamic = false;  ///< dynamic steps (Newmark) instead of DDA static ones
  int rate = 0;          ///< 0 slow, 1 twice as fast
};

/// A specimen: its scene and how its load and first crack are read.
struct RockTestSpecimen {
  nlohmann::json scene;       ///< scene document
  double mesh_size = 0;       ///< m
  double end_time = 0;        ///< s, the run's end: a few steps past the closed form's first crack
  double load_rate = 0;       ///< load units per s before the first crack (elastic estimate)
  // The load P = |∫_{body load_body} σ_k dA| / load_lever (k = load_component: 0 xx, 1 yy).
  int load_body = 0;          ///< index into the scene's bodies
  int load_component = 1;     ///< 0: σxx, 1: σyy
  double load_lever = 1;      ///< m (or m² / m: the body's area / width gives the mean stress)
  std::string load_unit;      ///< "Pa" or "N/m"
  double closed_form = 0;     ///< the first crack's load (load units); 0: none (the notched beam, the slope)
  std::string closed_form_name;  ///< what it is: "σt", "UCS = 2c·cosφ/(1 − sinφ)", ...
  double initial_load = 0;    ///< load units at t = 0 (the biaxial's in-situ σ3; 0 otherwise)
  // Notched beam: the compliance before cracking.
  double compliance = 0;      ///< m per N/m, δ_q / P by beam theory with the notch a (0: not a beam)
  double compliance_low = 0;  ///< m per N/m, the same with a notch a − 2h (the faces tied within a star)
  double net_section_load = 0;  ///< N/m, P_net of a notch a − 2h: the peak cannot pass it
  Vec2 notch_tip;             ///< m, the notch's tip: its first crack starts there (beam, slope: joint tips)
  std::vector<Vec2> tips;     ///< m, the joints' tips inside the rock (where cracks start)
  // The slope in dynamic steps: once its bridges break, the wedge slides as a rigid block on the
  // step path, a = g(sinβ − cosβ·tanφ), until its toe reaches the platform below the face, at
  // t = √(2d/a) (the release takes a few steps: it arrives a little later).
  double slide_acceleration = 0;  ///< m/s², a (0: not the slope)
  double slide_distance = 0;      ///< m, d: the wedge's travel along the dip from its toe to the platform
};

/// The specimen of one cell (sizes, rates and duration in rock_tests.cpp's table).
RockTestSpecimen rock_test(const RockTestCase& c);

/// "uniaxial.h1.static.slow": a cell's name, as the matrix's CTest entries are named.
std::string rock_test_case_name(const RockTestCase& c);
/// The cell of that name; false if it names none.
bool rock_test_case_from_name(const std::string& name, RockTestCase& c);

/// –, Tada's F(a/W) for an edge crack in a strip in pure bending (header).
double edge_crack_bending_factor(double a_over_w);

}  // namespace nmm::reference
