#pragma once
// `fe2heart farm-sim`: replay a run's measured per-unit costs on W simulated workers
// with the same placement, cost model and rebalancer code as the run, under a stated
// network model, and predict the micro-phase (Micro+L+C) and Entire times.
//
// Model, per recorded Newton iteration i and simulated unit v (of U):
//   cost(v) = measured CPU cost of unit v mod U_measured in iteration i (so the run's
//             spread of costs, refresh spikes included, is kept);
//   worker load = Σ cost of its units + per batch of `batch` jobs two messages
//             (latency each) + job and result bytes / bandwidth, + migrations
//             (state bytes / bandwidth + latency at both ends, and a factorization at
//             the destination unless the unit's job refreshes anyway);
//   rebalancing = the run's: cost-based plans before every iteration, or only before a
//             new step's first (farm.rebalance_at), from the same cost model;
//   Micro+L+C(i) = max load;  Entire(i) = Micro+L+C(i) + macro(i) × macro_scale,
//   macro(i) the measured Macro time of iteration i (coordinators do not scale with W).
#include "coordinator/farm/FarmOptions.h"
#include "coordinator/farm/trace_analysis.h"

#include <vector>

namespace fe2 {

struct FarmSimInput {
  std::vector<std::vector<double>> cost;          ///< [iteration][unit] CPU seconds
  std::vector<std::vector<char>> refreshed;       ///< [iteration][unit]
  std::vector<std::vector<double>> refresh_part;  ///< [iteration][unit] factorization CPU
  std::vector<std::vector<int>> gmres;            ///< [iteration][unit] GMRES iterations of the job
  std::vector<double> macro;                      ///< [iteration] seconds
  std::vector<MacroSolveKind> macro_kind;         ///< [iteration]
  std::vector<int> step;                          ///< [iteration] time step (empty: each new)
  std::vector<double> state_bytes;                ///< [unit]
};

/// From a run's traces; `state_bytes` per measured unit is the largest its jobs
/// reported (`default_state_bytes` for traces that do not record it).
FarmSimInput farm_sim_input(const TraceData& t, double default_state_bytes = 1e6);

/// Replaces each iteration's macro time by `cost`'s prediction for its kind (a macro
/// measured in another run).
void replace_macro(FarmSimInput& in, const MacroCost& cost);

struct FarmSimResult {
  double micro = 0.0;       ///< Σ predicted Micro+L+C
  double entire = 0.0;      ///< Σ predicted Entire
  double work = 0.0;        ///< Σ unit CPU seconds
  int migrations = 0;
  std::vector<double> makespan;  ///< per iteration
};

FarmSimResult simulate_farm(const FarmSimInput& in, int workers, long long units,
                            const FarmOptions& o, double macro_scale = 1.0);

}  // namespace fe2
