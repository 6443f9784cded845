#pragma once
// A standalone circulation run: elastance ventricles coupled strongly to the circulation
// (ElastanceVentricle.h, couple_step), step by step over the spec's time.
#include "common/circulation/Circulation.h"
#include "common/circulation/circulation_run_spec.h"

#include <vector>

namespace fe2 {

/// One sample: the state after a step (sample 0 is the initial state, without flows).
struct CirculationSample {
  double t = 0.0;
  std::vector<double> p, V;       ///< per cavity (Pa, mm³)
  CavityFlows flows;              ///< of the step that ended here (empty at sample 0)
  double blood_volume = 0.0;      ///< compartments + cavities (mm³)
  int newton_iterations = 0;      ///< of the pressure Newton (couple_step)
};

/// Runs the whole spec; returns steps + 1 samples.
std::vector<CirculationSample> run_circulation(const CirculationRunSpec& spec);

}  // namespace fe2
