#include "coordinator/farm/Rebalancer.h"

#include <algorithm>
#include <set>

namespace fe2 {

CostModel::CostModel(size_t units) : rec_(units) {}

void CostModel::observe(int unit, bool refreshed, double cpu_seconds, double cpu_refresh,
                        double state_bytes) {
  Record& r = rec_[unit];
  r.state_bytes = state_bytes;
  if (refreshed) {
    r.refresh = cpu_seconds;
    r.refresh_part = cpu_refresh;
  } else {
    r.reuse = cpu_seconds;
  }
  known_ = true;
}

UnitCost CostModel::predict_one(int unit, bool refreshes) const {
  const Record& r = rec_[unit];
  UnitCost c;
  const double any = r.reuse >= 0 ? r.reuse : std::max(0.0, r.refresh);
  c.next = refreshes && r.refresh >= 0 ? r.refresh : any;
  c.rebuild = refreshes ? 0.0 : r.refresh_part;  // moving at a refresh boundary is free
  c.state_bytes = r.state_bytes;
  return c;
}

Placement static_placement(int units, int workers, FarmOptions::Policy policy) {
  Placement p;
  p.worker_of_unit.resize(units);
  for (int u = 0; u < units; ++u)
    p.worker_of_unit[u] = policy == FarmOptions::Policy::round_robin
                              ? u % workers
                              : static_cast<int>(static_cast<long long>(u) * workers / units);
  return p;
}

std::vector<double> worker_loads(const std::vector<UnitCost>& cost,
                                 const std::vector<int>& worker_of_unit, int workers) {
  std::vector<double> load(workers, 0.0);
  for (size_t u = 0; u < cost.size(); ++u) load[worker_of_unit[u]] += cost[u].next;
  return load;
}

double transfer_seconds(double bytes, const FarmOptions& o) {
  return o.latency + bytes / o.bandwidth;
}

std::vector<double> predicted_loads(const std::vector<UnitCost>& cost,
                                    const std::vector<int>& from, const std::vector<int>& to,
                                    int workers, const FarmOptions& o) {
  std::vector<double> load(workers, 0.0);
  for (size_t u = 0; u < cost.size(); ++u) {
    load[to[u]] += cost[u].next;
    if (to[u] != from[u]) {
      const double t = transfer_seconds(cost[u].state_bytes, o);
      load[from[u]] += t;
      load[to[u]] += t + cost[u].rebuild;
    }
  }
  return load;
}

namespace {

/// Longest processing time first, sticky: units by decreasing cost, each to whichever
/// is cheaper of its current worker and the least loaded one (moving pays transfer
/// and rebuild). O(U log W).
std::vector<int> sticky_lpt(const std::vector<UnitCost>& cost, const std::vector<int>& current,
                            int workers, const FarmOptions& o) {
  std::vector<int> order(cost.size());
  for (size_t u = 0; u < order.size(); ++u) order[u] = static_cast<int>(u);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return cost[a].next > cost[b].next; });
  std::vector<double> load(workers, 0.0);
  std::set<std::pair<double, int>> by_load;
  for (int w = 0; w < workers; ++w) by_load.emplace(0.0, w);
  std::vector<int> to(cost.size());
  for (int u : order) {
    const int stay = current[u];
    const int lo = by_load.begin()->second;
    const double move_extra = transfer_seconds(cost[u].state_bytes, o) + cost[u].rebuild;
    const int w = load[lo] + move_extra < load[stay] ? lo : stay;
    by_load.erase({load[w], w});
    load[w] += cost[u].next + (w != stay ? move_extra : 0.0);
    by_load.emplace(load[w], w);
    to[u] = w;
  }
  return to;
}

/// Local search from the current placement: moves and swaps between the most and the
/// least loaded workers (see the header).
std::vector<int> local_search(const std::vector<UnitCost>& cost, const std::vector<int>& worker_of_unit,
                              int workers, const FarmOptions& o);

}  // namespace

