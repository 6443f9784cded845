// The farm simulator and the rebalancer: farm-sim predicts exactly the makespan the
// scheduler's placement gives, on a synthetic trace with known costs.
#include "coordinator/farm/Rebalancer.h"
#include "coordinator/farm/farm_sim.h"

#include <gtest/gtest.h>

#include <limits>

namespace fe2 {
namespace {

/// A synthetic trace: `iterations` copies of integer unit costs (exact in floating
/// point), all reuse jobs, no macro time.
FarmSimInput synthetic(const std::vector<double>& cost, int iterations) {
  FarmSimInput in;
  for (int i = 0; i < iterations; ++i) {
    in.cost.push_back(cost);
    in.refreshed.emplace_back(cost.size(), 0);
    in.refresh_part.emplace_back(cost.size(), 0.0);
    in.macro.push_back(0.0);
  }
  in.state_bytes.assign(cost.size(), 1000.0);
  return in;
}

FarmOptions free_network(FarmOptions::Policy p) {
  FarmOptions o;
  o.policy = p;
  o.latency = 0.0;
  o.bandwidth = std::numeric_limits<double>::infinity();
  o.min_gain = 0.0;
  o.tolerated_imbalance = 0.0;
  return o;
}

TEST(FarmSim, StaticPlacementMakespanIsExact) {
  const std::vector<double> cost = {3, 1, 3, 1, 5, 2};
  // round robin on 2 workers: {3,3,5} = 11 and {1,1,2} = 4
  const auto rr = simulate_farm(synthetic(cost, 2), 2, 6, free_network(FarmOptions::Policy::round_robin));
  ASSERT_EQ(rr.makespan.size(), 2u);
  EXPECT_EQ(rr.makespan[0], 11.0);
  EXPECT_EQ(rr.makespan[1], 11.0);
  // contiguous: {3,1,3} = 7 and {1,5,2} = 8
  const auto cg = simulate_farm(synthetic(cost, 1), 2, 6, free_network(FarmOptions::Policy::contiguous));
  EXPECT_EQ(cg.makespan[0], 8.0);
  EXPECT_EQ(cg.work, 15.0);
}

TEST(FarmSim, CostBasedMakespanIsTheSchedulersPlan) {
  const std::vector<double> cost = {9, 7, 6, 5, 4, 4, 3, 2, 2, 1, 1, 1};
  const int workers = 3;
  const FarmOptions o = free_network(FarmOptions::Policy::cost_based);
  const auto r = simulate_farm(synthetic(cost, 3), workers, 12, o);
  // Iteration 1 has no measured costs yet: the static contiguous start.
  const Placement start = static_placement(12, workers, o.policy);
  const auto loads = worker_loads([&] {
    std::vector<UnitCost> c(cost.size());
    for (size_t u = 0; u < cost.size(); ++u) c[u].next = cost[u], c[u].state_bytes = 1000.0;
    return c;
  }(), start.worker_of_unit, workers);
  EXPECT_EQ(r.makespan[0], *std::max_element(loads.begin(), loads.end()));  // 9+7+6+5 = 27
  EXPECT_EQ(r.makespan[0], 27.0);
  // Iteration 2: the scheduler's own plan from the measured costs.
  std::vector<UnitCost> c(cost.size());
  for (size_t u = 0; u < cost.size(); ++u) c[u].next = cost[u], c[u].state_bytes = 1000.0;
  const Plan plan = plan_rebalance(c, start.worker_of_unit, workers, o);
  EXPECT_EQ(r.makespan[1], plan.makespan_after);
  EXPECT_LT(plan.makespan_after, 27.0);
  EXPECT_LE(plan.makespan_after, 16.0);  // total 45 on 3 workers: 15 is the bound
  EXPECT_GT(r.migrations, 0);
}

// farm.rebalance_at = step: like the run, plan only before a new step's first
// iteration (iterations 0, 1 are step 0, iteration 2 is step 1).
TEST(FarmSim, RebalanceAtStepPlansOnlyBeforeANewStep) {
  const std::vector<double> cost = {9, 7, 6, 5, 4, 4, 3, 2, 2, 1, 1, 1};
  FarmSimInput in = synthetic(cost, 3);
  in.step = {0, 0, 1};
  FarmOptions o = free_network(FarmOptions::Policy::cost_based);
  o.rebalance_at = FarmOptions::When::step;
  const auto at_step = simulate_farm(in, 3, 12, o);
  EXPECT_EQ(at_step.makespan[0], 27.0);
  EXPECT_EQ(at_step.makespan[1], 27.0) << "same step: no rebalance";
  EXPECT_LE(at_step.makespan[2], 16.0) << "new step: the scheduler's plan";
  o.rebalance_at = FarmOptions::When::iteration;
  const auto every = simulate_farm(in, 3, 12, o);
  EXPECT_LE(every.makespan[1], 16.0);
  EXPECT_LE(every.makespan[2], 16.0);
}

TEST(Rebalancer, BalancesSeveralFoldCostsAndIsDeterministic) {
  // 6 expensive units (5) and 6 cheap ones (1), contiguous on 2 workers: 30 vs 6.
  std::vector<UnitCost> c(12);
  for (int u = 0; u < 12; ++u) c[u].next = u < 6 ? 5.0 : 1.0;
  const Placement p = static_placement(12, 2, FarmOptions::Policy::contiguous);
  FarmOptions o;
  const Plan a = plan_rebalance(c, p.worker_of_unit, 2, o);
  const Plan b = plan_rebalance(c, p.worker_of_unit, 2, o);
  EXPECT_EQ(a.makespan_before, 30.0);
  EXPECT_NEAR(a.makespan_after, 18.0, 1e-3);  // perfect: 3×5 + 3×1 on each
  EXPECT_EQ(a.moves, b.moves);
}

TEST(Rebalancer, PrefersNotToMoveWhenRebuildingCostsMoreThanItGains) {
  std::vector<UnitCost> c(4);
  for (int u = 0; u < 4; ++u) c[u].next = u == 0 ? 3.0 : 1.0, c[u].rebuild = 10.0;
  const Plan p = plan_rebalance(c, {0, 0, 1, 1}, 2, FarmOptions{});
  EXPECT_TRUE(p.moves.empty());  // 4 vs 2; any move adds a factorization of 10
  for (auto& u : c) u.rebuild = 0.0;  // at a refresh boundary moving is free
  EXPECT_FALSE(plan_rebalance(c, {0, 0, 1, 1}, 2, FarmOptions{}).moves.empty());
}

}  // namespace
}  // namespace fe2
