// The stress field of a state: see stress_field.h.
#include "solver/discretisation/stress_field.h"

#include "solver/discretisation/element_integration.h"

namespace nmm::solve {

std::vector<double> mean_stress(const Mesh& mesh, const CoverSpace& space, const RunState& s) {
  return mean_stress(mesh, space.order(), s);
}

std::vector<double> mean_stress(const Mesh& mesh, int order, const RunState& s) {
  const double h = basis_scale(mesh);
  const std::size_t T = static_cast<std::size_t>(monomial_count(order)), ne = mesh.element_count();
  if (T == 1) return s.stress;
  std::vector<double> out(3 * ne, 0.0);
  for (std::size_t e = 0; e < ne; ++e) {
    // The stress polynomial's origin is the element's first cover node, where it is now.
    const std::int32_t c0 = mesh.element_covers[3 * e];
    const double ox = s.cover_xy[2 * c0], oy = s.cover_xy[2 * c0 + 1];
    const std::size_t b = mesh.element_loop_offset[e], n = mesh.element_loop_offset[e + 1] - b;
    const MonomialMoments m = monomial_moments(s.loop_xy.data() + 2 * b, n, ox, oy,
                                               h, order);
    if (!(m.m[0] > 0)) continue;
    for (std::size_t t = 0; t < T; ++t)
      for (int r = 0; r < 3; ++r) out[3 * e + r] += s.stress[3 * (T * e + t) + r] * m.m[t] / m.m[0];
  }
  return out;
}

std::array<double, 3> stress_at(const Mesh& mesh, const CoverSpace& space, const RunState& s,
                                std::size_t e, double x, double y) {
  return stress_at(mesh, space.order(), s, e, x, y);
}

std::array<double, 3> stress_at(const Mesh& mesh, int order, const RunState& s, std::size_t e, double x, double y) {
  const std::size_t T = static_cast<std::size_t>(monomial_count(order));
  const double h = basis_scale(mesh);
  std::array<double, 3> out{};
  const std::int32_t c0 = mesh.element_covers[3 * e];
  const double ox = s.cover_xy[2 * c0], oy = s.cover_xy[2 * c0 + 1];
  for (std::size_t t = 0; t < T; ++t) {
    Poly p;
    p.degree = kMonomials.p[t] + kMonomials.q[t];
    p.c[t] = 1;
    const double v = p((x - ox) / h, (y - oy) / h);
    for (int r = 0; r < 3; ++r) out[r] += s.stress[3 * (T * e + t) + r] * v;
  }
  return out;
}

}  // namespace nmm::solve
