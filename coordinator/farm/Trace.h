#pragma once
// Load-balance traces, JSON Lines in the output folder (DESIGN §3, paper §IV-C):
//   trace_iterations.jsonl  per (step, iteration): entire, micro_lc, macro (= assemble
//                           + solve + the rest), comm1, comm2 (seconds, coordinator 0),
//                           bytes, migrations, jobs (run by workers), local_jobs and
//                           local_cpu (points evaluated by their coordinators),
//                           macro_law_jobs_sent (macro-law points that travelled)
//   trace_workers.jsonl     per (step, iteration, worker): units, jobs, busy (CPU summed
//                           over the rank's threads, wall as their mean), idle, wait,
//                           threads, t_begin/t_end, migrations, bytes
//   trace_units.jsonl       per (step, iteration, unit): worker, cost, refresh_cost,
//                           kind, GMRES, state_bytes, factor_evictions (other units'
//                           factors its worker dropped for it), factor_rebuilt
// Written by rank 0 only; every line is flushed, so a stopped run keeps its trace.
#include "proto/job.h"
#include "proto/messages.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

namespace fe2 {

struct IterationTiming {
  int step = 0, iteration = 0;
  double entire = 0.0;    ///< whole Newton iteration, (a)–(j)
  double micro_lc = 0.0;  ///< dispatch to last result: micro work + load imbalance + comm
  double macro = 0.0;     ///< (g) assembly, (i) convergence test and (h) solve
  double assemble = 0.0;  ///< (g) the macro terms
  double assemble_fluid = 0.0;  ///< of which the blood's (Navier–Stokes, its boundaries, the mesh motion)
  double solve = 0.0;     ///< (h) MUMPS
  /// The macro phase's thread CPU seconds on the busiest coordinator (the critical path
  /// when coordinators share cores) and summed over the coordinator group.
  double macro_cpu_max = 0.0, macro_cpu_sum = 0.0;
  int coordinators = 1;
  int macro_factorized = 0;  ///< the solve factored S̄ (0: kept factor, or no solve)
  int macro_gmres = 0;       ///< GMRES iterations of a solve with the kept factor
  double comm1 = 0.0, comm2 = 0.0;
  long long bytes = 0;
  int migrations = 0;
  int jobs = 0;                       ///< jobs run by workers (they travelled)
  long long local_jobs = 0;           ///< points evaluated by their coordinator (LocalPoints)
  double local_cpu = 0.0;             ///< their CPU seconds
  long long macro_law_jobs_sent = 0;  ///< jobs of macro-law points sent through the farm
  /// Units whose refresh the rebalancer's plan did not foresee (or foresaw wrongly); 0
  /// when no plan was made. A miss means the plan weighed that unit's job at the wrong
  /// kind of cost.
  int refresh_forecast_misses = 0;
};

/// Bytes written to each trace file so far (checkpoints; a restart continues there).
struct TraceOffsets {
  uint64_t iterations = 0, workers = 0, units = 0;
};

class Trace {
 public:
  /// New trace files in `dir`; with `resume`, the files there are cut back to those
  /// offsets (dropping what a killed run wrote after its checkpoint) and appended to.
  explicit Trace(const std::string& dir, const TraceOffsets* resume = nullptr);
  /// Flushes, and says how far each file is.
  TraceOffsets offsets();
  void iteration(const IterationTiming& t);
  void worker(const proto::WorkerStats& s, double micro_phase_seconds, double t0);
  void unit(int step, int iteration, int worker, const proto::JobCost& c);

 private:
  std::string dir_;
  std::ofstream iterations_, workers_, units_;
};

}  // namespace fe2
