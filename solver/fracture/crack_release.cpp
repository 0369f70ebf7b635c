// The strain energy a crack releases: see crack_release.h for the derivation.
#include "solver/fracture/crack_release.h"

#include "solver/discretisation/effect_energy.h"

namespace nmm::solve {

double crack_release(const Mesh& mesh, const RunState& s, const RunState& start, std::size_t first_new_joint) {
  // ½ r·d = −½ Σ_faces Σ_sides ∫ (σ0 n)·Δu ds: on each side of each new face, the traction σ0·n
  // its element carried across it at the step's start (n outward, from the start positions: the
  // internal force the step started from) times the side's displacement in the step, linear
  // along the edge (cover order 0: exact).
  double w = 0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (element_removed(mesh, s, static_cast<std::int32_t>(e))) continue;
    const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    const double sx = start.stress[3 * e], sy = start.stress[3 * e + 1], txy = start.stress[3 * e + 2];
    for (std::int32_t v = b; v < end; ++v) {
      if (mesh.loop_edge_joint[v] < static_cast<std::int32_t>(first_new_joint)) continue;
      const std::int32_t n = v + 1 < end ? v + 1 : b;
      // (dy, −dx): the outward normal times the edge's length (CCW loop: outside on the right).
      const double lnx = start.loop_xy[2 * n + 1] - start.loop_xy[2 * v + 1];
      const double lny = -(start.loop_xy[2 * n] - start.loop_xy[2 * v]);
      const double tx = sx * lnx + txy * lny, ty = txy * lnx + sy * lny;  // N/m · m: ∫ σ0·n ds
      const double dux = 0.5 * (s.loop_u[2 * v] - start.loop_u[2 * v] + s.loop_u[2 * n] - start.loop_u[2 * n]);
      const double duy =
          0.5 * (s.loop_u[2 * v + 1] - start.loop_u[2 * v + 1] + s.loop_u[2 * n + 1] - start.loop_u[2 * n + 1]);
      w -= 0.5 * (tx * dux + ty * duy);
    }
  }
  return w;
}

double crack_release_fluid(const Mesh& mesh, const RunState& s, const RunState& start, std::size_t first_new_joint,
                           const std::vector<double>& pressure) {
  // −½ Σ ∫ p n·Δu ds on each new face edge v → n, p and Δu linear along it: the exact rule of
  // the header, n·L from the start positions as the flow effect's face load takes them.
  double w = 0;
  if (pressure.size() < 2 * mesh.loop_vertex_count()) return w;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (element_removed(mesh, s, static_cast<std::int32_t>(e))) continue;
    const std::int32_t b = mesh.element_loop_offset[e], end = mesh.element_loop_offset[e + 1];
    for (std::int32_t v = b; v < end; ++v) {
      if (mesh.loop_edge_joint[v] < static_cast<std::int32_t>(first_new_joint)) continue;
      const double pa = pressure[2 * static_cast<std::size_t>(v)], pb = pressure[2 * static_cast<std::size_t>(v) + 1];
      if (pa == 0 && pb == 0) continue;
      const std::int32_t n = v + 1 < end ? v + 1 : b;
      const double lnx = start.loop_xy[2 * n + 1] - start.loop_xy[2 * v + 1];
      const double lny = -(start.loop_xy[2 * n] - start.loop_xy[2 * v]);
      // m²: Δu·n·L at the edge's two ends
      const double una =
          (s.loop_u[2 * v] - start.loop_u[2 * v]) * lnx + (s.loop_u[2 * v + 1] - start.loop_u[2 * v + 1]) * lny;
      const double unb =
          (s.loop_u[2 * n] - start.loop_u[2 * n]) * lnx + (s.loop_u[2 * n + 1] - start.loop_u[2 * n + 1]) * lny;
      w -= 0.5 * ((2 * pa + pb) * una + (pa + 2 * pb) * unb) / 6;  // J/m: −½ ∫ p n·Δu ds
    }
  }
  return w;
}

}  // namespace nmm::solve
