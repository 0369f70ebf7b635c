// What nmm-study reads off its fracture runs (the read-offs and their closed forms in the header).
#include "studies/fracture_readings.h"

#include <cmath>
#include <vector>

#include "common/mesh.h"
#include "solver/output/run_energy.h"
#include "solver/stepping/fracture_effect.h"
#include "solver/stepping/run_view.h"
#include "solver/stepping/time_stepper.h"

namespace nmm::studies {

namespace {

// Load units: |Σ A_e σ_e,k| / lever over the elements of `body` that are not debris.
double load_of(const solve::RunView& v, int body, int component, double lever) {
  const std::vector<double> s = solve::mean_stress(v);
  const std::vector<std::uint8_t>& debris = fracture_of(v).debris();
  double sum = 0;
  for (std::size_t e = 0; e < v.mesh.element_count(); ++e) {
    if (!debris.empty() && debris[e]) continue;
    if (v.mesh.element_body[e] != body) continue;
    sum += element_area(v.mesh, e) * s[3 * e + static_cast<std::size_t>(component)];
  }
  return std::abs(sum) / lever;
}

}  // namespace

FractureRun run_fracture(solve::TimeStepper& st, double t_end, std::size_t support,
                         const std::function<void(std::int64_t)>& on_step) {
  FractureRun r;
  // The energy balance, metered as nmm-solve meters it (run_energy.h); only the
  // last row is read, so no row is kept.
  solve::RunEnergy meter(st.view(), false);
  solve::EnergyRow intact = meter.meter().state_terms(st.view().state, meter.sources());
  double load = 0;
  r.outcome = st.run_until(t_end * (1 - 1e-9), [&](std::int64_t n) {
    const solve::RunView v = st.view();
    meter.after_step(v, true);
    const solve::EnergyRow& row = meter.rows().back();
    const double previous = load;
    load = solve::support_reactions(v).at(support).load();
    const auto& segments = fracture_of(v).segments();
    if (segments.empty()) {
      intact = row;
    } else if (r.first_crack_step < 0) {
      r.first_crack_step = segments.front().step;
      r.first_crack_load = previous;
    }
    if (load > r.peak) r.peak = load, r.peak_step = n;
    r.steps = n;
    on_step(n);
  });
  const solve::RunView v = st.view();
  if (!meter.rows().empty()) {
    const solve::EnergyRow& end = meter.rows().back();
    r.fracture = end.fracture;
    r.residual = end.residual;
    if (r.first_crack_step >= 0) r.released = end.fracture + (end.damped - intact.damped);
  }
  r.stored_intact = intact.strain + intact.springs;
  r.cracks = fracture_of(v).crack_count();
  r.segments = static_cast<int>(fracture_of(v).segments().size());
  return r;
}

GrowthLoad run_until_growth(solve::TimeStepper& st, double t_end, const std::function<void(std::int64_t)>& on_step) {
  GrowthLoad g;
  std::vector<double> load;  // Pa, mean σyy after each intact step
  while (!g.grew && st.view().state.time < t_end * (1 - 1e-9)) {
    g.outcome = st.run_until(t_end, [&](std::int64_t) {
      ++g.steps;
      on_step(g.steps);
      const solve::RunView v = st.view();
      if (!fracture_of(v).segments().empty()) {
        g.grew = true;
        g.segments = static_cast<int>(fracture_of(v).segments().size());
        return;
      }
      double area = 0;  // m²: the lever that makes the load the plate's mean σyy
      for (std::size_t e = 0; e < v.mesh.element_count(); ++e) area += element_area(v.mesh, e);
      load.push_back(load_of(v, 0, 1, area));
    }, 1);
    if (!g.outcome.ok()) break;
  }
  if (g.grew && load.size() >= 2) {
    g.previous = load.back();
    g.load = load.back() + (load.back() - load[load.size() - 2]);
  }
  return g;
}

}  // namespace nmm::studies
