// Reference slides with a known factor of safety (formulas in the header).
#include "reference/slides.h"

#include <cmath>
#include <vector>

#include "common/math_constants.h"
#include "common/ring_geometry.h"

namespace nmm::reference {

namespace {
constexpr double kG = 9.81;          // m/s²
constexpr double kDensity = 2500;    // kg/m³
constexpr double kWaterDensity = 1000;  // kg/m³
double rad(double d) { return d * kPi / 180; }

// The common scene: material, joint set "plane", solver settings for a short trial.
nlohmann::json base_scene(const std::string& name, double dip, double phi_deg, double cohesion,
                          double duration) {
  nlohmann::json s;
  s["name"] = name;
  s["gravity"] = {kG * std::sin(dip), -kG * std::cos(dip)};
  s["plane"] = "strain";
  s["materials"] = {{"rock", {{"density", kDensity}, {"young", 1e10}, {"poisson", 0.25}}}};
  s["joint_sets"] = {{"plane",
                      {{"friction_deg", phi_deg},
                       {"cohesion", cohesion},
                       {"tensile_strength", 0},
                       // Constant joint stiffness in Pa/m, kn = 10·E/h (limit equilibrium has a
                       // rigid plane: any stiff joint will do), ks = kn/2.5; as data/planar_slide.json.
                       {"normal", {{"model", "constant"}, {"kn", 2e11}, {"kni", 2e10}, {"vm", 2e-4}}},
                       {"shear", {{"model", "constant"}, {"ks", 8e10}, {"ksi", 1e10}, {"rf", 0.9}}}}}};
  s["interface_set"] = "plane";
  s["mesh"] = {{"size", 0.5}};
  const double dt = 2e-3;
  s["solver"] = {{"time_step", dt},
                 {"steps", static_cast<int>(std::lround(duration / dt))},
                 {"dynamic", true},
                 {"max_displacement_ratio", 0.001},
                 {"output_every", 10}};
  return s;
}

nlohmann::json ring(const std::vector<std::pair<double, double>>& pts) {
  nlohmann::json r = nlohmann::json::array();
  for (const auto& [x, y] : pts) r.push_back({x, y});
  return r;
}
}  // namespace

ReferenceSlide block_on_plane(double alpha_deg, double phi_deg, double duration) {
  ReferenceSlide r;
  const double a = rad(alpha_deg);
  r.scene = base_scene("block-on-plane", a, phi_deg, 0, duration);
  // The block slides towards +x: 2.5 m of base ahead of it.
  r.scene["bodies"] = {{{"material", "rock"}, {"outer", ring({{0, 0}, {7, 0}, {7, 1.1}, {0, 1.1}})}},
                       {{"material", "rock"},
                        {"outer", ring({{1.5, 1.1}, {4.5, 1.1}, {4.5, 1.6}, {1.5, 1.6}})}}};
  r.scene["fixed_points"] = {{0.3, 0.3}, {6.7, 0.3}, {3.5, 0.3}};
  r.scene["measure_points"] = {{3, 1.35}};
  r.weight = kDensity * kG * 3 * 0.5;
  r.plane_length = 3;
  r.fos = std::tan(rad(phi_deg)) / std::tan(a);
  return r;
}

ReferenceSlide planar_slide(double height, double face_deg, double plane_deg, double crack_x,
                            double phi_deg, double cohesion, double duration, bool plastic,
                            double water_depth) {
  ReferenceSlide r;
  const double pf = rad(face_deg), pp = rad(plane_deg);
  // The wedge in the real frame: toe, crack base, crack top, crest.
  const std::vector<std::pair<double, double>> real = {
      {0, 0}, {crack_x, crack_x * std::tan(pp)}, {crack_x, height}, {height / std::tan(pf), height}};
  Ring outline;
  for (const auto& [x, y] : real) outline.push_back({x, y});
  r.weight = kDensity * kG * ring_area(outline);
  r.plane_length = crack_x / std::cos(pp);
  const double gamma_w = kWaterDensity * kG, zw = water_depth;
  r.uplift = 0.5 * gamma_w * zw * r.plane_length;
  r.crack_thrust = 0.5 * gamma_w * zw * zw;
  r.fos = (cohesion * r.plane_length +
           (r.weight * std::cos(pp) - r.uplift - r.crack_thrust * std::sin(pp)) * std::tan(rad(phi_deg))) /
          (r.weight * std::sin(pp) + r.crack_thrust * std::cos(pp));
  // Plane frame, mirrored so that the wedge slides towards +x: turn by −ψ_p about the toe,
  // mirror x, put the toe at (x0, y0) with 4 m of base ahead of it. y0 = 1.1 keeps the plane off
  // the mesh lattice's node rows.
  const double y0 = 1.1, x0 = 1 + r.plane_length;
  std::vector<std::pair<double, double>> wedge;
  for (const auto& [x, y] : real)
    wedge.push_back({x0 - (x * std::cos(pp) + y * std::sin(pp)), y0 - x * std::sin(pp) + y * std::cos(pp)});
  wedge[0].second = wedge[1].second = y0;  // exactly on the plane
  const double right = x0 + 4;
  r.scene = base_scene("planar-slide", pp, phi_deg, cohesion, duration);
  r.scene["bodies"] = {{{"material", "rock"}, {"outer", ring({{0, 0}, {right, 0}, {right, y0}, {0, y0}})}},
                       {{"material", "rock"}, {"outer", ring(wedge)}}};
  if (plastic) r.scene["joint_sets"]["plane"]["residual_cohesion"] = cohesion;
  if (zw > 0) {
    // The water table from the level in the crack (z_w above its foot, against gravity) straight
    // down to the toe: the crack face and the plane are wet, the slope face above it dry.
    const double up[2] = {-std::sin(pp), std::cos(pp)};  // against the turned gravity
    r.scene["water"] = {{"density", kWaterDensity},
                        {"phreatic", ring({{1 + zw * up[0], y0 + zw * up[1]}, {x0, y0}})}};
  }
  // A rigid foundation: fixed points on a 0.5 m grid over the base body (see the header).
  nlohmann::json fixed = nlohmann::json::array();
  for (double x = 0.25; x < right - 0.1; x += 0.5)
    for (double y : {0.25, 0.75}) fixed.push_back({x, y});
  r.scene["fixed_points"] = fixed;
  // Measure point: the wedge's centroid-ish point, the mean of its corners.
  double mx = 0, my = 0;
  for (const auto& [x, y] : wedge) {
    mx += x / wedge.size();
    my += y / wedge.size();
  }
  r.scene["measure_points"] = {{mx, my}};
  return r;
}

}  // namespace nmm::reference
