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

/// What a Newton iteration's macro solve was: a factorization of S̄, a solve with the kept
/// factor (GMRES), or none (the iteration that found the residual converged). `unknown`
/// for traces written before the kind was recorded.
enum class MacroSolveKind { none, kept, factorizing, unknown };
MacroSolveKind macro_solve_kind(const nlohmann::json& iteration);

/// The macro phase per Newton iteration by kind (medians over the trace's iterations).
/// `cpu` is the thread CPU of the busiest coordinator (the critical path when
/// coordinators share cores), or the wall time for traces that do not record it.
struct MacroCost {
  struct Kind {
    int count = 0;
    double wall = 0, cpu = 0, assemble = 0, solve = 0, gmres = 0;  ///< medians
  };
  Kind factorizing, kept, none;
  int coordinators = 1;
  double cpu_critical = 0;  ///< Σ over iterations of the busiest coordinator's macro CPU
  double cpu_total = 0;     ///< Σ over iterations and coordinators
  bool cpu_recorded = false;
  /// Σ over iterations of the wall seconds coordinator 0 spent assembling the blood's
  /// terms (its share of Macro: the fluid's), and of the whole macro phase there.
  double fluid_assembly = 0, macro_wall = 0;
  /// The cost this trace predicts for an iteration of kind `k` (CPU median; a kind the
  /// trace lacks, or `unknown`, takes the median over its solving iterations).
  double predict(MacroSolveKind k) const;
  double solving_median = 0;  ///< CPU median over the iterations that solved
};
MacroCost macro_cost(const TraceData& t);

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
  MacroCost macro_cost;
};

TraceSummary summarize(const TraceData& t);
nlohmann::json to_json(const MacroCost& c);
nlohmann::json to_json(const TraceSummary& s);

}  // namespace fe2
