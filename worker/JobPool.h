#pragma once
// A rank's queue of unit jobs and the threads that drain it (farm.threads_per_rank,
// the paper's "MPI with OpenMP" future work). The rank's main thread keeps all the
// MPI traffic (MPI_THREAD_FUNNELED): it queues the jobs of the batches it pulls and
// collects the results. With one thread it is the plain worker: the main thread runs
// every job itself, in queue order, between two messages. With T > 1, T helper threads
// run the jobs and the main thread only talks (a pull, a batch, a coordinator's answer
// never waits for a job to end); it sleeps while nothing arrives.
//
// Jobs of different units touch disjoint state (UnitStore serializes its bookkeeping),
// so each unit's answer is bit for bit the same whichever thread runs it. A job that
// runs longer than farm.stall_timeout on a helper is a frozen thread: the main thread
// stops the run naming the unit, as it would a silent rank.
#include "proto/job.h"
#include "proto/messages.h"

#include <functional>
#include <memory>
#include <thread>
#include <vector>

namespace fe2 {

class JobPool {
 public:
  using Runner = std::function<proto::JobOutput(const proto::JobInput&)>;
  /// `run` executes one job and may be called from any of the pool's threads at once
  /// (for different units); `threads` run the jobs (1: the caller's own).
  JobPool(Runner run, int threads);
  ~JobPool();
  JobPool(const JobPool&) = delete;
  JobPool& operator=(const JobPool&) = delete;

  int threads() const { return helpers_.empty() ? 1 : static_cast<int>(helpers_.size()); }
  /// `sources` empty queues, one per coordinator pulled from (the start of an
  /// iteration: nothing may be queued, running or unreported).
  void reset(int sources);
  void push(int source, const proto::JobInput& job);
  /// Jobs of `source` queued and not yet started, and started but not finished.
  size_t queued(int source) const;
  int running(int source) const;
  /// Jobs queued, running, or finished and not yet collected, over every source (and 1
  /// for a helper's error not yet rethrown): while it is not 0 the caller must not block
  /// on a message, since a job that ended after its last collect() may hold back the
  /// pull that message waits for.
  size_t pending() const;
  /// Runs one queued job on the calling (main) thread: false if none is queued, or if
  /// helper threads run the jobs.
  bool run_one_here();
  /// Moves the finished results of `source` into `out`; rethrows a fatal error that a
  /// helper's job raised.
  void collect(int source, std::vector<proto::JobOutput>& out);
  /// Waits until a finished result (or a helper's error) is there to collect, or
  /// `seconds` pass.
  void wait_for_a_result(double seconds);
  /// Throws StallError if a helper's job has run longer than `limit` wall seconds; the
  /// message names `stall_timeout` (default: the limit itself) as the liveness limit.
  void check_alive(double limit, double stall_timeout = -1.0) const;

  /// Accumulated over the jobs since reset(): thread CPU and wall seconds of the jobs,
  /// and how many ran (on every thread).
  struct Account {
    double busy_cpu = 0.0, busy_wall = 0.0;
    int jobs = 0;
  };
  Account account() const;

 private:
  struct Shared;
  /// Queues, slots and results live in a block each helper also holds: a helper frozen
  /// in a job (left behind when the run stops) never touches freed memory.
  std::shared_ptr<Shared> shared_;
  std::vector<std::thread> helpers_;
};

}  // namespace fe2
