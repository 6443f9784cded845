// `fe2heart circulation SPEC --out DIR`: a 0D circulation run alone, time-varying
// elastance ventricles standing in for the wall (common/circulation/). Writes
// DIR/circulation.csv (every step), DIR/summary.json (per cavity EDV, ESV, SV, EF, peak
// pressure, dP/dt, stroke work; blood volume and its drift) and DIR/pv_loop.png.
#include "common/circulation/circulation_report.h"
#include "common/circulation/circulation_run.h"
#include "common/circulation/circulation_run_spec.h"
#include "common/io/atomic_file.h"
#include "tools/commands.h"
#include "tools/output_folder.h"

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

namespace fe2::cli {
namespace {

json summary(const CirculationRunSpec& spec, const std::vector<CirculationSample>& run, double seconds) {
  const Circulation& c = *spec.circulation;
  const int per_beat = spec.beats ? spec.steps / spec.beats : spec.steps;
  // The window of the figures: the last whole beat, or the whole run.
  const size_t last = run.size() - 1, first = spec.beats ? last - per_beat : 0;
  const json cav = cavity_figures(c, run, first, last, spec.beats, per_beat);
  double drift = 0.0;
  int max_it = 0;
  for (const auto& s : run) {
    drift = std::max(drift, std::abs(s.blood_volume - run.front().blood_volume));
    max_it = std::max(max_it, s.newton_iterations);
  }
  return {{"title", spec.title},
          {"complete", true},
          {"circulation", c.description()},
          {"units", {{"pressure", "Pa"}, {"volume", "mm^3"}, {"time", "s"}, {"flow", "mm^3/s"},
                     {"stroke_work", "Pa mm^3 (1e-9 J)"}}},
          {"steps", spec.steps},
          {"dt", spec.dt()},
          {"t_end", spec.t_end},
          {"beats", spec.beats},
          {"figures_over", spec.beats ? "the last beat" : "the whole run"},
          {"cavities", cav},
          {"blood_volume",
           {{"initial", run.front().blood_volume},
            {"final", run.back().blood_volume},
            {"max_drift", drift},
            {"max_relative_drift", drift / run.front().blood_volume},
            {"conserved", c.closed()}}},
          {"max_newton_iterations", max_it},
          {"wall_seconds", seconds}};
}

}  // namespace

int circulation(const CirculationOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const json j = read_json_file(o.spec);
  const CirculationRunSpec spec = read_circulation_run_spec(j, o.spec);
  spdlog::info("{}", spec.circulation->description());
  spdlog::info("{} steps of {:.4g} s to t = {} s", spec.steps, spec.dt(), spec.t_end);
  refuse_earlier_output(o.out, "an fe2heart run", earlier_run_files(o.out), o.overwrite);
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot create the folder ({})", o.out, ec.message()));
  const auto run = run_circulation(spec);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_file_atomically(o.out + "/circulation.csv", circulation_csv(*spec.circulation, run));
  const json s = summary(spec, run, seconds);
  write_file_atomically(o.out + "/summary.json", s.dump(2) + "\n");
  for (const auto& [name, c] : s["cavities"].items())
    spdlog::info("{}: EDV {:.1f} mL, ESV {:.1f} mL, SV {:.1f} mL, EF {:.1f} %, peak {:.1f} kPa ({:.0f} mmHg), "
                 "stroke work {:.3f} J", name, c["EDV"].get<double>() / 1e3, c["ESV"].get<double>() / 1e3,
                 c["SV"].get<double>() / 1e3, 100 * c["EF"].get<double>(),
                 c["peak_pressure"].get<double>() / 1e3, c["peak_pressure"].get<double>() / 133.322387415,
                 c["stroke_work_J"].get<double>());
  spdlog::info("blood volume drift {:.2e} (relative; {})", s["blood_volume"]["max_relative_drift"].get<double>(),
               spec.circulation->closed() ? "closed loop: conserved" : "open: Windkessel drains");
  // The picture; a missing matplotlib costs only the PNG.
  const std::string cmd = fmt::format("/usr/bin/python3 '{}' '{}' > /dev/null 2>&1", FE2_PV_LOOP_SCRIPT, o.out);
  if (std::system(cmd.c_str()) != 0)
    spdlog::warn("no pv_loop.png, pv_time.png: '{}' failed (it needs Debian's python3-matplotlib)", cmd);
  spdlog::info("results: {0}/summary.json, {0}/circulation.csv, {0}/pv_loop.png, {0}/pv_time.png ({1:.2f} s)",
               o.out, seconds);
  return 0;
}

int validate_circulation(const std::string& file) {
  const CirculationRunSpec spec = read_circulation_run_spec(read_json_file(file), file);
  fmt::print("{}: OK: circulation spec, {} steps to t = {} s; {}\n", file, spec.steps, spec.t_end,
             spec.circulation->description());
  return 0;
}

}  // namespace fe2::cli
