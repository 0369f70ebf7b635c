// The mean stress of a run's rock, as the fracture tests read a specimen's load: the
// area-weighted mean of one stress component over its elements,
//     σ̄_k = Σ_e A_e·σ_e,k / Σ_e A_e      (Pa; k = 0 σxx, 1 σyy, 2 τxy; σ_e the element's mean),
// which in equilibrium without body force is the force the rock carries across a section per m
// (∫σ dA = ∮ t⊗x ds). `skip` (optional, [me]): elements left out (a run's debris).
#pragma once

#include <cstdint>
#include <vector>

#include "common/mesh.h"
#include "solver/stepping/run_view.h"

namespace nmm::test {

inline double rock_mean_stress(const solve::RunView& v, int k, const std::vector<std::uint8_t>* skip = nullptr) {
  const std::vector<double> s = solve::mean_stress(v);
  double sum = 0, area = 0;
  for (std::size_t e = 0; e < v.mesh.element_count(); ++e) {
    if (skip && !skip->empty() && (*skip)[e]) continue;
    const double a = element_area(v.mesh, e);
    sum += a * s[3 * e + static_cast<std::size_t>(k)];
    area += a;
  }
  return sum / area;
}

}  // namespace nmm::test
