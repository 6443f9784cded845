#pragma once
// The scheduler's cost model and rebalancer (DESIGN §3), free of MPI so that the run
// and `fe2heart farm-sim` use the very same code.
//
// Predicted cost of a unit's next job: its last measured CPU cost of the same kind
// (refresh or reuse). Moving a unit costs the transfer of its state (latency +
// bytes / bandwidth, paid by both ends; the size the unit last reported) and, unless
// its next job refreshes the factor anyway (as the unit's own policy reports it), one
// factorization at the destination to rebuild it: this is how the plan prefers
// migrating at factor-refresh boundaries.
//
// Plan: two candidates, the better predicted makespan wins (fewer moves on a tie):
//  - local search from the current placement: repeatedly take the most and the least
//    loaded workers and apply the single move (hi -> lo) or swap (hi <-> lo) that
//    lowers the larger of their two loads the most, each unit moving at most once;
//  - sticky LPT: units by decreasing cost, each to the cheaper of its current worker
//    and the least loaded one (moving pays transfer and rebuild).
// Nothing moves while the predicted max/mean load is within 1 + tolerated_imbalance
// (measured costs are noisy; chasing noise only migrates), and a plan is kept only if
// the predicted makespan drops by at least min_gain.
// Deterministic (ties go to the lowest unit id / worker index).
#include "coordinator/farm/FarmOptions.h"

#include <cstdint>
#include <vector>

namespace fe2 {

struct UnitCost {
  double next = 0.0;        ///< predicted CPU seconds of the next job
  double rebuild = 0.0;     ///< extra CPU seconds at a new worker (0 at a refresh boundary)
  double state_bytes = 0.0; ///< serialized state size
};

struct Placement {
  std::vector<int> worker_of_unit;  ///< unit -> worker index (into the worker list)
};

struct Plan {
  std::vector<int> worker_of_unit;
  std::vector<std::pair<int, int>> moves;  ///< (unit, new worker)
  double makespan_before = 0.0;            ///< predicted, no moves
  double makespan_after = 0.0;             ///< predicted, with migration costs
};

/// Per-unit measured costs and the prediction of each unit's next job (the cost model
/// shared by the run and farm-sim).
class CostModel {
 public:
  explicit CostModel(size_t units);
  /// A measured job: CPU seconds of the whole job and of its factorization, if any,
  /// and the unit's serialized state size after it (as the unit reports them).
  void observe(int unit, bool refreshed, double cpu_seconds, double cpu_refresh,
               double state_bytes);
  /// The UnitCost of each unit's next job; `refreshes(u)` says if it will refresh.
  template <class RefreshPredicate>
  std::vector<UnitCost> predict(RefreshPredicate refreshes) const {
    std::vector<UnitCost> c(rec_.size());
    for (size_t u = 0; u < rec_.size(); ++u) c[u] = predict_one(static_cast<int>(u), refreshes(static_cast<int>(u)));
    return c;
  }
  UnitCost predict_one(int unit, bool refreshes) const;
  bool known() const { return known_; }

 private:
  struct Record {
    double reuse = -1.0, refresh = -1.0;  ///< last measured CPU cost of each job kind
    double refresh_part = 0.0;            ///< CPU of the factorization inside a refresh job
    double state_bytes = 0.0;
  };
  std::vector<Record> rec_;
  bool known_ = false;
};

/// Initial placement of `units` on `workers` under a static policy (cost-based starts
/// contiguous, then is rebalanced from measured costs).
Placement static_placement(int units, int workers, FarmOptions::Policy policy);

/// Predicted load per worker of a placement (no migration costs).
std::vector<double> worker_loads(const std::vector<UnitCost>& cost, const std::vector<int>& worker_of_unit,
                                 int workers);

/// Seconds to move `bytes` between two ranks under the network model.
double transfer_seconds(double bytes, const FarmOptions& o);

/// Loads after moving every unit from `from` to `to` (migrations included).
std::vector<double> predicted_loads(const std::vector<UnitCost>& cost, const std::vector<int>& from,
                                    const std::vector<int>& to, int workers, const FarmOptions& o);

/// Cost-based plan from the current placement.
Plan plan_rebalance(const std::vector<UnitCost>& cost, const std::vector<int>& worker_of_unit,
                    int workers, const FarmOptions& o);

}  // namespace fe2
