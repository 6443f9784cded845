#pragma once
// How a run is spread over MPI ranks (spec section "farm"; DESIGN §3).
#include "common/spec/SpecNode.h"
#include "worker/point_models.h"

#include <string>
#include <vector>

namespace fe2 {

struct FarmOptions {
  int coordinators = 1;             ///< first n_c ranks own the macro problem
  bool coordinators_work = true;    ///< coordinator ranks also hold units (paper ranks 0–63)
  enum class Policy { round_robin, contiguous, cost_based } policy = Policy::cost_based;
  enum class When { iteration, step } rebalance_at = When::iteration;
  int batch = 4;                    ///< jobs per pull (per thread)
  /// Threads that run a rank's unit jobs (worker/JobPool.h): 1, the main thread between
  /// its messages; more, that many helpers while the main thread only talks MPI. One copy
  /// of the mesh, spec and models per rank, not per core; answers bit for bit as one's.
  int threads_per_rank = 1;
  double min_gain = 0.03;           ///< rebalance only if the predicted makespan drops this much
  double tolerated_imbalance = 0.05;///< ... and only if max/mean predicted load exceeds 1 + this
  double latency = 2e-6;            ///< network model: seconds per message
  double bandwidth = 5e9;           ///< network model: bytes per second (paper: 5 GB/s links)
  /// Liveness limit: a rank that waits this long (wall seconds) for a message it needs
  /// (a result, a batch, a control message, a collective) aborts the job naming whom it
  /// waited for. A healthy wait can span one whole Newton iteration (a worker idle until
  /// the next command: the other workers' jobs, the macro solve) and an output write.
  double stall_timeout = 600.0;
  /// Bytes of sparse factors a worker rank may hold (0: unlimited). Past it the rank drops
  /// the least recently used factors of other units; a unit rebuilds its factor on its
  /// next job (worker/UnitStore.h). As written in the spec, for messages ("2G").
  double factor_memory_budget = 0.0;
  std::string factor_memory_budget_text;
  /// Where macro-law points are evaluated: `local`, by the coordinator that owns their
  /// element (microseconds of work, no message, never placed nor moved), or `farm`, as
  /// jobs on the workers like FE² units (for laws costly enough to spread, e.g. a cell
  /// ODE at many points with few coordinators).
  enum class MacroLawPoints { local, farm } macro_law_points = MacroLawPoints::local;

  /// Reads the spec section "farm" (every key optional): the run and `farm-sim`
  /// (which replays a run from its spec.json) share these declarations.
  static FarmOptions from_spec(SpecNode farm);
  /// A budget below one unit's factor (the largest of the FE² models that `model_of_point`
  /// uses, by the memory estimate) is an InputError naming the key, the value and the
  /// smallest useful budget.
  void check_factor_budget(const std::vector<PointModelSpec>& models,
                           const std::vector<int>& model_of_point) const;

  /// The placement policies by their spec names ("round_robin", "contiguous",
  /// "cost_based"), one table for the spec, the command line and the reports.
  static const std::vector<std::string>& policy_names();
  static Policy policy_of(const std::string& name);  ///< InputError on an unknown name
  static const char* name_of(Policy p);
};

}  // namespace fe2
