#include "worker/PullClient.h"

#include "common/cpu_timer.h"

#include <algorithm>
#include <thread>

namespace fe2 {

namespace {
/// The main thread's longest nap while helpers run (seconds): a finished job wakes it
/// at once; the limit bounds how late a batch that arrives meanwhile is taken.
constexpr double kHelperNap = 0.001;
}  // namespace

PullClient::PullClient(proto::Transport& transport, UnitStore& store, int batch, int threads)
    : transport_(transport),
      store_(store),
      batch_(std::max(1, batch) * std::max(1, threads)),
      pool_([&store](const proto::JobInput& job) { return store.run(job); }, std::max(1, threads)) {}

void PullClient::begin(const std::vector<int>& coordinators, int step, int iteration) {
  sources_.clear();
  // Every coordinator sends its first batch unasked (JobServer::begin).
  for (int c : coordinators) {
    Source& s = sources_.emplace_back();
    s.rank = c;
    s.outstanding = true;
  }
  pool_.reset(static_cast<int>(sources_.size()));
  stats_ = proto::WorkerStats{};
  stats_.worker = transport_.rank();
  stats_.step = step;
  stats_.iteration = iteration;
  stats_.units_held = store_.size();
  stats_.t_begin = wall_seconds();
  sent0_ = transport_.bytes_sent();
  received0_ = transport_.bytes_received();
  if (sources_.empty()) close_stats();
}

void PullClient::close_stats() {
  stats_.t_end = wall_seconds();
  const JobPool::Account a = pool_.account();
  stats_.busy_cpu = a.busy_cpu;
  stats_.busy_wall = a.busy_wall;
  stats_.jobs = a.jobs;
  stats_.threads = pool_.threads();
  stats_.bytes_sent = transport_.bytes_sent() - sent0_;
  stats_.bytes_received = transport_.bytes_received() - received0_;
  stats_.migrations_in = migrations_in_;
  stats_.migrations_out = migrations_out_;
  migrations_in_ = migrations_out_ = 0;
}

bool PullClient::finished() const {
  return std::all_of(sources_.begin(), sources_.end(), [](const Source& s) { return s.done; });
}

void PullClient::check_helpers(double limit) const {
  if (pool_.threads() > 1) pool_.check_alive(limit, proto::stall_timeout());
}

bool PullClient::poll(bool block) {
  if (finished()) return true;
  // Results the pool's threads finished go with the next pull.
  for (size_t k = 0; k < sources_.size(); ++k) {
    const size_t before = sources_[k].results.size();
    pool_.collect(static_cast<int>(k), sources_[k].results);
    progress_ += static_cast<long long>(sources_[k].results.size() - before);
  }
  check_helpers(proto::stall_timeout());
  // Ask ahead (with the results so far): while half a batch is still queued, or, once
  // the coordinator has no more jobs, with the last results when none is queued or running.
  const size_t ahead = static_cast<size_t>(batch_ / 2);
  for (size_t k = 0; k < sources_.size(); ++k) {
    Source& s = sources_[k];
    const int source = static_cast<int>(k);
    const size_t queued = pool_.queued(source);
    if (!s.done && !s.outstanding &&
        (s.exhausted ? queued == 0 && pool_.running(source) == 0 : queued <= ahead)) {
      proto::Pull p;
      p.worker = transport_.rank();
      p.max_jobs = batch_;
      p.results = std::move(s.results);
      s.results.clear();
      Bytes b;
      p.pack(b);
      transport_.send(s.rank, proto::Type::pull, std::move(b));
      s.outstanding = true;
      ++progress_;
    }
  }
  // Run one job here, if any is queued.
  if (pool_.run_one_here()) {
    ++progress_;
    return false;
  }
  // Nothing to run here: take a batch that has arrived, or wait for one — unless helpers
  // have jobs, whose results the next pull may wait for: then nap until one finishes.
  Bytes b;
  int from = -1;
  const double w0 = wall_seconds();
  bool got = transport_.try_recv(proto::Type::batch, b, &from);
  if (!got && block) {
    if (pool_.pending() > 0) {
      pool_.wait_for_a_result(kHelperNap);
    } else {
      b = transport_.recv(proto::Type::batch, MPI_ANY_SOURCE, &from, proto::kIndirectPatience);
      got = true;
    }
  }
  stats_.wait_wall += wall_seconds() - w0;
  if (!got) return false;
  ++progress_;
  const proto::Batch batch = proto::Batch::unpack(b);
  auto it = std::find_if(sources_.begin(), sources_.end(), [&](const Source& s) { return s.rank == from; });
  FE2_CHECK(it != sources_.end() && it->outstanding, "unexpected batch from rank {}", from);
  it->outstanding = false;
  it->done = batch.done;
  it->exhausted = batch.jobs.empty();
  const int source = static_cast<int>(it - sources_.begin());
  for (const auto& j : batch.jobs) pool_.push(source, j);
  if (finished()) close_stats();
  return finished();
}

bool PullClient::wait_for_helpers(double seconds) {
  if (pool_.threads() == 1 || pool_.pending() == 0) return false;
  pool_.wait_for_a_result(seconds);
  return true;
}

proto::WorkerStats PullClient::stats() const { return stats_; }

std::pair<int, int> migrate(proto::Transport& transport, UnitStore& store,
                            const std::vector<proto::Move>& moves) {
  const int me = transport.rank();
  int sent = 0, received = 0;
  for (const auto& m : moves)
    if (m.from == me) {
      proto::UnitState s;
      s.unit = m.unit;
      s.state = store.take(m.unit);
      Bytes b;
      s.pack(b);
      transport.send(m.to, proto::Type::state, std::move(b));
      ++sent;
    }
  for (const auto& m : moves)
    if (m.to == me) {
      const proto::UnitState s = proto::UnitState::unpack(transport.recv(proto::Type::state, m.from));
      FE2_CHECK(s.unit == m.unit, "expected the state of unit {} from rank {}, got unit {}", m.unit,
                m.from, s.unit);
      store.put(s.unit, s.state);
      ++received;
    }
  return {received, sent};
}

}  // namespace fe2
