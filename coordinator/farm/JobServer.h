#pragma once
// A coordinator's job queue for one Newton iteration: the jobs of its own units, one
// queue per worker rank (a unit runs where its state lives). Each Pull from a worker
// brings the results it has and asks for more (workers ask ahead, before their queue
// runs dry); the reply is up to `max_jobs` more, an empty batch once the queue is
// drained but results are still out, or "done" once every result is in.
#include "proto/Transport.h"

#include <deque>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace fe2 {

class JobServer {
 public:
  explicit JobServer(proto::Transport& transport) : transport_(transport) {}

  /// `worker_of_job[k]`: world rank holding jobs[k].unit. Sends every worker its first
  /// batch of up to `first_batch` jobs unasked, so no worker waits for a first reply.
  void begin(const std::vector<proto::JobInput>& jobs, const std::vector<int>& worker_of_job,
             int first_batch);
  /// Serves one waiting Pull (or waits for one if `block`). True once every worker with
  /// jobs here has been told "done" (so every result is in).
  bool poll(bool block);
  bool finished() const { return open_ == 0; }
  /// Pulls served so far (tells a polling loop whether anything happened).
  long long served() const { return served_; }
  /// Results in job order.
  const std::vector<proto::JobOutput>& results() const { return results_; }
  /// The workers whose results are still out and what they hold (for a stall report).
  std::string describe_outstanding() const;
  double comm1_seconds() const { return comm1_; }  ///< packing and posting job batches
  double comm2_seconds() const { return comm2_; }  ///< receiving and unpacking results

 private:
  struct Queue {
    std::deque<int> jobs;  ///< indices into jobs_
    int assigned = 0;      ///< jobs of this worker in this iteration
    int received = 0;      ///< results back so far
    bool done = false;
  };
  /// Sends `worker` up to `n` more jobs, or an empty / done batch.
  void send_batch(int worker, Queue& queue, int n);
  proto::Transport& transport_;
  std::vector<proto::JobInput> jobs_;
  std::vector<proto::JobOutput> results_;
  std::vector<int> worker_of_job_;
  std::unordered_map<int, int> job_of_unit_;
  std::map<int, Queue> queues_;
  int open_ = 0;
  long long served_ = 0;
  double comm1_ = 0.0, comm2_ = 0.0;
};

}  // namespace fe2
