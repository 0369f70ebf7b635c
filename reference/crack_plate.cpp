// Plates with a straight crack (closed forms and set-up in the header).
#include "reference/crack_plate.h"

#include <cmath>

#include "common/math_constants.h"

namespace nmm::reference {

nlohmann::json crack_plate(double x0, double y0, double x1, double y1, Vec2 p, Vec2 q, double h) {
  nlohmann::json d;
  d["plane"] = "strain";
  d["materials"]["rock"] = {{"density", 2500}, {"young", kCrackPlateYoung}, {"poisson", kCrackPlatePoisson}};
  d["joint_sets"]["crack"] = {{"friction_deg", 30},
                              {"normal", {{"model", "constant"}, {"kn", 1e12}}},
                              {"shear", {{"model", "constant"}, {"ks", 4e11}}}};
  d["bodies"] = {{{"material", "rock"}, {"outer", {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}}};
  d["joints"] = {{{"set", "crack"}, {"points", {{p.x, p.y}, {q.x, q.y}}}}};
  d["mesh"]["size"] = h;
  d["tractions"] = {{{"points", {{x0, y1}, {x1, y1}}}, {"normal", kCrackPlateStress}, {"shear", 0}},
                    {{"points", {{x0, y0}, {x1, y0}}}, {"normal", kCrackPlateStress}, {"shear", 0}}};
  const double xm = 0.5 * (x0 + x1);
  d["fixed_points"] = {{xm, y0 + 0.01 * h}};
  d["supports"] = {{{"points", {{x1 - 0.5 * h, y0}, {x1, y0}}}, {"fix", "y"}}};
  d["solver"] = {{"time_step", 1}, {"steps", 1}, {"dynamic", false}, {"static_mode", "equilibrium"}};
  return d;
}

double tada_centre(double alpha) {
  return (1 - 0.025 * alpha * alpha + 0.06 * std::pow(alpha, 4)) / std::sqrt(std::cos(kPi * alpha / 2));
}

double tada_edge(double alpha) {
  const double t = kPi * alpha / 2;
  return std::sqrt(std::tan(t) / t) * (0.752 + 2.02 * alpha + 0.37 * std::pow(1 - std::sin(t), 3)) / std::cos(t);
}

nlohmann::json pulled_crack_plate(double h, double k_ic, double v, double ramp) {
  const double W = 1, H = 2, a = 0.5;
  nlohmann::json d = crack_plate(-W, -H, W, H, {-a, 0}, {a, 0}, h);
  d["materials"]["rock"]["strength"] = {{"tensile", 1e9}, {"cohesion", 1e9}, {"friction_deg", 30}, {"toughness", k_ic}};
  d["fracture"] = {{"crack_set", "crack"}};
  d.erase("tractions");
  d["supports"] = {{{"points", {{-W, -H}, {W, -H}}}, {"fix", "y"}},
                   {{"points", {{-W, H}, {W, H}}}, {"fix", "xy"}, {"velocity", {0, v}},
                    {"table", {{0, ramp}, {1, ramp}, {1.000001, 1}}}}};
  d["fixed_points"] = {{0, -H + 0.01 * h}};
  return d;
}

}  // namespace nmm::reference
