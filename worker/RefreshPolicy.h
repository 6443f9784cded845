#pragma once
// When a micro unit refactors K and recomputes χ (paper Fig. 6), as one small value
// type: MicroUnit asks it before every job and tells it what each job cost; the task
// farm learns its answers from the unit's cost report (proto::UnitCost), so the unit
// and the scheduler cannot disagree about which job refreshes.
//
//   every_iteration  every job refreshes
//   fixed            iteration 1 of every N_t-th step (the paper's choice)
//   adaptive         ski rental on the libraries' own flop counts: refresh once the
//                    GMRES work beyond one iteration per job since the last refresh,
//                      Σ_jobs max(0, k_j − 1) · (solve + matvec),
//                    has cost as much as the refresh it avoids, factor + 9 solves (χ).
//                    Flop counts, not seconds: the same decision on every rank and run.
//   collective       the same rental, decided by the coordinators for all units of a model
//                    at once (coordinator/farm/CollectiveRefresh.h): the unit never refreshes on
//                    its own and reports each job's excess and its refresh cost instead. With
//                    one unit per worker a unit refreshing alone stalls every other worker
//                    for a factorization; refreshing together costs the farm one.
//
// Within one job the rental policies rent too: Step 1 GMRES on a stale factor gives up
// once its iterations have cost as much as a refresh (stale_gmres_budget), and the unit
// refreshes and solves again. A job thus costs at most about two refreshes, where a
// factor far from the current K could spin to gmres_max_iterations first (measured on
// 3k-DOF binary16 units in the contraction: 500 iterations, 7 refreshes' worth, on the
// farm's critical path).
//
// A forced refresh (job flag) and a unit without a factor refresh regardless; that is
// MicroUnit's business, not the policy's.
#include "common/bytes.h"
#include "worker/MicroModel.h"

namespace fe2 {

class RefreshPolicy {
 public:
  using Kind = MicroSolverOptions::Refresh;

  /// `matvec_flops`: one product with K (2 nnz), part of each GMRES iteration.
  /// `solve_flop_cost`: a flop of a solve in flops of a factorization (the budget within
  /// a job; MicroSolverOptions::solve_flop_cost).
  RefreshPolicy(Kind kind, int N_t, double matvec_flops, double solve_flop_cost = 1.0);

  /// Whether a job at (step, iteration) refreshes under this policy, now.
  bool due(int step, int iteration) const;

  /// A refresh happened: its factor cost `factor_flops`, one solve `solve_flops`.
  void refreshed(double factor_flops, double solve_flops);
  /// A job reused the factor and its Step 1 GMRES took `gmres_iterations`.
  void reused(int gmres_iterations);

  Kind kind() const { return kind_; }
  /// Flops of the GMRES work beyond one iteration in a job that took `gmres_iterations`.
  double excess_flops(int gmres_iterations) const {
    return (gmres_iterations > 1 ? gmres_iterations - 1 : 0) * iteration_flops();
  }
  /// Adaptive: GMRES iterations beyond one per job since the last refresh.
  double excess_iterations() const { return excess_iterations_; }
  /// The Step 1 GMRES iterations a job may spend on a stale factor before it refreshes:
  /// refresh_flops / (solve_flop_cost · iteration_flops) for the rental policies (at least
  /// kMinStaleGmresBudget, at most `max_iterations`); `max_iterations` for the others
  /// (fixed keeps the paper's factor until GMRES fails) and before the first refresh.
  int stale_gmres_budget(int max_iterations) const;
  /// A floor for units whose refresh is cheap (a few hundred DOF): the budget must not
  /// turn every job with a dozen iterations into a refresh.
  static constexpr int kMinStaleGmresBudget = 20;

  /// Adaptive cost model (flops): one more GMRES iteration, and one refresh.
  double iteration_flops() const { return solve_flops_ + matvec_flops_; }
  double refresh_flops() const { return factor_flops_ + 9.0 * solve_flops_; }

  /// The mutable part (counters and flop counts) to bytes and back; kind, N_t and the
  /// matvec cost come from the unit model.
  void write(ByteWriter& w) const;
  void read(ByteReader& r);

 private:
  Kind kind_;
  int N_t_;
  double matvec_flops_;
  double solve_flop_cost_;
  double excess_iterations_ = 0.0;
  double factor_flops_ = 0.0;  ///< of the last refresh
  double solve_flops_ = 0.0;
};

}  // namespace fe2
