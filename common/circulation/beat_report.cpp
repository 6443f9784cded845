#include "common/circulation/beat_report.h"

#include "common/circulation/circulation_report.h"
#include "common/error.h"

#include <cmath>

namespace fe2 {

BeatWindow beat_window(const std::vector<CirculationSample>& run, double period) {
  FE2_CHECK(run.size() >= 3, "beat_window: {} samples, expected the initial state and two steps",
            run.size());
  BeatWindow w;
  w.last = run.size() - 1;
  const double t_end = run.back().t;
  // The relative slack keeps a sample that lands on t_end - period by rounding in.
  while (w.first + 1 < run.size() && run[w.first + 1].t <= t_end - period + 1e-9 * period) ++w.first;
  w.per_beat = static_cast<int>(std::lround(period / (t_end / static_cast<double>(run.size() - 1))));
  w.beats = w.per_beat > 0 ? static_cast<int>((run.size() - 1) / static_cast<std::size_t>(w.per_beat)) : 0;
  w.whole_period = t_end >= period * (1 - 1e-9);
  return w;
}

std::size_t systole_sample(const std::vector<CirculationSample>& run, const BeatWindow& w,
                           int cavity) {
  const auto k = static_cast<std::size_t>(cavity);
  std::size_t systole = w.first;
  for (std::size_t i = w.first; i <= w.last; ++i)
    if (run[i].p[k] > run[systole].p[k]) systole = i;
  return systole;
}

nlohmann::json beat_report(const Circulation& c, const std::vector<CirculationSample>& run) {
  const BeatWindow w = beat_window(run, c.period());
  const std::size_t systole = systole_sample(run, w, c.left_ventricle());
  return {{"description", c.description()},
          {"beats_run", w.beats},
          {"figures_over", w.whole_period ? "the last period" : "the whole run (shorter than a period)"},
          {"period", c.period()},
          {"cavities", cavity_figures(c, run, w.first, w.last, w.beats, w.per_beat)},
          {"systole_step", systole},
          {"systole_time", run[systole].t},
          {"systole_cavity", c.cavity_names()[static_cast<std::size_t>(c.left_ventricle())]}};
}

}  // namespace fe2
