// The collective refresh decision (coordinator/farm/CollectiveRefresh.h): the ski rental over
// the summed costs of a model's units, per model, with commit/rollback and checkpoints.
#include "coordinator/farm/CollectiveRefresh.h"

#include "common/error.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

// Points 0..3 belong to model 0 (collective), 4..5 to model 1 (its own policy).
CollectiveRefresh two_models() { return CollectiveRefresh({0, 0, 0, 0, 1, 1}, {true, false}); }

std::vector<proto::JobOutput> results(double excess, double refresh, int points = 6) {
  std::vector<proto::JobOutput> r(points);
  for (int k = 0; k < points; ++k) {
    r[k].unit = k;
    r[k].excess_flops = excess;
    r[k].refresh_flops = refresh;
  }
  return r;
}

const CollectiveRefresh::SumOverCoordinators one_coordinator = [](int64_t*, int) {};

TEST(CollectiveRefresh, RefreshesAllUnitsOfTheModelOnceTheirExcessPaysForIt) {
  CollectiveRefresh c = two_models();
  EXPECT_TRUE(c.active());
  // R_0 = 4 × 100; each iteration adds 4 × 45 = 180 of excess: due after the third.
  EXPECT_EQ(c.account(results(45, 100), false, one_coordinator), 0);
  EXPECT_EQ(c.excess(0), 180);
  EXPECT_EQ(c.refresh_cost(0), 400);
  EXPECT_EQ(c.account(results(45, 100), false, one_coordinator), 0);
  EXPECT_FALSE(c.due(0));
  EXPECT_EQ(c.account(results(45, 100), false, one_coordinator), 1);
  for (int k = 0; k < 4; ++k) EXPECT_TRUE(c.due(k)) << k;
  // Model 1 keeps its own policy: its excess (counted above too) never forces it.
  EXPECT_FALSE(c.due(4));
  EXPECT_FALSE(c.due(5));
  EXPECT_EQ(c.excess(1), 0);
  EXPECT_EQ(c.due_models(), 1);
  // The refreshing iteration reports no excess: the rental starts over.
  EXPECT_EQ(c.account(results(0, 100), false, one_coordinator), 0);
  EXPECT_FALSE(c.due(0));
  EXPECT_EQ(c.excess(0), 0);
}

TEST(CollectiveRefresh, StallGuardRefreshStartsEveryModelOver) {
  CollectiveRefresh c = two_models();
  c.account(results(90, 100), false, one_coordinator);
  EXPECT_EQ(c.excess(0), 360);
  c.account(results(10, 100), true, one_coordinator);  // every unit refactored in this iteration
  EXPECT_EQ(c.excess(0), 40);
  EXPECT_FALSE(c.due(0));
}

TEST(CollectiveRefresh, UnitsWithoutAFactorHaveNothingToRent) {
  CollectiveRefresh c = two_models();
  EXPECT_EQ(c.account(results(1e6, 0), false, one_coordinator), 0);
  EXPECT_FALSE(c.due(0));
}

TEST(CollectiveRefresh, SumsOverCoordinatorsExactly) {
  // Two coordinators, each with two of model 0's units and costs that do not add up
  // exactly in double: 0.1 + 0.2 style fractions are rounded per unit to whole flops,
  // so any order of the reduction gives the same integers.
  CollectiveRefresh a({0, 0, 0, 0}, {true}), b({0, 0, 0, 0}, {true});
  std::vector<proto::JobOutput> mine = results(1e15 / 3, 3e15 / 7, 2), theirs = results(2e15 / 3, 1e15 / 7, 4);
  theirs.erase(theirs.begin(), theirs.begin() + 2);  // points 2, 3
  auto totals_of = [](const std::vector<proto::JobOutput>& r) {
    std::vector<int64_t> t(2, 0);
    for (const auto& o : r) t[0] += std::llround(o.excess_flops), t[1] += std::llround(o.refresh_flops);
    return t;
  };
  const auto ta = totals_of(mine), tb = totals_of(theirs);
  a.account(mine, false, [&](int64_t* v, int n) { for (int i = 0; i < n; ++i) v[i] += tb[i]; });
  b.account(theirs, false, [&](int64_t* v, int n) { for (int i = 0; i < n; ++i) v[i] += ta[i]; });
  EXPECT_EQ(a.excess(0), b.excess(0));
  EXPECT_EQ(a.refresh_cost(0), b.refresh_cost(0));
  EXPECT_EQ(a.excess(0), 2 * std::llround(1e15 / 3) + 2 * std::llround(2e15 / 3));
  EXPECT_TRUE(a.due(0));  // 2e15 of excess against 8e15/7 of refresh
  EXPECT_TRUE(b.due(0));
}

TEST(CollectiveRefresh, RollbackReturnsToTheCommittedStepAndCheckpointsKeepIt) {
  CollectiveRefresh c = two_models();
  c.account(results(45, 100), false, one_coordinator);
  c.account(results(45, 100), false, one_coordinator);
  c.commit();  // E_0 = 360
  c.account(results(45, 100), false, one_coordinator);
  EXPECT_TRUE(c.due(0));
  c.rollback();  // a cut-back: the step is retried from its start
  EXPECT_FALSE(c.due(0));
  EXPECT_EQ(c.excess(0), 360);

  Bytes b;
  ByteWriter w(b);
  c.save(w);
  CollectiveRefresh restored = two_models();
  ByteReader r(b, "checkpoint");
  restored.restore(r);
  EXPECT_EQ(restored.excess(0), 360);
  restored.account(results(45, 100), false, one_coordinator);
  EXPECT_TRUE(restored.due(0));

  // A checkpoint of a run with another number of point models is refused.
  CollectiveRefresh other({0}, {true});
  ByteReader r2(b, "checkpoint");
  EXPECT_THROW(other.restore(r2), InputError);
}

TEST(CollectiveRefresh, InactiveWithoutACollectiveModel) {
  EXPECT_FALSE(CollectiveRefresh({0, 1}, {false, false}).active());
}

}  // namespace
}  // namespace fe2
