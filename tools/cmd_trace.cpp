// `fe2heart trace summary|plot DIR` and `fe2heart farm-sim DIR`.
#include "common/error.h"
#include "common/spec/SpecNode.h"
#include "common/spec/spec_schemas.h"
#include "coordinator/farm/beat_projection.h"
#include "coordinator/farm/farm_sim.h"
#include "coordinator/farm/timing_noise.h"
#include "coordinator/farm/trace_analysis.h"
#include "tools/commands.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>

namespace fe2::cli {

int trace_summary(const std::string& dir, bool as_json) {
  const TraceSummary s = summarize(read_traces(dir));
  if (as_json) {
    fmt::print("{}\n", to_json(s).dump(2));
    return 0;
  }
  fmt::print("trace of {}: {} Newton iterations, {} workers, {} units\n", dir, s.iterations,
             s.workers, s.units);
  fmt::print("  time (s)        Entire {:.4g}   Micro+L+C {:.4g}   Macro {:.4g}   comm1 {:.3g}   comm2 {:.3g}\n",
             s.entire, s.micro_lc, s.macro, s.comm1, s.comm2);
  fmt::print("  Table I         Micro+L+C/Entire {:.3f}   Macro/Entire {:.4f}\n", s.micro_over_entire,
             s.macro_over_entire);
  fmt::print("  imbalance       max/mean worker busy: mean {:.3f}, max {:.3f}, last {:.3f}, "
             "after first rebalance {:.3f}\n",
             s.imbalance_mean, s.imbalance_max, s.imbalance_last, s.imbalance_after_first_rebalance);
  fmt::print("  micro phase     efficiency {:.3f} (Σ worker busy / (workers × Micro+L+C))\n",
             s.micro_efficiency);
  fmt::print("  communication   {:.0f} bytes per unit-iteration (paper: about 2 KB); comm1+comm2 = "
             "{:.2f} % of Micro+L+C\n",
             s.bytes_per_unit_iteration, s.micro_lc > 0 ? 100 * (s.comm1 + s.comm2) / s.micro_lc : 0.0);
  fmt::print("  migrations      {}{}\n", s.migrations,
             s.first_rebalance_iteration >= 0
                 ? fmt::format(" (first at iteration {} of the trace)", s.first_rebalance_iteration + 1)
                 : "");
  const MacroCost& m = s.macro_cost;
  if (!m.cpu_recorded) return 0;  // traces of older runs: no breakdown
  fmt::print("  macro           {} coordinator(s); CPU of the busiest summed over iterations {:.4g} s (all "
             "coordinators {:.4g} s)\n",
             m.coordinators, m.cpu_critical, m.cpu_total);
  const auto row = [](const char* what, const MacroCost::Kind& k) {
    if (k.count == 0) return;
    fmt::print("    {:<20} {:>5} iterations, medians: CPU {:.4g} s, wall {:.4g} s (assembly {:.4g}, solve "
               "{:.4g}), GMRES {:.3g}\n",
               what, k.count, k.cpu, k.wall, k.assemble, k.solve, k.gmres);
  };
  row("factorizing", m.factorizing);
  row("kept factor", m.kept);
  row("converged (no solve)", m.none);
  if (m.fluid_assembly > 0)
    fmt::print("  blood           its terms' assembly {:.4g} s = {:.3f} of Macro (coordinator 0; the solve is of wall "
               "and blood together)\n",
               m.fluid_assembly, m.macro_wall > 0 ? m.fluid_assembly / m.macro_wall : 0.0);
  return 0;
}

int trace_plot(const std::string& dir, const std::string& out) {
  read_traces(dir);  // clear error if the folder has no traces
  const std::string script = FE2_TRACE_PLOT_SCRIPT;
  if (!std::filesystem::exists(script))
    throw InputError(fmt::format("trace plot: script '{}' not found (run from a source build)", script));
  const std::string cmd = fmt::format("/usr/bin/python3 '{}' '{}'{}", script, dir,
                                      out.empty() ? "" : fmt::format(" --out '{}'", out));
  const int rc = std::system(cmd.c_str());
  if (rc != 0)
    throw Error(fmt::format("trace plot: '{}' failed (status {}); it needs Debian's "
                            "python3-matplotlib (apt-get install -y python3-matplotlib)",
                            cmd, rc));
  return 0;
}

namespace {

/// The run's own farm settings (DIR/spec.json), then the command line's overrides.
FarmOptions farm_options_of_run(const FarmSimOptions& o) {
  const std::string file = o.dir + "/spec.json";
  if (!std::filesystem::exists(file))
    throw InputError(fmt::format("farm-sim: '{}' not found; expected the spec.json that "
                                 "`fe2heart run` writes into its output folder",
                                 file));
  const json spec = read_json_file(file);
  if (!spec.is_object())
    throw InputError(fmt::format("farm-sim: '{}': got a JSON {}, expected a run spec object",
                                 file, spec.type_name()));
  FarmOptions f = FarmOptions::from_spec(SpecNode(spec, "", run_spec_schema()).child("farm"));
  if (o.policy)
    f.policy = FarmOptions::policy_of(*o.policy);
  if (o.rebalance_at)
    f.rebalance_at = *o.rebalance_at == "step" ? FarmOptions::When::step : FarmOptions::When::iteration;
  if (o.latency) f.latency = *o.latency;
  if (o.bandwidth) f.bandwidth = *o.bandwidth;
  if (o.batch) f.batch = *o.batch;
  if (o.min_gain) f.min_gain = *o.min_gain;
  if (o.tolerated_imbalance) f.tolerated_imbalance = *o.tolerated_imbalance;
  return f;
}

/// A run's summary.json: the circulation phase of each step in its history.
std::map<int, std::string> phases_of_run(const std::string& dir, int* beats = nullptr) {
  const std::string file = dir + "/summary.json";
  if (!std::filesystem::exists(file))
    throw InputError(fmt::format("farm-sim --beat: '{}' not found; expected the summary.json of a run", file));
  const json s = read_json_file(file);
  std::map<int, std::string> phase;
  if (s.is_object() && s.contains("history") && s["history"].is_array())
    for (const json& h : s["history"]) {
      if (!h.contains("step") || !h.contains("circulation") || !h["circulation"].is_object() ||
          h["circulation"].empty())
        continue;
      const json& first = h["circulation"].begin().value();
      if (first.contains("phase")) phase[h["step"].get<int>()] = first["phase"].get<std::string>();
    }
  if (phase.empty())
    throw InputError(fmt::format("farm-sim --beat: '{}' has no circulation phases in its history; expected a "
                                 "run with a circulation (a beat)",
                                 file));
  if (beats) {
    *beats = 1;
    if (s.contains("circulation") && s["circulation"].contains("beats_run"))
      *beats = std::max(1, s["circulation"]["beats_run"].get<int>());
  }
  return phase;
}

/// One simulated farm's projection of the beat.
struct BeatRow {
  int workers = 0, units_per_worker = 0;
  BeatProjection beat;
};

/// What a beat costs on the simulated farm: the replay's predicted Entire per step where
/// it ran, the full beat's relative cost per step elsewhere (beat_projection.h).
struct BeatContext {
  std::vector<StepCost> beat;
  int beats = 1;
  std::map<int, std::string> replay_phase;
};

BeatContext beat_context(const FarmSimOptions& o, const FarmSimInput& replay) {
  if (replay.step.size() != replay.macro.size())
    throw InputError(fmt::format("farm-sim --beat: the traces of '{}' do not record their steps (an older run)", o.dir));
  BeatContext b;
  b.replay_phase = phases_of_run(o.dir);
  const FarmSimInput full = farm_sim_input(read_traces(o.beat));
  if (full.step.size() != full.macro.size())
    throw InputError(fmt::format("farm-sim --beat: the traces of '{}' do not record their steps (an older run)", o.beat));
  std::vector<double> cost(full.macro.size());
  for (std::size_t i = 0; i < cost.size(); ++i) {
    cost[i] = full.macro[i];
    for (double c : full.cost[i]) cost[i] += c;
  }
  b.beat = step_costs(full.step, cost, phases_of_run(o.beat, &b.beats), o.beat);
  return b;
}

void print_beat_projection(const FarmSimOptions& o, const BeatContext& b, const std::vector<BeatRow>& rows,
                           int coordinators) {
  const BeatProjection& first = rows.front().beat;
  fmt::print("\none beat of {} ({} beat(s) run; inflation left out), on the simulated farm, by segment (consecutive "
             "steps of one phase): a segment the replay ran ({}+ steps) takes its predicted Entire per step "
             "(replayed); any other, the beat's own cost per step there (units' CPU + macro) x rho, the replay's "
             "time per unit of the beat's cost on the steps both ran (extrapolated: it assumes the replayed units "
             "cost the same multiple of the beat's everywhere).\n",
             o.beat, b.beats, kMinReplayedSteps);
  for (std::size_t i = 0; i < first.segments.size(); ++i) {
    const SegmentProjection& g = first.segments[i];
    fmt::print("  {:>2} {:<24} steps {:>4}-{:<4} {:>5.1f} per beat, the beat's cost {:.4g} s per step; {}\n", i + 1,
               g.phase, g.first_step, g.last_step, g.steps_per_beat, g.beat_cost,
               g.replayed() ? fmt::format("replayed ({} steps)", g.replay_steps)
                            : fmt::format("extrapolated (the replay ran {} step{} of it)", g.replay_steps,
                                          g.replay_steps == 1 ? "" : "s"));
  }
  fmt::print("\n{:>8} {:>6} | seconds per step in segment 1..{} | {:>6} {:>10} {:>12}\n", "workers", "u/w",
             first.segments.size(), "rho", "beat s", "core-hours");
  for (const BeatRow& r : rows) {
    fmt::print("{:>8} {:>6} |", r.workers, r.units_per_worker);
    for (const SegmentProjection& g : r.beat.segments) fmt::print(" {:>9.4g}", g.seconds_per_step);
    fmt::print(" | {:>6.3g} {:>10.4g} {:>12.4g}\n", r.beat.ratio, r.beat.seconds,
               (r.workers + coordinators) * r.beat.seconds / 3600.0);
  }
  fmt::print("core-hours: (workers + {} coordinator(s)) x the beat's seconds.\n", coordinators);
}

}  // namespace

int farm_sim(const FarmSimOptions& o) {
  const TraceData t = read_traces(o.dir);
  FarmSimInput in = farm_sim_input(t);
  int coordinators = macro_cost(t).coordinators;
  if (!o.macro_from.empty()) {
    const MacroCost c = macro_cost(read_traces(o.macro_from));
    replace_macro(in, c);
    coordinators = c.coordinators;
    fmt::print("macro costs from {} ({} coordinator(s), {}): {:.4g} s per factorizing iteration, {:.4g} s "
               "per kept-factor one, {:.4g} s per converged check\n",
               o.macro_from, c.coordinators, c.cpu_recorded ? "busiest coordinator's CPU" : "wall time",
               c.predict(MacroSolveKind::factorizing), c.predict(MacroSolveKind::kept),
               c.predict(MacroSolveKind::none));
  }
  const CostSpread spread = cost_spread(in);
  fmt::print("cost spread of the replayed jobs (timing_noise.h), against the median of their kind in their "
             "iteration: per unit (persistent) {:.1f} %, per job {:.1f} %, lag-1 correlation of a unit's "
             "per-job deviation {:.2f} ({}); {} of {} jobs in kinds of {} or more\n",
             100.0 * spread.persistent, 100.0 * spread.noise, spread.lag1,
             std::abs(spread.lag1) < 0.2 ? "it does not repeat: timing noise" : "it repeats: work",
             spread.jobs, spread.all_jobs, kMinJobsOfAKind);
  if (o.without_timing_noise) {
    remove_timing_noise(in);
    fmt::print("--without-timing-noise: each such job replayed at its kind's median x its unit's persistent "
               "factor\n");
  }
  const long long measured = static_cast<long long>(in.state_bytes.size());
  const FarmOptions f = farm_options_of_run(o);
  std::vector<int> worker_counts = o.workers;
  if (worker_counts.empty()) worker_counts = {6144, 60000, 600000};
  fmt::print("farm-sim of {}: {} measured units, {} Newton iterations replayed; network "
             "latency {:.1e} s, bandwidth {:.2g} B/s, batch {}; policy {}, rebalance at {}, "
             "tolerated imbalance {}, min gain {}; macro time as measured × {}\n",
             o.dir, measured, in.macro.size(), f.latency, f.bandwidth, f.batch,
             FarmOptions::name_of(f.policy), f.rebalance_at == FarmOptions::When::step ? "step" : "iteration",
             f.tolerated_imbalance, f.min_gain, o.macro_scale);
  fmt::print("efficiency 'vs W/4': the paper's strong scaling (same units on W/4 workers as the "
             "base, e.g. 1536 -> 6144);\n'vs balance': Σ work / W over the predicted time.\n\n");
  std::optional<BeatContext> beat;
  if (!o.beat.empty()) beat = beat_context(o, in);
  std::vector<BeatRow> projections;
  fmt::print("{:>8} {:>6} {:>10} | {:>12} {:>12} | {:>9} {:>9} | {:>9} {:>9} | {:>6}\n", "workers",
             "u/w", "units", "Micro+L+C s", "Entire s", "micro/W4", "entire/W4", "micro/bal",
             "ent./bal", "moves");
  for (int W : worker_counts)
    for (int k : o.units_per_worker) {
      const long long U = static_cast<long long>(W) * k;
      if (U > o.max_units) continue;
      const FarmSimResult r = simulate_farm(in, W, U, f, o.macro_scale);
      const int base = std::max(1, W / 4);
      const FarmSimResult b = simulate_farm(in, base, U, f, o.macro_scale);
      const double micro_rel = (b.micro * base) / (r.micro * W);
      const double entire_rel = (b.entire * base) / (r.entire * W);
      const double macro_total = r.entire - r.micro;
      fmt::print("{:>8} {:>6} {:>10} | {:>12.4g} {:>12.4g} | {:>9.3f} {:>9.3f} | {:>9.3f} {:>9.3f} | {:>6}\n",
                 W, k, U, r.micro, r.entire, micro_rel, entire_rel, (r.work / W) / r.micro,
                 (r.work / W + macro_total) / r.entire, r.migrations);
      if (beat) {
        std::vector<double> entire(r.makespan.size());
        for (std::size_t i = 0; i < entire.size(); ++i) entire[i] = r.makespan[i] + in.macro[i] * o.macro_scale;
        projections.push_back({W, k, project_beat(beat->beat, beat->beats,
                                                  step_costs(in.step, entire, beat->replay_phase, o.dir))});
      }
    }
  if (beat && !projections.empty()) print_beat_projection(o, *beat, projections, coordinators);
  fmt::print("\npaper (T2K, 6144 cores, one unit each, vs 1536): entire 0.893, micro+L+C 0.918\n");
  return 0;
}

}  // namespace fe2::cli
