#include "coordinator/farm/beat_projection.h"

#include "common/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace fe2 {

namespace {
constexpr const char* kInflation = "inflation";
}

std::vector<StepCost> step_costs(const std::vector<int>& iteration_step, const std::vector<double>& iteration_seconds,
                                 const std::map<int, std::string>& phase_of_step, const std::string& run) {
  FE2_CHECK(iteration_step.size() == iteration_seconds.size(), "step_costs: {} steps for {} iterations",
            iteration_step.size(), iteration_seconds.size());
  std::vector<StepCost> steps;
  for (std::size_t i = 0; i < iteration_step.size(); ++i) {
    if (i == 0 || iteration_step[i] != iteration_step[i - 1]) {
      const auto it = phase_of_step.find(iteration_step[i]);
      if (it == phase_of_step.end())
        throw InputError(fmt::format("{}: step {} of the traces has no circulation phase in summary.json's "
                                     "history; expected a run with a circulation whose summary covers its traces",
                                     run, iteration_step[i]));
      steps.push_back({it->second, 0.0});
    }
    steps.back().seconds += iteration_seconds[i];
  }
  return steps;
}

BeatProjection project_beat(const std::vector<StepCost>& beat, int beats, const std::vector<StepCost>& replay) {
  if (beats < 1) throw InputError(fmt::format("beat projection: {} beats, expected at least one", beats));
  BeatProjection p;
  std::map<std::string, std::size_t> row;  // phase -> index in p.phases
  std::vector<double> beat_total;
  for (const StepCost& s : beat) {
    if (s.phase == kInflation) continue;
    auto [it, added] = row.emplace(s.phase, p.phases.size());
    if (added) {
      p.phases.push_back({s.phase});
      beat_total.push_back(0.0);
    }
    p.phases[it->second].steps_per_beat += 1.0;
    beat_total[it->second] += s.seconds;
  }
  std::vector<double> replay_total(p.phases.size(), 0.0);
  for (const StepCost& s : replay) {
    const auto it = row.find(s.phase);
    if (it == row.end()) continue;  // the replay's inflation, or a phase the beat never reached
    ++p.phases[it->second].replay_steps;
    replay_total[it->second] += s.seconds;
  }
  double replay_sum = 0.0, beat_sum = 0.0;
  for (std::size_t i = 0; i < p.phases.size(); ++i) {
    PhaseProjection& ph = p.phases[i];
    ph.beat_cost = beat_total[i] / ph.steps_per_beat;
    if (ph.replay_steps < kMinReplayedSteps) continue;
    ph.seconds_per_step = replay_total[i] / ph.replay_steps;
    replay_sum += replay_total[i];
    beat_sum += ph.replay_steps * ph.beat_cost;
  }
  if (!(replay_sum > 0.0) || !(beat_sum > 0.0))
    throw InputError(fmt::format("beat projection: the replayed steps cover no phase of the full beat (after "
                                 "inflation) with {} steps or more; expected a replay of some of the beat's steps",
                                 kMinReplayedSteps));
  p.ratio = replay_sum / beat_sum;
  for (PhaseProjection& ph : p.phases) {
    ph.steps_per_beat /= beats;
    if (ph.replay_steps < kMinReplayedSteps) ph.seconds_per_step = p.ratio * ph.beat_cost;
    p.seconds += ph.steps_per_beat * ph.seconds_per_step;
  }
  return p;
}

}  // namespace fe2
