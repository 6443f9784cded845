#include "coordinator/farm/farm_sim.h"

#include "common/error.h"
#include "coordinator/farm/Rebalancer.h"
#include "proto/messages.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace fe2 {

FarmSimInput farm_sim_input(const TraceData& t, double default_state_bytes) {
  FarmSimInput in;
  std::map<std::pair<int, int>, size_t> index;
  for (const auto& it : t.iterations) {
    index[{it.at("step").get<int>(), it.at("iteration").get<int>()}] = in.macro.size();
    in.macro.push_back(it.at("macro").get<double>());
    in.macro_kind.push_back(macro_solve_kind(it));
    in.step.push_back(it.at("step").get<int>());
  }
  // The units that travelled, numbered densely (points evaluated by their coordinators,
  // farm.macro_law_points "local", have no records: they are no farm work).
  std::map<int, int> dense;
  for (const auto& u : t.units) dense.emplace(u.at("unit").get<int>(), 0);
  int units = 0;
  for (auto& [id, v] : dense) v = units++;
  if (units == 0)
    throw InputError("farm-sim: trace_units.jsonl has no unit records (no point travelled "
                     "through the farm: macro-law points are evaluated by their coordinators)");
  const size_t n = in.macro.size();
  in.cost.assign(n, std::vector<double>(units, 0.0));
  in.refreshed.assign(n, std::vector<char>(units, 0));
  in.refresh_part.assign(n, std::vector<double>(units, 0.0));
  in.gmres.assign(n, std::vector<int>(units, 0));
  in.state_bytes.assign(units, 0.0);
  for (const auto& u : t.units) {
    const int v = dense.at(u.at("unit").get<int>());
    in.state_bytes[v] = std::max(in.state_bytes[v], u.value("state_bytes", 0.0));
    auto it = index.find({u.at("step").get<int>(), u.at("iteration").get<int>()});
    if (it == index.end()) continue;  // an iteration the run did not finish
    in.cost[it->second][v] = u.at("cost").get<double>();
    in.refreshed[it->second][v] = u.at("kind").get<std::string>() == "refresh";
    in.refresh_part[it->second][v] = u.value("refresh_cost", 0.0);
    in.gmres[it->second][v] = u.value("gmres", 0);
  }
  for (double& b : in.state_bytes)
    if (b <= 0.0) b = default_state_bytes;
  return in;
}

void replace_macro(FarmSimInput& in, const MacroCost& cost) {
  for (size_t i = 0; i < in.macro.size(); ++i) in.macro[i] = cost.predict(in.macro_kind[i]);
}

FarmSimResult simulate_farm(const FarmSimInput& in, int workers, long long units,
                            const FarmOptions& o, double macro_scale) {
  FE2_CHECK(workers >= 1 && units >= 1, "workers {}, units {}", workers, units);
  const long long measured = static_cast<long long>(in.state_bytes.size());
  std::vector<double> bytes(units);
  for (long long v = 0; v < units; ++v) bytes[v] = in.state_bytes[v % measured];
  CostModel model(static_cast<size_t>(units));
  std::vector<int> where = static_placement(static_cast<int>(units), workers, o.policy).worker_of_unit;
  const double job_bytes = static_cast<double>(proto::kJobInputBytes + proto::kJobOutputBytes);

  FarmSimResult r;
  std::vector<double> load(workers);
  std::vector<long long> jobs(workers);
  for (size_t i = 0; i < in.macro.size(); ++i) {
    auto cost_of = [&](long long v) { return in.cost[i][v % measured]; };
    auto refreshes = [&](long long v) { return in.refreshed[i][v % measured] != 0; };
    std::fill(load.begin(), load.end(), 0.0);
    std::fill(jobs.begin(), jobs.end(), 0);
    const bool new_step = in.step.empty() || i == 0 || in.step[i] != in.step[i - 1];
    if (o.policy == FarmOptions::Policy::cost_based && model.known() &&
        (o.rebalance_at == FarmOptions::When::iteration || new_step)) {
      const Plan plan = plan_rebalance(model.predict([&](int v) { return refreshes(v); }), where,
                                       workers, o);
      for (const auto& [v, to] : plan.moves) {
        const double t = transfer_seconds(bytes[v], o);
        load[where[v]] += t;
        load[to] += t + model.predict_one(v, refreshes(v)).rebuild;
        where[v] = to;
      }
      r.migrations += static_cast<int>(plan.moves.size());
    }
    for (long long v = 0; v < units; ++v) {
      load[where[v]] += cost_of(v);
      ++jobs[where[v]];
      r.work += cost_of(v);
    }
    double makespan = 0.0;
    for (int w = 0; w < workers; ++w) {
      if (jobs[w] > 0) {
        const double messages = 2.0 * std::ceil(static_cast<double>(jobs[w]) / o.batch);
        load[w] += messages * o.latency + jobs[w] * job_bytes / o.bandwidth;
      }
      makespan = std::max(makespan, load[w]);
    }
    r.makespan.push_back(makespan);
    r.micro += makespan;
    r.entire += makespan + in.macro[i] * macro_scale;
    for (long long v = 0; v < units; ++v)
      model.observe(static_cast<int>(v), refreshes(v), cost_of(v), in.refresh_part[i][v % measured],
                    bytes[v]);
  }
  return r;
}

}  // namespace fe2
