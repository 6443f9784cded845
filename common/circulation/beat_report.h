#pragma once
// The "circulation" block of a coupled run's summary.json: the samples that make the
// reported beat (the last period, or the whole run if it is shorter), how many whole
// beats ran, each cavity's figures over that window (circulation_report.h), and systole,
// the sample of peak left-ventricular pressure in it.
#include "common/circulation/circulation_run.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <vector>

namespace fe2 {

/// Samples [first, last] of a run, and the run measured in beats.
struct BeatWindow {
  std::size_t first = 1, last = 0;
  int per_beat = 0;           ///< samples per period, from the mean step
  int beats = 0;              ///< whole periods run
  bool whole_period = false;  ///< the run lasts at least a period
};

/// `run` starts with the unloaded initial state (sample 0, left out of the window) and
/// needs at least two steps after it (size() >= 3).
BeatWindow beat_window(const std::vector<CirculationSample>& run, double period);

/// The sample of the highest pressure of `cavity` in the window (the earliest of equals).
std::size_t systole_sample(const std::vector<CirculationSample>& run, const BeatWindow& w,
                           int cavity);

/// description, beats_run, figures_over, period, cavities (cavity_figures) and
/// systole_step/_time/_cavity of Circulation::left_ventricle(); the step is the sample's
/// index, as displacement_<step>.vtu and units/unit_<id>_<step>.vtu number it.
nlohmann::json beat_report(const Circulation& c, const std::vector<CirculationSample>& run);

}  // namespace fe2
