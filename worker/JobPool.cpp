#include "worker/JobPool.h"

#include "common/cpu_timer.h"
#include "common/error.h"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>

namespace fe2 {

struct JobPool::Shared {
  struct Queue {
    std::deque<proto::JobInput> waiting;
    std::vector<proto::JobOutput> finished;
    int running = 0;
  };
  struct Slot {  ///< what a helper runs now
    int unit = -1, step = 0, iteration = 0;
    double since = 0.0;  ///< wall seconds when its job started; 0 while idle
  };
  Runner run;
  std::mutex mutex;
  std::condition_variable work;      ///< a job was queued, or the pool stops
  std::condition_variable finished;  ///< a job finished
  std::vector<Queue> queues;
  std::vector<Slot> slots;           ///< one per helper
  Account account;
  std::exception_ptr error;          ///< the first fatal error of a helper's job
  bool stop = false;

  /// The next queued job, sources in order (the lock held); false if none.
  bool take(int& source, proto::JobInput& job) {
    for (size_t s = 0; s < queues.size(); ++s)
      if (!queues[s].waiting.empty()) {
        source = static_cast<int>(s);
        job = queues[s].waiting.front();
        queues[s].waiting.pop_front();
        ++queues[s].running;
        return true;
      }
    return false;
  }

  /// Runs a taken job outside the lock, then files its result (or its fatal error).
  void execute(int source, const proto::JobInput& job) {
    const double w0 = wall_seconds(), c0 = thread_cpu_seconds();
    proto::JobOutput out;
    std::exception_ptr failure;
    try {
      out = run(job);
    } catch (...) {
      failure = std::current_exception();
    }
    const double cpu = thread_cpu_seconds() - c0, wall = wall_seconds() - w0;
    {
      std::lock_guard<std::mutex> lock(mutex);
      Queue& q = queues[source];
      --q.running;
      if (failure) {
        if (!error) error = failure;
      } else {
        q.finished.push_back(std::move(out));
        account.busy_cpu += cpu;
        account.busy_wall += wall;
        ++account.jobs;
      }
    }
    finished.notify_all();
  }

  void helper_loop(size_t slot) {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      int source = -1;
      proto::JobInput job;
      work.wait(lock, [&] { return stop || take(source, job); });
      if (source < 0) return;  // stopping, nothing taken
      slots[slot] = Slot{job.unit, job.step, job.iteration, wall_seconds()};
      lock.unlock();
      execute(source, job);
      lock.lock();
      slots[slot].since = 0.0;
    }
  }
};

JobPool::JobPool(Runner run, int threads) : shared_(std::make_shared<Shared>()) {
  FE2_CHECK(threads >= 1, "a job pool of {} threads", threads);
  const int helpers = threads > 1 ? threads : 0;
  shared_->run = std::move(run);
  shared_->slots.resize(helpers);
  for (int k = 0; k < helpers; ++k)
    helpers_.emplace_back([s = shared_, k] { s->helper_loop(static_cast<size_t>(k)); });
}

JobPool::~JobPool() {
  std::vector<bool> busy(helpers_.size());
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->stop = true;
    for (size_t k = 0; k < helpers_.size(); ++k) busy[k] = shared_->slots[k].since > 0.0;
  }
  shared_->work.notify_all();
  // A helper still in a job is only there when the run is stopping on an error (a
  // frozen thread, or another rank's failure): it is left to the process's end, holding
  // its own reference to the shared block; an idle one finishes now.
  for (size_t k = 0; k < helpers_.size(); ++k)
    if (busy[k])
      helpers_[k].detach();
    else
      helpers_[k].join();
}

void JobPool::reset(int sources) {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  for (const auto& q : shared_->queues)
    FE2_CHECK(q.waiting.empty() && q.running == 0 && q.finished.empty(),
              "job pool reset with jobs queued, running or unreported");
  shared_->queues.assign(sources, Shared::Queue{});
  shared_->account = Account{};
}

void JobPool::push(int source, const proto::JobInput& job) {
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->queues.at(source).waiting.push_back(job);
  }
  shared_->work.notify_one();
}

size_t JobPool::queued(int source) const {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  return shared_->queues.at(source).waiting.size();
}

int JobPool::running(int source) const {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  return shared_->queues.at(source).running;
}

size_t JobPool::pending() const {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  size_t n = 0;
  for (const auto& q : shared_->queues)
    n += q.waiting.size() + static_cast<size_t>(q.running) + q.finished.size();
  return n + (shared_->error ? 1 : 0);
}

bool JobPool::run_one_here() {
  if (!helpers_.empty()) return false;
  int source = -1;
  proto::JobInput job;
  {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    if (!shared_->take(source, job)) return false;
  }
  shared_->execute(source, job);
  return true;
}

void JobPool::collect(int source, std::vector<proto::JobOutput>& out) {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  if (shared_->error) std::rethrow_exception(shared_->error);
  auto& done = shared_->queues.at(source).finished;
  for (auto& r : done) out.push_back(std::move(r));
  done.clear();
}

void JobPool::wait_for_a_result(double seconds) {
  std::unique_lock<std::mutex> lock(shared_->mutex);
  // A result already waiting returns at once: a job that ended after the caller's last
  // collect() must not cost it the whole nap.
  shared_->finished.wait_for(lock, std::chrono::duration<double>(seconds), [&] {
    if (shared_->error) return true;
    for (const auto& q : shared_->queues)
      if (!q.finished.empty()) return true;
    return false;
  });
}

void JobPool::check_alive(double limit, double stall_timeout) const {
  if (stall_timeout < 0.0) stall_timeout = limit;
  std::lock_guard<std::mutex> lock(shared_->mutex);
  const double now = wall_seconds();
  for (size_t k = 0; k < shared_->slots.size(); ++k) {
    const Shared::Slot& s = shared_->slots[k];
    if (s.since > 0.0 && now - s.since > limit)
      throw StallError(fmt::format(
          "the job of unit {} (step {}, iteration {}) has run for {:.0f} s on helper thread {} "
          "(farm.stall_timeout {:.0f} s): the thread is frozen or the job slower than the limit",
          s.unit, s.step, s.iteration, now - s.since, k + 1, stall_timeout));
  }
}

JobPool::Account JobPool::account() const {
  std::lock_guard<std::mutex> lock(shared_->mutex);
  return shared_->account;
}

}  // namespace fe2
