#pragma once
// How a run is spread over MPI ranks (spec section "farm"; DESIGN §3).
#include "common/spec/SpecNode.h"

#include <string>
#include <vector>

namespace fe2 {

struct FarmOptions {
  int coordinators = 1;             ///< first n_c ranks own the macro problem
  bool coordinators_work = true;    ///< coordinator ranks also hold units (paper ranks 0–63)
  enum class Policy { round_robin, contiguous, cost_based } policy = Policy::cost_based;
  enum class When { iteration, step } rebalance_at = When::iteration;
  int batch = 4;                    ///< jobs per pull
  double min_gain = 0.03;           ///< rebalance only if the predicted makespan drops this much
  double tolerated_imbalance = 0.05;///< ... and only if max/mean predicted load exceeds 1 + this
  double latency = 2e-6;            ///< network model: seconds per message
  double bandwidth = 5e9;           ///< network model: bytes per second (paper: 5 GB/s links)
  /// Liveness limit: a rank that waits this long (wall seconds) for a message it needs
  /// (a result, a batch, a control message, a collective) aborts the job naming whom it
  /// waited for. A healthy wait can span one whole Newton iteration (a worker idle until
  /// the next command: the other workers' jobs, the macro solve) and an output write.
  double stall_timeout = 600.0;

  /// Reads the spec section "farm" (every key optional): the run and `farm-sim`
  /// (which replays a run from its spec.json) share these declarations.
  static FarmOptions from_spec(SpecNode farm);

  /// The placement policies by their spec names ("round_robin", "contiguous",
  /// "cost_based"), one table for the spec, the command line and the reports.
  static const std::vector<std::string>& policy_names();
  static Policy policy_of(const std::string& name);  ///< InputError on an unknown name
  static const char* name_of(Policy p);
};

}  // namespace fe2
