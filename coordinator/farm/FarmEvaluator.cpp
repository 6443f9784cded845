#include "coordinator/farm/FarmEvaluator.h"

#include "coordinator/farm/Rebalancer.h"

#include "common/cpu_timer.h"
#include "worker/worker_loop.h"

#include <spdlog/spdlog.h>

#include <set>
#include <thread>

namespace fe2 {

namespace {
/// Local points evaluated between two polls of the job server (each a few µs).
constexpr int kLocalPointsPerPoll = 32;
/// The longest nap while this rank's helper threads run its jobs (seconds): a finished
/// job wakes the loop at once; the limit bounds how late another worker's pull is
/// served. A 20 µs nap loop there took a whole core from the helpers.
constexpr double kHelperNap = 2e-4;
}  // namespace

FarmEvaluator::FarmEvaluator(proto::Transport& transport, const proto::Group& coordinators,
                             const FarmLayout& layout, const RunSpec& spec, UnitStore* store,
                             Trace* trace)
    : transport_(transport),
      coords_(coordinators),
      layout_(layout),
      spec_(spec),
      store_(store),
      trace_(trace),
      server_(transport),
      placement_(layout.initial_worker_of_unit),
      farm_units_(layout.farm_units()),
      t0_(wall_seconds()) {
  if (store_) client_.emplace(transport_, *store_, spec.farm.batch, spec.farm.threads_per_rank);
  const std::vector<int> model = spec.model_of_points();
  model_of_point_ = model;
  num_models_ = static_cast<int>(spec.models.size());
  macro_law_.resize(model.size());
  std::vector<int> here;
  for (size_t u = 0; u < model.size(); ++u) {
    macro_law_[u] = spec.models[model[u]].kind == PointModelSpec::Kind::macro_law;
    if (layout.is_local(static_cast<int>(u)) && layout.coordinator_of_unit[u] == transport_.rank())
      here.push_back(static_cast<int>(u));
  }
  local_.emplace(spec.models, model, here);
  if (coords_.rank() == 0) {
    costs_.emplace(placement_.size());
    last_cost_.resize(placement_.size());
    planned_refresh_.assign(placement_.size(), -1);
  }
}

void FarmEvaluator::send_to_pure_workers(const proto::Control& c) {
  if (coords_.rank() != 0) return;
  Bytes b;
  c.pack(b);
  for (int r : layout_.worker_ranks)
    if (!layout_.is_coordinator(r)) transport_.send(r, proto::Type::control, b);
}

bool FarmEvaluator::next_job_refreshes(int unit, int step, int iteration) const {
  // The unit said, with its last result, which of its possible next jobs refresh.
  return proto::refreshes_next(last_cost_[unit].next_refresh, last_costs_at_.first,
                               last_costs_at_.second, step, iteration);
}

void FarmEvaluator::rebalance(int step, int iteration, const std::vector<int64_t>& forced_model) {
  if (farm_units_.empty()) return;  // every point is evaluated where it lives
  Bytes plan_bytes;
  if (coords_.rank() == 0) {
    // Cost model: each unit's next job costs what its last job of the same kind did.
    // Only units that travel are planned (local points are no movable work). A unit
    // refreshes when its own policy said so with its last result, or when the
    // coordinators force its model (a collective refresh, the stall guard): then all of
    // a model's units cost a refresh at once, and moving them costs no rebuild.
    const int nw = static_cast<int>(layout_.worker_ranks.size());
    std::vector<int> index_of_rank(layout_.ranks, -1);
    for (int i = 0; i < nw; ++i) index_of_rank[layout_.worker_ranks[i]] = i;
    std::vector<UnitCost> cost(farm_units_.size());
    std::vector<int> where(farm_units_.size());
    for (size_t i = 0; i < farm_units_.size(); ++i) {
      const int u = farm_units_[i];
      const bool refreshes = forced_model[model_of_point_[u]] > 0 || next_job_refreshes(u, step, iteration);
      planned_refresh_[u] = refreshes ? 1 : 0;
      cost[i] = costs_->predict_one(u, refreshes);
      // A rank's threads share its jobs: its CPU work takes 1/threads of the wall time
      // (every rank has farm.threads_per_rank), while a move's transfer does not shrink.
      cost[i].next /= spec_.farm.threads_per_rank;
      cost[i].rebuild /= spec_.farm.threads_per_rank;
      where[i] = index_of_rank[placement_[u]];
    }
    const Plan plan = plan_rebalance(cost, where, nw, spec_.farm);
    proto::Control c;
    c.command = proto::Command::rebalance;
    c.step = step;
    c.iteration = iteration;
    for (const auto& [i, w] : plan.moves) {
      const int u = farm_units_[i];
      c.moves.push_back({u, placement_[u], layout_.worker_ranks[w]});
    }
    if (!c.moves.empty())
      spdlog::debug("rebalance: {} moves, predicted makespan {:.4g} s -> {:.4g} s",
                    c.moves.size(), plan.makespan_before, plan.makespan_after);
    c.pack(plan_bytes);
  }
  coords_.bcast(plan_bytes, 0);
  const proto::Control c = proto::Control::unpack(plan_bytes);
  if (c.moves.empty()) return;
  send_to_pure_workers(c);
  for (const auto& m : c.moves) placement_[m.unit] = m.to;
  if (store_) {
    const auto [in, out] = migrate(transport_, *store_, c.moves);
    client_->count_migrations(in, out);
  }
  last_.migrations = static_cast<int>(c.moves.size());
}

void FarmEvaluator::evaluate(const std::vector<proto::JobInput>& jobs,
                             std::vector<proto::JobOutput>& out) {
  FE2_CHECK(!jobs.empty(), "every coordinator owns at least one unit");
  const int step = jobs.front().step, iteration = jobs.front().iteration;
  last_ = IterationTiming{};
  last_.step = step;
  last_.iteration = iteration;
  const bool new_step = step != last_step_;
  last_step_ = step;
  if (coords_.rank() == 0) std::fill(planned_refresh_.begin(), planned_refresh_.end(), -1);
  if (spec_.farm.policy == FarmOptions::Policy::cost_based) rebalance_if_due(jobs, new_step);
  std::vector<size_t> farm_index;
  const double t_start = dispatch(jobs, farm_index);
  serve_until_done();
  out.assign(jobs.size(), proto::JobOutput{});
  const std::vector<proto::JobOutput>& farm_out = server_.results();
  for (size_t i = 0; i < farm_out.size(); ++i) out[farm_index[i]] = farm_out[i];
  local_->results(out);
  const double micro_phase = wall_seconds() - t_start;
  last_.comm1 = server_.comm1_seconds();
  last_.comm2 = server_.comm2_seconds();
  gather_worker_stats(step, iteration, micro_phase);
  sum_local_points();
  gather_costs(farm_out, step, iteration);
}

void FarmEvaluator::rebalance_if_due(const std::vector<proto::JobInput>& jobs, bool new_step) {
  // Whether any coordinator has costs yet, and which models' jobs are forced to
  // refresh, summed over the coordinators: a model's units may all live elsewhere.
  std::vector<int64_t> known(1 + num_models_, 0);
  known[0] = have_costs_ ? 1 : 0;
  for (const auto& j : jobs)
    if (j.force_refresh) known[1 + model_of_point_[j.unit]] = 1;
  coords_.allreduce_sum(known.data(), static_cast<int>(known.size()));
  if (known[0] > 0 && (spec_.farm.rebalance_at == FarmOptions::When::iteration || new_step))
    rebalance(jobs.front().step, jobs.front().iteration, std::vector<int64_t>(known.begin() + 1, known.end()));
}

double FarmEvaluator::dispatch(const std::vector<proto::JobInput>& jobs, std::vector<size_t>& farm_index) {
  // (a) pure workers start pulling; this coordinator queues its units' jobs.
  const int step = jobs.front().step, iteration = jobs.front().iteration;
  proto::Control go;
  go.command = proto::Command::iterate;
  go.step = step;
  go.iteration = iteration;
  go.time = jobs.front().time;
  go.dt = jobs.front().dt;
  send_to_pure_workers(go);
  const double t_start = wall_seconds();
  // The jobs of local points stay here; the others are queued for their workers.
  std::vector<proto::JobInput> farm_jobs;
  local_->begin(jobs, farm_jobs, farm_index);
  for (const auto& j : farm_jobs) last_.macro_law_jobs_sent += macro_law_[j.unit];
  std::vector<int> worker_of_job(farm_jobs.size());
  for (size_t k = 0; k < farm_jobs.size(); ++k) worker_of_job[k] = placement_[farm_jobs[k].unit];
  server_.begin(farm_jobs, worker_of_job, spec_.farm.batch);
  if (client_) client_->begin(coordinators_of(*store_, layout_.coordinator_of_unit), step, iteration);
  return t_start;
}

void FarmEvaluator::serve_until_done() {
  // (b)–(f) serve pulls and work, until all of this coordinator's results are in and
  // this rank's own units and local points are done.
  auto client_done = [&] { return !client_ || client_->finished(); };
  double last_progress = wall_seconds();
  while (!(server_.finished() && client_done() && local_->finished())) {
    const long long before = server_.served() + (client_ ? client_->progress() : 0);
    if (!server_.finished()) server_.poll(false);
    if (!local_->finished()) {
      // A few local points between two polls: a waiting worker is served within
      // microseconds.
      local_->run(kLocalPointsPerPoll);
      last_progress = wall_seconds();
      continue;
    }
    if (!client_done()) client_->poll(false);
    if (server_.served() + (client_ ? client_->progress() : 0) != before) {
      last_progress = wall_seconds();
      continue;
    }
    if (wall_seconds() - last_progress > proto::stall_timeout()) {  // liveness limit
      // This rank's own frozen helper is the likelier culprit, and the one to name: its
      // job may have started just after the last progress, its own limit not yet up
      // (a race the frozen-thread test lost now and then). A job running for half the
      // limit while nothing arrived for all of it is the suspect.
      if (client_) client_->check_helpers(0.5 * proto::stall_timeout());
      throw StallError(fmt::format("nothing arrived for {:.0f} s (farm.stall_timeout); {}",
                                   proto::stall_timeout(), server_.describe_outstanding()));
    }
    // Nothing happened: block on whichever side is left, or nap briefly when both
    // wait for messages (MPI cannot probe two tags at once).
    if (server_.finished()) {
      client_->poll(true);
    } else if (client_done()) {
      server_.poll(true);
    } else if (!client_->wait_for_helpers(kHelperNap)) {
      std::this_thread::sleep_for(std::chrono::microseconds(20));
    }
  }
}

void FarmEvaluator::gather_worker_stats(int step, int iteration, double micro_phase) {
  // Worker stats to rank 0 (from every worker rank, this one included).
  if (client_) {
    Bytes b;
    client_->stats().pack(b);
    transport_.send(0, proto::Type::stats, std::move(b));
  }
  if (coords_.rank() == 0) {
    std::set<int> missing(layout_.worker_ranks.begin(), layout_.worker_ranks.end());
    for (size_t k = 0; k < layout_.worker_ranks.size(); ++k) {
      Bytes in;
      try {
        in = transport_.recv(proto::Type::stats, MPI_ANY_SOURCE);
      } catch (const StallError& e) {
        throw StallError(fmt::format("{}; silent: rank(s) {}, which ran their jobs of step {} "
                                     "iteration {} but never reported",
                                     e.what(), fmt::join(missing, ", "), step, iteration));
      }
      const proto::WorkerStats s = proto::WorkerStats::unpack(in);
      missing.erase(s.worker);
      last_.bytes += s.bytes_sent + s.bytes_received;
      last_.jobs += s.jobs;
      if (trace_) trace_->worker(s, micro_phase, t0_);
    }
  }
}

void FarmEvaluator::sum_local_points() {
  // Local points, summed over the coordinators (traces): jobs and CPU evaluated in
  // place, and jobs of macro-law points sent through the farm.
  double local[3] = {static_cast<double>(local_->jobs()), local_->cpu_seconds(),
                     static_cast<double>(last_.macro_law_jobs_sent)};
  coords_.reduce_sum(local, 3, 0);
  last_.local_jobs = static_cast<long long>(local[0]);
  last_.local_cpu = local[1];
  last_.macro_law_jobs_sent = static_cast<long long>(local[2]);
}

void FarmEvaluator::gather_costs(const std::vector<proto::JobOutput>& out, int step, int iteration) {
  // Per-unit costs of the farm's jobs to rank 0 (the cost model and the unit trace), as
  // a small message.
  proto::CostReport mine;
  mine.step = step;
  mine.iteration = iteration;
  mine.jobs.reserve(out.size());
  for (const auto& r : out) mine.jobs.push_back(proto::JobCost::of(r));
  Bytes packed;
  mine.pack(packed);
  const std::vector<Bytes> all = coords_.gather(packed, 0);
  if (coords_.rank() == 0) {
    for (const Bytes& b : all) {
      const proto::CostReport rep = proto::CostReport::unpack(b);
      for (const proto::JobCost& c : rep.jobs) {
        FE2_CHECK(static_cast<size_t>(c.unit) < last_cost_.size(), "cost of unknown unit {}", c.unit);
        if (trace_) trace_->unit(step, iteration, placement_[c.unit], c);
        if (planned_refresh_[c.unit] >= 0 && (planned_refresh_[c.unit] == 1) != (c.kind == proto::Refresh::refresh))
          ++last_.refresh_forecast_misses;
        if (c.failed) continue;  // no cost measured: keep the unit's last good figures
        costs_->observe(c.unit, c.kind == proto::Refresh::refresh, c.cpu_seconds, c.cpu_refresh,
                        static_cast<double>(c.state_bytes));
        last_cost_[c.unit] = c;
      }
    }
    last_costs_at_ = {step, iteration};
  }
  have_costs_ = true;
}

void FarmEvaluator::commit_step() {
  proto::Control c;
  c.command = proto::Command::commit;
  send_to_pure_workers(c);
  if (store_) store_->commit();
  local_->commit();
}

void FarmEvaluator::rollback_step() {
  // A rollback restores the units' committed state: their next-refresh bits, given
  // before it, no longer hold (the retry's moves are charged a rebuild).
  last_costs_at_ = {-2, 0};  // no job follows step -2: every bit reads "unknown"
  proto::Control c;
  c.command = proto::Command::rollback;
  send_to_pure_workers(c);
  if (store_) store_->rollback();
  local_->rollback();
}

std::vector<proto::UnitFields> FarmEvaluator::unit_fields(const std::vector<int>& units, int step) {
  // Every coordinator gets the same `units`, so all refuse alike (no one waits).
  for (int u : units)
    FE2_CHECK(!(u >= 0 && static_cast<size_t>(u) < placement_.size() && layout_.is_local(u)),
              "fields of unit {}: a macro_law point has no micro fields", u);
  // Every coordinator knows the placement (rebalance plans are broadcast), so each
  // holder answers without being asked twice; only pure workers need the request.
  proto::Control c;
  c.command = proto::Command::fields;
  c.step = step;
  for (int u : units) c.moves.push_back({u, placement_.at(static_cast<size_t>(u)), 0});
  send_to_pure_workers(c);
  const int me = transport_.rank();
  if (store_ && me != 0) send_unit_fields(transport_, *store_, c.moves, step);
  std::vector<proto::UnitFields> out;
  if (me != 0) return out;
  out.resize(units.size());
  std::vector<int> index(placement_.size(), -1);
  for (size_t k = 0; k < units.size(); ++k) {
    index[static_cast<size_t>(units[k])] = static_cast<int>(k);
    if (c.moves[k].from == 0) out[k] = store_->fields(units[k], step);
  }
  for (const proto::Move& m : c.moves) {
    if (m.from == 0) continue;
    int from = -1;
    proto::UnitFields f = proto::UnitFields::unpack(transport_.recv(proto::Type::unit_fields, MPI_ANY_SOURCE, &from));
    FE2_CHECK(f.unit >= 0 && static_cast<size_t>(f.unit) < index.size() && index[f.unit] >= 0 &&
                  placement_[f.unit] == from && f.step == step,
              "rank {} sent the fields of unit {} at step {}; expected one of the units it holds "
              "at step {}", from, f.unit, f.step, step);
    out[index[f.unit]] = std::move(f);
  }
  return out;
}

void FarmEvaluator::save_states(const StateSink& sink, bool with_factors) {
  proto::Control c;
  c.command = proto::Command::checkpoint;
  c.with_factors = with_factors ? 1 : 0;
  for (size_t u = 0; u < placement_.size(); ++u) c.moves.push_back({static_cast<int>(u), placement_[u], 0});
  send_to_pure_workers(c);
  // A coordinator holds its local points and, if it works, units of the farm.
  auto copy_here = [&](int u) {
    return local_->holds(u) ? local_->copy(u, with_factors) : store_->copy(u, with_factors);
  };
  const int me = transport_.rank();
  if (me != 0) {
    send_unit_states(transport_, c.moves, copy_here);
    return;
  }
  // Rank 0 writes each state as it comes, so it never holds more than the messages in flight.
  std::vector<char> seen(placement_.size(), 0);
  int expected = 0;
  for (const proto::Move& m : c.moves) {
    if (m.from != 0) {
      ++expected;
      continue;
    }
    sink(m.unit, copy_here(m.unit));
    seen[m.unit] = 1;
  }
  for (int k = 0; k < expected; ++k) {
    int from = -1;
    proto::UnitState s = proto::UnitState::unpack(transport_.recv(proto::Type::state, MPI_ANY_SOURCE, &from));
    FE2_CHECK(s.unit >= 0 && static_cast<size_t>(s.unit) < seen.size() && !seen[s.unit] &&
                  placement_[s.unit] == from,
              "rank {} sent the state of unit {} for the checkpoint; expected one of the units it holds, once",
              from, s.unit);
    seen[s.unit] = 1;
    sink(s.unit, s.state);
  }
}

void FarmEvaluator::restore_states(const std::vector<int>& points, const StateSource& read) {
  // Every coordinator must know the order in which rank 0 sends (its own units' states
  // arrive in it); pure workers learn it from the Control.
  Bytes order;
  if (coords_.rank() == 0) {
    ByteWriter w(order);
    w.put_array(points.data(), points.size());
  }
  coords_.bcast(order, 0);
  ByteReader r(order, "checkpoint unit order");
  const std::vector<int> units = r.get_array<int>();
  proto::Control c;
  c.command = proto::Command::restore;
  for (int u : units) {
    FE2_CHECK(u >= 0 && static_cast<size_t>(u) < placement_.size(), "checkpoint: unit {} of {}", u, placement_.size());
    c.moves.push_back({u, 0, placement_[u]});
  }
  send_to_pure_workers(c);
  auto restore_here = [&](int u, const Bytes& state) {
    if (local_->holds(u)) local_->restore(u, state);
    else store_->restore(u, state);
  };
  const int me = transport_.rank();
  if (me != 0) {
    receive_unit_states(transport_, c.moves, restore_here);
    return;
  }
  for (const proto::Move& m : c.moves) {
    if (m.to == 0) {
      restore_here(m.unit, read(m.unit));
      continue;
    }
    proto::UnitState s;
    s.unit = m.unit;
    s.state = read(m.unit);
    Bytes b;
    s.pack(b);
    transport_.send(m.to, proto::Type::state, std::move(b));
  }
}

void FarmEvaluator::shutdown() {
  proto::Control c;
  c.command = proto::Command::shutdown;
  send_to_pure_workers(c);
  transport_.complete_sends();
}

}  // namespace fe2
