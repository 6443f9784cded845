// The refresh policies (paper Fig. 6) as scripted sequences with exact answers: which
// job refactors, given the libraries' flop counts and each job's GMRES iterations.
#include "tools/unit_spec.h"
#include "worker/RefreshPolicy.h"

#include <gtest/gtest.h>

#include <vector>

namespace fe2 {
namespace {

using Kind = RefreshPolicy::Kind;

TEST(RefreshPolicy, EveryIterationAndFixedAreTablesOfStepAndIteration) {
  const RefreshPolicy every(Kind::every_iteration, 10, 100.0);
  const RefreshPolicy fixed(Kind::fixed, 3, 100.0);
  for (int step = 0; step < 7; ++step)
    for (int it = 1; it < 4; ++it) {
      EXPECT_TRUE(every.due(step, it));
      EXPECT_EQ(fixed.due(step, it), it == 1 && (step == 0 || step == 3 || step == 6))
          << "step " << step << " iteration " << it;
    }
}

/// Runs jobs with the given GMRES iteration counts (a reuse job reports its count; a
/// refresh job's count is ignored, as a fresh factor needs one) and returns the
/// indices of the jobs that refreshed. Job 0 finds no factor and refreshes.
std::vector<int> refresh_jobs(RefreshPolicy& p, const std::vector<int>& gmres) {
  std::vector<int> refreshed;
  for (int j = 0; j < static_cast<int>(gmres.size()); ++j) {
    if (j == 0 || p.due(0, j + 1)) {
      p.refreshed(10000.0, 1000.0);  // factor 10⁴ flops, one solve 10³
      refreshed.push_back(j);
    } else {
      p.reused(gmres[j]);
    }
  }
  return refreshed;
}

// Ski rental: one GMRES iteration costs a solve plus a product with K, 1000 + 200
// flops; a refresh costs the factor and 9 solves for χ, 10⁴ + 9·10³ = 19000 flops. So
// the policy refreshes once the iterations beyond one per job since the last refresh
// reach 19000 / 1200 = 15.8, i.e. 16.
TEST(RefreshPolicy, AdaptiveRefreshesExactlyWhenExcessKrylovWorkPaysForARefresh) {
  RefreshPolicy p(Kind::adaptive, 10, 200.0);
  p.refreshed(10000.0, 1000.0);
  EXPECT_EQ(p.iteration_flops(), 1200.0);
  EXPECT_EQ(p.refresh_flops(), 19000.0);
  //                  job:  0  1  2  3  4  5  6  7  8  9 10 11 12 13 14
  const std::vector<int> k{1, 1, 4, 6, 2, 5, 3, 1, 9, 9, 1, 1, 17, 1, 2};
  // excess after jobs 1..6: 0, 3, 8, 9, 13, 15 (< 15.8); job 7 reuses (+0), job 8
  // brings 23: job 9 refreshes. Then 0 (10), 0 (11), 16 (12) >= 15.8: job 13 refreshes.
  EXPECT_EQ(refresh_jobs(p, k), (std::vector<int>{0, 9, 13}));
  // 16 excess iterations pay for a refresh (19200 >= 19000 flops), 15 do not (18000).
  RefreshPolicy q(Kind::adaptive, 10, 200.0);
  q.refreshed(10000.0, 1000.0);
  q.reused(16);
  EXPECT_FALSE(q.due(0, 2));
  q.reused(2);
  EXPECT_TRUE(q.due(0, 3));
  EXPECT_TRUE(q.due(5, 1)) << "adaptive ignores step and iteration";
  q.refreshed(10000.0, 1000.0);
  EXPECT_FALSE(q.due(0, 4)) << "a refresh pays the debt";
}

// Within a job: the rental policies let a stale Step 1 spend one refresh's worth of
// GMRES iterations (refresh / (weight · iteration) flops, rounded up), between the floor
// for cheap refreshes and the model's limit; fixed and every_iteration keep the limit.
TEST(RefreshPolicy, RentalPoliciesBudgetAStaleSolveAtOneRefresh) {
  for (Kind kind : {Kind::adaptive, Kind::collective}) {
    RefreshPolicy p(kind, 10, 200.0);
    EXPECT_EQ(p.stale_gmres_budget(500), 500) << "no refresh yet: no cost to compare with";
    p.refreshed(100000.0, 1000.0);  // 109000 flops against 1200 an iteration: 90.8
    EXPECT_EQ(p.stale_gmres_budget(500), 91);
    EXPECT_EQ(p.stale_gmres_budget(60), 60);
    p.refreshed(10000.0, 1000.0);  // 15.8: the floor
    EXPECT_EQ(p.stale_gmres_budget(500), RefreshPolicy::kMinStaleGmresBudget);
    EXPECT_EQ(p.stale_gmres_budget(8), 8);
  }
  // A solve's flop at four of a factorization's: 109000 / (4 · 1200) = 22.7.
  RefreshPolicy weighted(Kind::collective, 10, 200.0, 4.0);
  weighted.refreshed(100000.0, 1000.0);
  EXPECT_EQ(weighted.stale_gmres_budget(500), 23);
  EXPECT_EQ(weighted.refresh_flops(), 109000.0) << "the weight is the budget's alone";
  for (Kind kind : {Kind::fixed, Kind::every_iteration}) {
    RefreshPolicy p(kind, 10, 200.0);
    p.refreshed(100000.0, 1000.0);
    EXPECT_EQ(p.stale_gmres_budget(500), 500);
  }
}

// A unit that never needs more than one GMRES iteration never refreshes again.
TEST(RefreshPolicy, AdaptiveNeverRefreshesWhileTheFactorIsExact) {
  RefreshPolicy p(Kind::adaptive, 10, 200.0);
  EXPECT_EQ(refresh_jobs(p, std::vector<int>(50, 1)), std::vector<int>{0});
}

// The counters travel with a migrated unit: the copy decides as the original.
TEST(RefreshPolicy, StateRoundTripKeepsTheDecision) {
  RefreshPolicy a(Kind::adaptive, 10, 200.0);
  a.refreshed(10000.0, 1000.0);
  a.reused(10);
  Bytes bytes;
  ByteWriter w(bytes);
  a.write(w);
  RefreshPolicy b(Kind::adaptive, 10, 200.0);
  ByteReader r(bytes, "policy");
  b.read(r);
  EXPECT_TRUE(r.at_end());
  EXPECT_EQ(b.excess_iterations(), 9.0);
  EXPECT_EQ(b.refresh_flops(), a.refresh_flops());
  for (int more : {5, 1, 2, 3}) {  // excess 13, 13, 14, 16
    a.reused(more);
    b.reused(more);
    EXPECT_EQ(a.due(0, 1), b.due(0, 1));
  }
  EXPECT_TRUE(b.due(0, 1));
}

}  // namespace
}  // namespace fe2

