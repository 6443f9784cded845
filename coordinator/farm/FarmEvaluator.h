#pragma once
// The point evaluator of a coordinator rank in the MPI task farm (DESIGN §3). In one
// evaluate() call — one Newton iteration's micro phase, paper Fig. 5 (a)–(f):
//   rebalance   cost-based policy: coordinator 0 plans from measured per-unit CPU
//               costs (Rebalancer), every rank learns the moves, states migrate
//   dispatch    coordinator 0 tells pure workers to pull; each coordinator queues the
//               jobs of its own units per worker (JobServer), except those of its
//               local points (macro-law points, LocalPoints), which it evaluates itself
//               between serving pulls
//   serve/work  serve pulls and, if this rank also works, run its own units' jobs
//               (PullClient), until every result of this coordinator's units is in
//   account     worker stats and per-unit costs (proto::CostReport) reach coordinator 0
//               (traces, cost model)
// @note Every member function is collective on the coordinator group.
#include "coordinator/farm/FarmLayout.h"
#include "coordinator/farm/JobServer.h"
#include "coordinator/LocalPoints.h"
#include "coordinator/farm/Rebalancer.h"
#include "coordinator/PointEvaluator.h"
#include "coordinator/farm/Trace.h"
#include "worker/PullClient.h"

#include <memory>
#include <optional>

namespace fe2 {

class FarmEvaluator final : public PointEvaluator {
 public:
  /// `store` (null if coordinators do not work), `trace` (rank 0 only) are lent.
  FarmEvaluator(proto::Transport& transport, const proto::Group& coordinators,
                const FarmLayout& layout, const RunSpec& spec, UnitStore* store, Trace* trace);

  void evaluate(const std::vector<proto::JobInput>& jobs,
                std::vector<proto::JobOutput>& out) override;
  void commit_step() override;
  void rollback_step() override;
  /// Coordinator 0 asks each unit's holder (itself, another coordinator that works, or a
  /// pure worker by a Control 'fields') to send it the unit's fields.
  std::vector<proto::UnitFields> unit_fields(const std::vector<int>& units, int step) override;
  /// Each holder (a pure worker by a Control 'checkpoint') sends rank 0 a copy of each
  /// of its units' states; rank 0 hands them to `sink` as they arrive.
  void save_states(const StateSink& sink, bool with_factors) override;
  /// Rank 0 sends each unit's state to its holder under the current placement (pure
  /// workers by a Control 'restore'), in `points` order.
  void restore_states(const std::vector<int>& points, const StateSource& read) override;
  /// Rank 0: tells every pure worker to stop.
  void shutdown();

  /// Communication figures of the last evaluate (on rank 0).
  const IterationTiming& last() const { return last_; }
  /// Current placement: unit -> world rank.
  const std::vector<int>& placement() const { return placement_; }

 private:
  void send_to_pure_workers(const proto::Control& c);
  /// `forced_model[m]`: the jobs of model m carry the force flag in this iteration (a
  /// collective refresh, or the stall guard's for every model), so they refresh whatever
  /// the units' own policies said.
  void rebalance(int step, int iteration, const std::vector<int64_t>& forced_model);
  bool next_job_refreshes(int unit, int step, int iteration) const;
  /// farm.policy cost_based: rebalances when costs are known and it is due (every
  /// iteration, or at a new step). @note Collective on the coordinators.
  void rebalance_if_due(const std::vector<proto::JobInput>& jobs, bool new_step);
  /// (a) starts the pure workers and queues this coordinator's jobs; `farm_index[i]` is
  /// the position in `jobs` of the i-th job sent through the farm. Returns the start time.
  double dispatch(const std::vector<proto::JobInput>& jobs, std::vector<size_t>& farm_index);
  /// (b)–(f) serves pulls and works until this coordinator's results are in.
  void serve_until_done();
  /// The iteration's accounts for the traces and the cost model, on coordinator 0:
  /// every worker rank's stats, the local points' work, each farm job's cost.
  void gather_worker_stats(int step, int iteration, double micro_phase);
  void sum_local_points();
  void gather_costs(const std::vector<proto::JobOutput>& out, int step, int iteration);

  proto::Transport& transport_;
  const proto::Group& coords_;
  const FarmLayout& layout_;
  const RunSpec& spec_;
  UnitStore* store_;
  Trace* trace_;
  JobServer server_;
  std::optional<PullClient> client_;
  std::vector<int> placement_;
  std::vector<int> farm_units_;        ///< units that travel: the rebalancer's problem
  std::vector<char> macro_law_;        ///< per unit: a macro-law point (trace counter)
  std::vector<int> model_of_point_;    ///< per unit: its point model
  int num_models_ = 0;
  std::vector<int8_t> planned_refresh_;  ///< rank 0: the last plan's forecast per unit, −1 unplanned
  std::optional<LocalPoints> local_;   ///< points this coordinator evaluates in place
  std::optional<CostModel> costs_;  ///< rank 0
  std::vector<proto::JobCost> last_cost_;      ///< rank 0: each unit's last job
  std::pair<int, int> last_costs_at_{-2, 0};   ///< (step, iteration) of those jobs
  bool have_costs_ = false;
  int last_step_ = -1;
  IterationTiming last_;
  double t0_;
};

}  // namespace fe2
