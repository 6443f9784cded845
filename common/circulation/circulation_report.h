#pragma once
// What a run with a circulation reports, shared by `fe2heart circulation` (elastance
// ventricles) and `fe2heart run` (the wall's cavities): circulation.csv, one line per
// sample, and the haemodynamic figures of each cavity over a window (beat_summary.h).
#include "common/circulation/circulation_run.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace fe2 {

/// t, per cavity p, V, Q_in, Q_out, Q_net, phase; every compartment's pressure
/// ("p:lv.arterial"), every connection's flow ("Q:lv.Zc"), the blood volume.
std::string circulation_csv(const Circulation& c, const std::vector<CirculationSample>& run);

/// Per cavity: EDV, ESV, SV, EF, peak pressure, dP/dt extremes, stroke work over samples
/// [first, last]; with beats ≥ 1 (`per_beat` samples each) also the EDV of every beat and
/// the relative EDV change over the last beat.
nlohmann::json cavity_figures(const Circulation& c, const std::vector<CirculationSample>& run,
                              size_t first, size_t last, int beats, int per_beat);

}  // namespace fe2
