// The Kirsch opening: the wall read-off (kirsch_opening.h).
#include "studies/kirsch_opening.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "solver/stepping/time_stepper.h"

namespace nmm::studies {

using reference::kirsch_hoop;
using reference::kirsch_radial_displacement;
using reference::kKirschPoisson;
using reference::kKirschPressure;
using reference::kKirschRadius;
using reference::kKirschYoung;

namespace {

// σθ (compression positive) of a stress (σxx, σyy, τxy; tension positive) at angle θ.
double hoop_of(const std::array<double, 3>& s, double th) {
  const double c = std::cos(th), sn = std::sin(th);
  return -(s[0] * sn * sn + s[1] * c * c - 2 * s[2] * sn * c);
}
}  // namespace

KirschWall kirsch_wall(const reference::KirschSetup& k, const Mesh& m, const solve::TimeStepper& st) {
  const double a = kKirschRadius, py = kKirschPressure, px = k.k0 * py, nu = kKirschPoisson;
  const double G = kKirschYoung / (2 * (1 + nu)), P = 0.5 * (px + py), Q = 0.5 * (px - py);
  const double hoop_max = std::max(std::abs(2 * P - 4 * Q), std::abs(2 * P + 4 * Q));
  const double ur_max = a / (4 * G) * (std::abs(px + py) + std::abs(px - py) * (3 - 4 * nu));
  const double tol = 1e-6 * k.h;
  const std::vector<double> mean = mean_stress(st.view());
  const std::vector<double>& now = st.view().state.loop_xy;
  const std::vector<double>& u = st.view().state.loop_u;
  auto on_wall = [&](double x, double y) { return std::abs(std::hypot(x, y) - a) < 1e-3 * a; };
  double e_wall = 0, e_cent = 0, e_ur = 0, side = 0;
  std::size_t n_wall = 0, n_cent = 0, n_ur = 0, n_side = 0;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    if (m.element_body[e] != 0) continue;
    bool wall = false;
    double cx = 0, cy = 0;
    const std::int32_t b0 = m.element_loop_offset[e], b1 = m.element_loop_offset[e + 1];
    for (std::int32_t v = b0; v < b1; ++v) {
      const double x = m.loop_xy[2 * v], y = m.loop_xy[2 * v + 1];
      cx += x / (b1 - b0);
      cy += y / (b1 - b0);
      const std::int32_t nv = v + 1 < b1 ? v + 1 : b0;
      const bool boundary = (m.loop_edge_origin[v] & kEdgeBoundary) != 0;
      if (boundary && on_wall(x, y) && on_wall(m.loop_xy[2 * nv], m.loop_xy[2 * nv + 1])) {
        wall = true;
        // The element's stress field at both ends of its wall edge (where it is now).
        for (const std::int32_t w : {v, nv}) {
          const double x0 = m.loop_xy[2 * w], y0 = m.loop_xy[2 * w + 1], th = std::atan2(y0, x0);
          const double got = hoop_of(stress_at(st.view(), e, now[2 * w], now[2 * w + 1]), th);
          const double want = kirsch_hoop(px, py, std::hypot(x0, y0), th);
          e_wall += (got - want) * (got - want);
          ++n_wall;
          if (std::abs(y0) < tol && std::abs(x0 - a) < tol) {
            side += got;
            ++n_side;
          }
        }
      }
      if (boundary && on_wall(x, y) && x > tol && y > tol) {
        // Radial displacement of a wall vertex (inward positive) against Kirsch.
        const double th = std::atan2(y, x);
        const double ur = -(u[2 * v] * std::cos(th) + u[2 * v + 1] * std::sin(th));
        const double want = kirsch_radial_displacement(px, py, G, nu, std::hypot(x, y), th);
        e_ur += (ur - want) * (ur - want);
        ++n_ur;
      }
    }
    if (!wall) continue;
    const double th = std::atan2(cy, cx);
    const double got = hoop_of({mean[3 * e], mean[3 * e + 1], mean[3 * e + 2]}, th);
    const double want = kirsch_hoop(px, py, std::hypot(cx, cy), th);
    e_cent += (got - want) * (got - want);
    ++n_cent;
  }
  KirschWall out;
  out.hoop_wall = std::sqrt(e_wall / std::max<std::size_t>(n_wall, 1)) / hoop_max;
  out.hoop_centroid = std::sqrt(e_cent / std::max<std::size_t>(n_cent, 1)) / hoop_max;
  out.radial = std::sqrt(e_ur / std::max<std::size_t>(n_ur, 1)) / ur_max;
  out.side_wall_hoop = n_side ? side / static_cast<double>(n_side) : std::nan("");
  out.side_wall_exact = kirsch_hoop(px, py, a, 0);
  out.wall_points = n_wall;
  return out;
}

}  // namespace nmm::studies
