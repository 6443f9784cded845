#include "coordinator/farm/JobServer.h"

#include "common/cpu_timer.h"

#include <algorithm>

namespace fe2 {

void JobServer::begin(const std::vector<proto::JobInput>& jobs, const std::vector<int>& worker_of_job,
                      int first_batch) {
  jobs_ = jobs;
  worker_of_job_ = worker_of_job;
  results_.assign(jobs.size(), proto::JobOutput{});
  job_of_unit_.clear();
  queues_.clear();
  for (size_t k = 0; k < jobs.size(); ++k) {
    job_of_unit_[jobs[k].unit] = static_cast<int>(k);
    Queue& q = queues_[worker_of_job[k]];
    q.jobs.push_back(static_cast<int>(k));
    ++q.assigned;
  }
  open_ = static_cast<int>(queues_.size());
  comm1_ = comm2_ = 0.0;
  const double t0 = wall_seconds();
  for (auto& [worker, queue] : queues_) send_batch(worker, queue, first_batch);
  comm1_ += wall_seconds() - t0;
}

void JobServer::send_batch(int worker, Queue& queue, int n) {
  proto::Batch batch;
  while (!queue.jobs.empty() && static_cast<int>(batch.jobs.size()) < n) {
    batch.jobs.push_back(jobs_[queue.jobs.front()]);
    queue.jobs.pop_front();
  }
  if (batch.jobs.empty() && queue.received == queue.assigned) {
    batch.done = true;
    queue.done = true;
    --open_;
  }
  Bytes out;
  batch.pack(out);
  transport_.send(worker, proto::Type::batch, std::move(out));
}

bool JobServer::poll(bool block) {
  if (finished()) return true;
  Bytes in;
  int from = -1;
  double t0 = wall_seconds();
  if (!transport_.try_recv(proto::Type::pull, in, &from)) {
    if (!block) return false;
    try {
      in = transport_.recv(proto::Type::pull, MPI_ANY_SOURCE, &from);
    } catch (const StallError& e) {
      throw StallError(fmt::format("{}; {}", e.what(), describe_outstanding()));
    }
    t0 = wall_seconds();  // waiting is not communication cost
  }
  const proto::Pull pull = proto::Pull::unpack(in);
  ++served_;
  auto q = queues_.find(from);
  FE2_CHECK(q != queues_.end() && !q->second.done, "pull from rank {} which has no jobs here", from);
  for (const auto& r : pull.results) {
    auto it = job_of_unit_.find(r.unit);
    FE2_CHECK(it != job_of_unit_.end(), "result for unit {} which is not in this queue", r.unit);
    results_[it->second] = r;
    ++q->second.received;
  }
  const double t1 = wall_seconds();
  comm2_ += t1 - t0;

  send_batch(from, q->second, pull.max_jobs);
  comm1_ += wall_seconds() - t1;
  return finished();
}

std::string JobServer::describe_outstanding() const {
  std::string out;
  for (const auto& [worker, q] : queues_) {
    if (q.done) continue;
    std::vector<int> running;  // handed out, result not back
    for (size_t k = 0; k < jobs_.size(); ++k)
      if (worker_of_job_[k] == worker && results_[k].unit < 0 &&
          std::find(q.jobs.begin(), q.jobs.end(), static_cast<int>(k)) == q.jobs.end())
        running.push_back(jobs_[k].unit);
    const size_t unanswered = running.size();
    if (running.size() > 8) running.resize(8);
    out += fmt::format("{}rank {} is silent: it holds {} unanswered job(s) of step {} iteration "
                       "{} (units {}{})",
                       out.empty() ? "" : "; ", worker, unanswered, jobs_.front().step,
                       jobs_.front().iteration, fmt::join(running, ", "),
                       unanswered > 8 ? ", ..." : "");
  }
  return out.empty() ? "no worker owes this coordinator a result" : out;
}

}  // namespace fe2
