#pragma once
// The worker side of one Newton iteration (paper Fig. 5 (a)–(f), DESIGN §3): pull
// batches of jobs for the units living here from each coordinator that owns some of
// them, run them, and send results back with the next pull, until every coordinator
// says it is done. A pull goes out while half a batch is still queued, so the next
// batch arrives while this rank computes (a coordinator that also works answers only
// between its own jobs). Non-blocking steps, so a rank that also coordinates
// can serve its own queue in between.
//
// With farm.threads_per_rank = T > 1, T helper threads of a JobPool run the jobs while
// this (main) thread alone talks MPI; a pull then asks for T batches.
#include "proto/Transport.h"
#include "worker/JobPool.h"
#include "worker/UnitStore.h"

#include <vector>

namespace fe2 {

class PullClient {
 public:
  /// `threads` (≥ 1) run this rank's jobs: this thread, or that many helpers.
  PullClient(proto::Transport& transport, UnitStore& store, int batch, int threads = 1);

  /// Starts an iteration: pull from these coordinator ranks.
  void begin(const std::vector<int>& coordinators, int step, int iteration);
  /// Makes progress (one job, or one message); `block` waits for a batch when there is
  /// nothing else to do. Returns true once every coordinator is done.
  bool poll(bool block);
  bool finished() const;
  /// Jobs run, batches taken and pulls sent so far (tells a polling loop whether
  /// anything happened).
  long long progress() const { return progress_; }
  /// Sleeps until one of the helper threads' jobs finishes, or `seconds` pass: the nap of
  /// a polling loop that has nothing else to do. Returns false at once when no helper
  /// has a job (the caller then naps its own way).
  bool wait_for_helpers(double seconds);
  /// Throws StallError naming a helper thread whose job has run longer than `limit`
  /// (JobPool::check_alive): a coordinator that also works asks this before it blames
  /// a silent rank, since that rank may be itself.
  void check_helpers(double limit) const;
  /// This iteration's account (valid after finished()).
  proto::WorkerStats stats() const;
  void count_migrations(int in, int out) { migrations_in_ += in, migrations_out_ += out; }

 private:
  void close_stats();
  struct Source {
    int rank = -1;
    bool outstanding = false;
    bool exhausted = false;  ///< the coordinator has no more jobs; results still to send
    bool done = false;
    std::vector<proto::JobOutput> results;  ///< finished, to go with the next pull
  };
  proto::Transport& transport_;
  UnitStore& store_;
  int batch_;  ///< jobs per pull: farm.batch per thread
  JobPool pool_;
  std::vector<Source> sources_;
  proto::WorkerStats stats_;
  int migrations_in_ = 0, migrations_out_ = 0;
  long long progress_ = 0;
  int64_t sent0_ = 0, received0_ = 0;
};

/// Executes the moves of a rebalance that involve this rank: sends out the units it
/// gives away and receives those it gets (same move order on both ends). Returns
/// (received, sent).
std::pair<int, int> migrate(proto::Transport& transport, UnitStore& store,
                            const std::vector<proto::Move>& moves);

}  // namespace fe2