Plan plan_rebalance(const std::vector<UnitCost>& cost, const std::vector<int>& worker_of_unit,
                    int workers, const FarmOptions& o) {
  Plan plan;
  plan.worker_of_unit = worker_of_unit;
  const auto before = worker_loads(cost, worker_of_unit, workers);
  plan.makespan_before = *std::max_element(before.begin(), before.end());
  plan.makespan_after = plan.makespan_before;
  double total = 0.0;
  for (double l : before) total += l;
  if (plan.makespan_before <= (1.0 + o.tolerated_imbalance) * total / workers) return plan;
  auto makespan = [&](const std::vector<int>& to) {
    const auto l = predicted_loads(cost, worker_of_unit, to, workers, o);
    return *std::max_element(l.begin(), l.end());
  };
  auto moves = [&](const std::vector<int>& to) {
    int n = 0;
    for (size_t u = 0; u < to.size(); ++u) n += to[u] != worker_of_unit[u];
    return n;
  };
  // Two candidates: few moves from where units are, or a fresh sticky LPT; the lower
  // predicted makespan wins (fewer moves on a tie).
  const std::vector<int> a = local_search(cost, worker_of_unit, workers, o);
  const std::vector<int> b = sticky_lpt(cost, worker_of_unit, workers, o);
  const double ma = makespan(a), mb = makespan(b);
  const std::vector<int>& best = (mb < ma || (mb == ma && moves(b) < moves(a))) ? b : a;
  const double after = std::min(ma, mb);
  if (after > (1.0 - o.min_gain) * plan.makespan_before) return plan;  // not worth the moves
  plan.worker_of_unit = best;
  plan.makespan_after = after;
  for (size_t u = 0; u < cost.size(); ++u)
    if (best[u] != worker_of_unit[u]) plan.moves.emplace_back(static_cast<int>(u), best[u]);
  return plan;
}

namespace {

std::vector<int> local_search(const std::vector<UnitCost>& cost, const std::vector<int>& worker_of_unit,
                              int workers, const FarmOptions& o) {
  struct {
    std::vector<int> worker_of_unit;
  } plan;
  plan.worker_of_unit = worker_of_unit;
  std::vector<double> load = worker_loads(cost, worker_of_unit, workers);
  std::vector<std::vector<int>> held(workers);
  for (size_t u = 0; u < cost.size(); ++u) held[worker_of_unit[u]].push_back(static_cast<int>(u));
  std::set<std::pair<double, int>> by_load;  // (load, worker): O(log W) max and min
  for (int w = 0; w < workers; ++w) by_load.emplace(load[w], w);
  std::vector<char> moved(cost.size(), 0);
  auto move_cost = [&](int u) { return transfer_seconds(cost[u].state_bytes, o); };
  auto set_load = [&](int w, double v) {
    by_load.erase({load[w], w});
    load[w] = v;
    by_load.emplace(v, w);
  };

  for (size_t round = 0; round < cost.size(); ++round) {
    const int hi = by_load.rbegin()->second;
    const int lo = by_load.begin()->second;
    if (hi == lo) break;
    // Best single move hi -> lo, and best swap (u on hi) <-> (v on lo).
    int best_u = -1, best_v = -1;
    double best = load[hi];
    for (int u : held[hi]) {
      if (moved[u]) continue;
      const double t = move_cost(u);
      const double m = std::max(load[hi] - cost[u].next + t,
                                load[lo] + cost[u].next + t + cost[u].rebuild);
      if (m < best) best = m, best_u = u, best_v = -1;
      for (int v : held[lo]) {
        if (moved[v]) continue;
        const double tv = move_cost(v);
        const double ms = std::max(load[hi] - cost[u].next + cost[v].next + t + tv + cost[v].rebuild,
                                   load[lo] - cost[v].next + cost[u].next + t + tv + cost[u].rebuild);
        if (ms < best) best = ms, best_u = u, best_v = v;
      }
    }
    if (best_u < 0) break;
    const double t = move_cost(best_u);
    double new_hi = load[hi] - cost[best_u].next + t;
    double new_lo = load[lo] + cost[best_u].next + t + cost[best_u].rebuild;
    held[hi].erase(std::find(held[hi].begin(), held[hi].end(), best_u));
    held[lo].push_back(best_u);
    moved[best_u] = 1;
    plan.worker_of_unit[best_u] = lo;
    if (best_v >= 0) {
      const double tv = move_cost(best_v);
      new_hi += cost[best_v].next + tv + cost[best_v].rebuild;
      new_lo += tv - cost[best_v].next;
      held[lo].erase(std::find(held[lo].begin(), held[lo].end(), best_v));
      held[hi].push_back(best_v);
      moved[best_v] = 1;
      plan.worker_of_unit[best_v] = hi;
    }
    set_load(hi, new_hi);
    set_load(lo, new_lo);
  }
  return plan.worker_of_unit;
}

}  // namespace

}  // namespace fe2
