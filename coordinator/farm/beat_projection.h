#pragma once
// A whole beat's time on W workers from a replay of a few of its steps (farm-sim of a
// window run, e.g. tools/bench_seed_scale.sh) and a full beat of the same heart with
// cheaper units (its phases' lengths and relative costs).
//
// Per circulation phase p of the beat (inflation excluded: it is preparation, not a beat):
//   covered by the replay (at least kMinReplayedSteps of its steps in p: one step, such as
//   the restart step a window begins with, is no sample of a phase):
//                           s_p = the replay's predicted seconds per step in p;
//   not covered:            s_p = ρ · c_p, where c_p is the full beat's own cost per step
//                           in p (units' CPU + macro) and ρ = Σ_q n_q s_q / Σ_q n_q c_q
//                           over the covered phases q (n_q: the replay's steps in q), the
//                           replay's time per unit of the full beat's cost where both ran;
//   beat seconds T = Σ_p N_p s_p  (N_p: the beat's steps in p).
// The uncovered phases are an extrapolation (stated so in the output): they assume the
// larger units cost the same multiple of the small units' cost in every phase.
#include <map>
#include <string>
#include <vector>

namespace fe2 {

inline constexpr int kMinReplayedSteps = 2;

/// One time step: its circulation phase and its cost (seconds).
struct StepCost {
  std::string phase;
  double seconds = 0.0;
};

struct PhaseProjection {
  std::string phase;
  double steps_per_beat = 0.0;  ///< N_p: the full beat's steps in p, per beat
  double beat_cost = 0.0;       ///< c_p: the full beat's cost per step in p
  int replay_steps = 0;         ///< n_p: steps of the replay in p (< kMinReplayedSteps: extrapolated)
  double seconds_per_step = 0.0;  ///< s_p
};

struct BeatProjection {
  std::vector<PhaseProjection> phases;  ///< in the order the beat meets them
  double ratio = 0.0;                   ///< ρ
  double seconds = 0.0;                 ///< T
};

/// Iterations' seconds summed per time step (`iteration_step`: each iteration's step, in
/// run order), each step labelled with its phase from `phase_of_step`. Throws InputError
/// naming `run` when a step has no phase there.
std::vector<StepCost> step_costs(const std::vector<int>& iteration_step, const std::vector<double>& iteration_seconds,
                                 const std::map<int, std::string>& phase_of_step, const std::string& run);

/// `beat`: every step of the full run (phase "inflation" skipped) over `beats` beats;
/// `replay`: the replayed steps with their predicted seconds. Throws InputError when the
/// replay covers no phase of the beat, or `beats` < 1.
BeatProjection project_beat(const std::vector<StepCost>& beat, int beats, const std::vector<StepCost>& replay);

}  // namespace fe2
