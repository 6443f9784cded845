#include "common/circulation/circulation_report.h"

#include "common/circulation/beat_summary.h"

#include <spdlog/fmt/fmt.h>

#include <cmath>

namespace fe2 {

std::string circulation_csv(const Circulation& c, const std::vector<CirculationSample>& run) {
  std::string out = "t";
  for (const auto& n : c.cavity_names())
    out += fmt::format(",p_{0},V_{0},Q_in_{0},Q_out_{0},Q_net_{0},phase_{0}", n);
  for (const auto& n : c.compartment_names()) out += ",p:" + n;
  for (const auto& n : c.connection_names()) out += ",Q:" + n;
  out += ",blood_volume\n";
  const size_t nodes = c.compartment_names().size(), links = c.connection_names().size();
  for (const auto& s : run) {
    const bool flows = !s.flows.Q_net.empty();
    out += fmt::format("{:.9g}", s.t);
    for (int k = 0; k < c.cavities(); ++k)
      out += fmt::format(",{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{}", s.p[k], s.V[k],
                         flows ? s.flows.Q_in[k] : 0.0, flows ? s.flows.Q_out[k] : 0.0,
                         flows ? s.flows.Q_net[k] : 0.0, flows ? s.flows.phase[k] : "initial");
    for (size_t k = 0; k < nodes; ++k) out += flows ? fmt::format(",{:.10g}", s.flows.pressures[k]) : ",";
    for (size_t k = 0; k < links; ++k) out += flows ? fmt::format(",{:.10g}", s.flows.flows[k]) : ",";
    out += fmt::format(",{:.17g}\n", s.blood_volume);
  }
  return out;
}

nlohmann::json cavity_figures(const Circulation& c, const std::vector<CirculationSample>& run,
                              size_t first, size_t last, int beats, int per_beat) {
  std::vector<double> t;
  for (const auto& s : run) t.push_back(s.t);
  nlohmann::json cav = nlohmann::json::object();
  for (int k = 0; k < c.cavities(); ++k) {
    std::vector<double> p, V;
    for (const auto& s : run) p.push_back(s.p[k]), V.push_back(s.V[k]);
    const BeatFigures b = beat_figures(t, p, V, first, last);
    nlohmann::json edv = nlohmann::json::array();
    for (int beat = 0; beat < beats; ++beat)
      edv.push_back(beat_figures(t, p, V, beat * per_beat, (beat + 1) * per_beat).EDV);
    nlohmann::json j = {{"EDV", b.EDV},
                        {"ESV", b.ESV},
                        {"SV", b.SV},
                        {"EF", b.EF},
                        {"peak_pressure", b.peak_pressure},
                        {"dpdt_max", b.dpdt_max},
                        {"dpdt_min", b.dpdt_min},
                        {"stroke_work", b.stroke_work},
                        {"stroke_work_J", b.stroke_work * 1e-9},
                        {"EDV_per_beat", edv}};
    if (beats >= 2)
      j["EDV_change_last_beat"] =
          std::abs(edv[beats - 1].get<double>() - edv[beats - 2].get<double>()) / edv[beats - 1].get<double>();
    cav[c.cavity_names()[k]] = j;
  }
  return cav;
}

}  // namespace fe2
