#include "common/circulation/circulation_run.h"

#include <numeric>

namespace fe2 {

std::vector<CirculationSample> run_circulation(const CirculationRunSpec& spec) {
  const Circulation& circ = *spec.circulation;
  const int n = circ.cavities();
  std::vector<double> committed(circ.state_size()), current(circ.state_size());
  circ.initial_state(committed);
  CirculationSample s;
  for (int c = 0; c < n; ++c) {
    s.V.push_back(spec.ventricles[c].initial_volume());
    s.p.push_back(spec.ventricles[c].pressure(0.0, s.V[c]));
  }
  circ.set_cavity_pressures(committed, s.p);
  s.blood_volume = circ.blood_volume(committed) + std::accumulate(s.V.begin(), s.V.end(), 0.0);
  std::vector<CirculationSample> out;
  out.reserve(spec.steps + 1);
  out.push_back(s);
  const double dt = spec.dt();
  for (int k = 1; k <= spec.steps; ++k) {
    // t_k as k·Δt (not summed), so beat boundaries fall on steps exactly.
    s.t = k * dt;
    s.flows = couple_step(circ, spec.ventricles, s.t, dt, committed, current, s.p, s.V,
                          &s.newton_iterations);
    committed.swap(current);
    s.blood_volume = circ.blood_volume(committed) + std::accumulate(s.V.begin(), s.V.end(), 0.0);
    out.push_back(s);
  }
  return out;
}

}  // namespace fe2
