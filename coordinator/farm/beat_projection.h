#pragma once
// A whole beat's time on W workers from a replay of a few of its steps (farm-sim of a
// window of the beat restarted from its checkpoint, e.g. tools/bench_seed_scale.sh) and the
// full beat of the same heart with cheaper units (its steps and their relative costs).
//
// The beat's steps (inflation excluded: preparation, not a beat) fall into segments: runs
// of consecutive steps in one circulation phase (the late-diastolic steps with both valves
// shut are a segment of their own, apart from the systolic isovolumic contraction although
// the valves label both alike). Replay and beat share step numbers. Per segment g:
//   replayed (the replay ran at least kMinReplayedSteps of its steps: one step, such as the
//   restart step a window begins with, is no sample of a segment):
//                s_g = the replay's predicted seconds per step over the steps it ran;
//   otherwise:   s_g = ρ · c_g, c_g the full beat's own cost per step in g (units' CPU +
//                macro) and ρ = Σ replay / Σ beat over the steps of the replayed segments
//                that the replay ran (the replayed units' time per unit of the beat's cost);
//   beat seconds T = Σ_g N_g s_g / beats  (N_g: steps in g).
// The segments not replayed are an extrapolation (stated so in the output): they assume
// the replayed units cost the same multiple of the beat's units everywhere.
#include <map>
#include <string>
#include <vector>

namespace fe2 {

inline constexpr int kMinReplayedSteps = 2;

/// One time step: its number, circulation phase and cost (seconds).
struct StepCost {
  int step = 0;
  std::string phase;
  double seconds = 0.0;
};

struct SegmentProjection {
  std::string phase;
  int first_step = 0, last_step = 0;
  double steps_per_beat = 0.0;    ///< N_g / beats
  double beat_cost = 0.0;         ///< c_g: the full beat's cost per step in g
  int replay_steps = 0;           ///< steps of g the replay ran (< kMinReplayedSteps: extrapolated)
  double seconds_per_step = 0.0;  ///< s_g
  bool replayed() const { return replay_steps >= kMinReplayedSteps; }
};

struct BeatProjection {
  std::vector<SegmentProjection> segments;  ///< in step order
  double ratio = 0.0;                       ///< ρ
  double seconds = 0.0;                     ///< T
};

/// Iterations' seconds summed per time step (`iteration_step`: each iteration's step, in
/// run order), each step labelled with its phase from `phase_of_step`. Throws InputError
/// naming `run` when a step has no phase there.
std::vector<StepCost> step_costs(const std::vector<int>& iteration_step, const std::vector<double>& iteration_seconds,
                                 const std::map<int, std::string>& phase_of_step, const std::string& run);

/// `beat`: every step of the full run over `beats` beats; `replay`: the replayed steps with
/// their predicted seconds (steps the beat lacks, or its inflation's, are ignored). Throws
/// InputError when the replay covers no segment, or `beats` < 1.
BeatProjection project_beat(const std::vector<StepCost>& beat, int beats, const std::vector<StepCost>& replay);

}  // namespace fe2
