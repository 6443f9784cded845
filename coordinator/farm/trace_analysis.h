#pragma once
// Reading a run's traces back (trace_*.jsonl) and the figures users quote from them:
// the paper's Table I ratios, load imbalance, micro-phase efficiency, bytes per
// unit-iteration, migrations. Shared by `fe2heart trace summary` and `farm-sim`.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace fe2 {

struct TraceData {
  std::vector<nlohmann::json> iterations, workers, units;
};

/// Throws InputError naming the file if the folder has no (or malformed) traces.
TraceData read_traces(const std::string& dir);

struct TraceSummary {
  int iterations = 0, workers = 0, units = 0;
  double entire = 0, micro_lc = 0, macro = 0, comm1 = 0, comm2 = 0;  ///< totals, seconds
  double micro_over_entire = 0, macro_over_entire = 0;  ///< paper Table I
  double imbalance_mean = 0, imbalance_max = 0;         ///< max/mean worker busy per iteration
  double imbalance_after_first_rebalance = 0;           ///< mean over iterations after it
  double imbalance_last = 0;
  double micro_efficiency = 0;  ///< Σ busy / (workers × Σ micro phase)
  double bytes_per_unit_iteration = 0;
  int migrations = 0;
  int first_rebalance_iteration = -1;  ///< index into iterations, -1 if none
  std::vector<double> imbalance;       ///< per iteration
};

TraceSummary summarize(const TraceData& t);
nlohmann::json to_json(const TraceSummary& s);

}  // namespace fe2
