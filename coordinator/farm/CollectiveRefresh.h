#pragma once
// The collective refresh decision (`unit.solver.refresh: "collective"`): the
// adaptive policy's ski rental (worker/RefreshPolicy.h) made by the coordinators for all
// units of one point model at once. After every Newton iteration the units' reported
// costs are summed over the model m,
//
//   E_m += Σ_{u ∈ m} max(0, k_u − 1) · (solve + matvec)_u      GMRES work a stale factor cost
//   R_m  = Σ_{u ∈ m} (factor + 9 solves)_u                     what refreshing them all costs
//
// and once E_m ≥ R_m every unit of m refreshes in the next iteration (the job's force
// flag) and E_m starts again from 0. A stall-guard iteration (every unit refactors) resets
// every model.
//
// Why collective: with one unit per worker, a unit that refreshes alone holds every other
// worker for the length of a factorization in that iteration; units that refresh together
// cost the farm one factorization per refresh (docs/solvers.md, "How often to refactor").
//
// The sums are integers (flops rounded), so they are exact whatever the order of the terms:
// the run refreshes in the same iterations on any number of ranks and coordinators.
#include "common/bytes.h"
#include "proto/job.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace fe2 {

class CollectiveRefresh {
 public:
  /// Sums `n` values over every coordinator, in place (an allreduce).
  using SumOverCoordinators = std::function<void(int64_t* values, int n)>;

  /// `model_of_point[k]`: the model of point k; `collective[m]`: whether model m refreshes
  /// collectively.
  CollectiveRefresh(std::vector<int> model_of_point, std::vector<bool> collective);

  /// Some model decides collectively (the same on every coordinator: it is the spec's).
  bool active() const { return active_; }
  /// Whether point k's next job refreshes by collective decision.
  bool due(int point) const { return due_[model_of_point_[point]]; }
  /// Models whose units refresh in the next iteration.
  int due_models() const;

  /// After an iteration whose jobs carried due() (and, if `forced_all`, the stall guard's
  /// refresh of every unit): this coordinator's `results`, summed over the coordinators by
  /// `sum`. Returns the models that become due for the next iteration. @note Collective.
  int account(const std::vector<proto::JobOutput>& results, bool forced_all, const SumOverCoordinators& sum);

  /// The step converged / is retried: keep / go back to the state at the last commit.
  void commit();
  void rollback();

  /// The committed state (a checkpoint is taken between steps).
  void save(ByteWriter& w) const;
  void restore(ByteReader& r);

  /// E_m, R_m of the last account() (for tests and logs).
  int64_t excess(int model) const { return excess_[model]; }
  int64_t refresh_cost(int model) const { return refresh_cost_[model]; }

 private:
  std::vector<int> model_of_point_;
  std::vector<bool> collective_;
  bool active_ = false;
  std::vector<int64_t> excess_, refresh_cost_;
  std::vector<bool> due_;
  std::vector<int64_t> excess_committed_;
  std::vector<bool> due_committed_;
};

}  // namespace fe2
