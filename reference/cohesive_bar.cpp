// The cohesive tension bar (set-up and closed forms in the header).
#include "reference/cohesive_bar.h"

#include <cmath>

namespace nmm::reference {

nlohmann::json cohesive_bar(double size, double length) {
  nlohmann::json d;
  d["plane"] = "stress";
  d["materials"]["rock"] = {{"density", 2500},
                            {"young", kCohesiveBarYoung},
                            {"poisson", 0.2},
                            {"strength",
                             {{"tensile", kCohesiveBarTensile},
                              {"cohesion", 4e6},
                              {"friction_deg", 35},
                              {"fracture_energy", kCohesiveBarFractureEnergy}}}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 1e13}}},
                              {"shear", {{"model", "constant"}, {"ks", 4e12}}}};
  d["bodies"] = {{{"material", "rock"},
                  {"outer", {{0, 0}, {length / 2, 0.005}, {length, 0}, {length, 0.2}, {length / 2, 0.195}, {0, 0.2}}}}};
  d["fracture"] = {{"crack_set", "crack"}};
  d["mesh"]["size"] = size;
  d["supports"] = {{{"points", {{0, 0}, {0, 0.2}}}, {"fix", "x"}},
                   {{"points", {{length, 0}, {length, 0.2}}}, {"fix", "x"}, {"velocity", {1e-3, 0}}}};
  d["fixed_points"] = {{0, 0.1}};
  d["measure_points"] = {{length - 0.001, 0.1}, {0.001, 0.1}};
  d["solver"] = {{"time_step", 1e-3}, {"steps", 260}, {"dynamic", false}, {"output_every", 1}};
  return d;
}

// Each half tapers linearly from 0.2 to 0.19 m over L/2: ∫ dx/b = (L/2)/0.01·ln(0.2/0.19).
double cohesive_bar_compliance(double length) {
  return 2 * (length / 2) / (kCohesiveBarYoung * 0.01) * std::log(0.2 / kCohesiveBarNeck);
}

}  // namespace nmm::reference
