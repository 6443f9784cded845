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
      steps.push_back({iteration_step[i], it->second, 0.0});
    }
    steps.back().seconds += iteration_seconds[i];
  }
  return steps;
}

BeatProjection project_beat(const std::vector<StepCost>& beat, int beats, const std::vector<StepCost>& replay) {
  if (beats < 1) throw InputError(fmt::format("beat projection: {} beats, expected at least one", beats));
  std::map<int, double> replayed;  // step -> predicted seconds
  for (const StepCost& s : replay) replayed[s.step] += s.seconds;
  BeatProjection p;
  std::vector<double> beat_total, replay_total, beat_on_replayed;
  for (std::size_t i = 0; i < beat.size(); ++i) {
    const StepCost& s = beat[i];
    if (s.phase == kInflation) continue;
    if (p.segments.empty() || p.segments.back().phase != s.phase || p.segments.back().last_step + 1 != s.step) {
      p.segments.push_back({s.phase, s.step, s.step});
      beat_total.push_back(0.0);
      replay_total.push_back(0.0);
      beat_on_replayed.push_back(0.0);
    }
    SegmentProjection& g = p.segments.back();
    g.last_step = s.step;
    g.steps_per_beat += 1.0;
    beat_total.back() += s.seconds;
    if (const auto it = replayed.find(s.step); it != replayed.end()) {
      ++g.replay_steps;
      replay_total.back() += it->second;
      beat_on_replayed.back() += s.seconds;
    }
  }
  double replay_sum = 0.0, beat_sum = 0.0;
  for (std::size_t i = 0; i < p.segments.size(); ++i) {
    SegmentProjection& g = p.segments[i];
    g.beat_cost = beat_total[i] / g.steps_per_beat;
    if (!g.replayed()) continue;
    g.seconds_per_step = replay_total[i] / g.replay_steps;
    replay_sum += replay_total[i];
    beat_sum += beat_on_replayed[i];
  }
  if (!(replay_sum > 0.0) || !(beat_sum > 0.0))
    throw InputError(fmt::format("beat projection: the replayed steps cover no segment of the full beat (after "
                                 "inflation) with {} steps or more; expected a replay of some of the beat's steps "
                                 "(a window restarted from its checkpoint)",
                                 kMinReplayedSteps));
  p.ratio = replay_sum / beat_sum;
  for (SegmentProjection& g : p.segments) {
    if (!g.replayed()) g.seconds_per_step = p.ratio * g.beat_cost;
    g.steps_per_beat /= beats;
    p.seconds += g.steps_per_beat * g.seconds_per_step;
  }
  return p;
}

}  // namespace fe2