namespace fe2 {
namespace {

// Collective: the unit never refreshes on its own however stale its factor (the
// coordinators decide, coordinator/farm/CollectiveRefresh.h); it reports each job's excess
// GMRES work and its refresh cost in the adaptive policy's own flop counts.
TEST(RefreshPolicy, CollectiveLeavesTheDecisionToTheCoordinators) {
  RefreshPolicy p(Kind::collective, 10, 200.0);
  p.refreshed(10000.0, 1000.0);
  EXPECT_EQ(refresh_jobs(p, std::vector<int>(20, 30)), std::vector<int>{0});
  EXPECT_EQ(p.excess_flops(1), 0.0);
  EXPECT_EQ(p.excess_flops(4), 3 * 1200.0);
  EXPECT_EQ(p.refresh_flops(), 19000.0);
}

// `fe2heart unit` runs one unit with no coordinators: there a collective unit rents alone.
TEST(RefreshPolicy, ALoneUnitSpecTakesCollectiveAsAdaptive) {
  const json j = {{"unit", {{"cell", "homogeneous"}, {"resolution", {2, 2, 2}},
                            {"materials", {{"matrix", {{"model", "neo_hookean"}, {"E", 1.0e4}, {"nu", 0.3}}}}},
                            {"solver", {{"refresh", "collective"}}}}},
                  {"Zbar", {0.01, 0, 0, 0, 0, 0, 0, 0, 0}}};
  const cli::UnitSpec u = cli::read_unit_spec(j, "unit.json", nullptr, false);
  EXPECT_EQ(u.plan->options.refresh, MicroSolverOptions::Refresh::adaptive);
}

}  // namespace
}  // namespace fe2
