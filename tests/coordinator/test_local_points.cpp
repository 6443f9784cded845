// The points a coordinator evaluates in place (LocalPoints, farm.macro_law_points
// "local") must answer exactly as a worker's UnitStore would: the same outputs bit for
// bit through a step, a commit, a failed step rolled back and its retry. The law keeps
// history (tests/support/history_law.h), so a lost commit or a missed rollback changes
// numbers.
#include "coordinator/LocalPoints.h"
#include "tests/support/history_law.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fe2 {
namespace {

proto::JobInput job(int unit, int step, double time, double dt, double stretch) {
  proto::JobInput in;
  in.unit = unit;
  in.step = step;
  in.iteration = 1;
  in.time = time;
  in.dt = dt;
  in.Zbar = Vec9::Zero();
  in.Zbar[0] = stretch * (1.0 + 0.01 * unit);  // Z̄ = F̄ − I, a different one per point
  in.Zbar[4] = -0.3 * stretch;
  in.Zbar_dot = in.Zbar / dt;
  return in;
}

bool same_bits(const proto::JobOutput& a, const proto::JobOutput& b) {
  return a.unit == b.unit && a.failed == b.failed &&
         std::memcmp(a.P_bar.data(), b.P_bar.data(), sizeof(double) * 9) == 0 &&
         std::memcmp(a.P_tilde.data(), b.P_tilde.data(), sizeof(double) * 9) == 0 &&
         std::memcmp(a.A_hom.data(), b.A_hom.data(), sizeof(double) * 81) == 0 &&
         a.state_bytes == b.state_bytes && a.next_refresh == b.next_refresh;
}

struct Scene {
  std::vector<PointModelSpec> models;
  std::vector<int> model_of_unit = std::vector<int>(6, 0);
  Scene() {
    PointModelSpec m;
    m.name = "history";
    m.kind = PointModelSpec::Kind::macro_law;
    m.material = std::make_shared<test::HistoryLaw>(1.0e4, 0.3, 5.0);
    models.push_back(m);
  }
};

TEST(LocalPoints, KeepsItsOwnJobsAndHandsBackTheRest) {
  const Scene s;
  LocalPoints local(s.models, s.model_of_unit, {1, 3, 4});
  EXPECT_EQ(local.size(), 3);
  std::vector<proto::JobInput> jobs;
  for (int u = 0; u < 6; ++u) jobs.push_back(job(u, 0, 0.1, 0.1, 0.05));
  std::vector<proto::JobInput> farm;
  std::vector<size_t> index;
  local.begin(jobs, farm, index);
  ASSERT_EQ(farm.size(), 3u);
  EXPECT_EQ(farm[0].unit, 0);
  EXPECT_EQ(farm[1].unit, 2);
  EXPECT_EQ(farm[2].unit, 5);
  EXPECT_EQ(index, (std::vector<size_t>{0, 2, 5}));
  EXPECT_EQ(local.jobs(), 3);
  EXPECT_FALSE(local.run(2));  // a few at a time: the coordinator serves pulls between
  EXPECT_TRUE(local.run(2));
  std::vector<proto::JobOutput> out(jobs.size());
  local.results(out);
  const std::vector<int> expected = {-1, 1, -1, 3, 4, -1};  // farm slots untouched
  for (size_t k = 0; k < out.size(); ++k) EXPECT_EQ(out[k].unit, expected[k]) << k;
  EXPECT_GT(out[1].P_bar.norm(), 0.0);
  EXPECT_GE(local.cpu_seconds(), 0.0);
}

TEST(LocalPoints, AnswersAsAWorkerThroughCommitRollbackAndRetry) {
  const Scene s;
  const std::vector<int> units = {0, 2, 5};
  LocalPoints local(s.models, s.model_of_unit, units);
  UnitStore worker(s.models, s.model_of_unit);  // what a worker rank holds
  for (int u : units) worker.create(u);

  auto iterate_local = [&](int step, double t, double dt, double stretch) {
    std::vector<proto::JobInput> jobs, farm;
    std::vector<size_t> index;
    for (int u : units) jobs.push_back(job(u, step, t, dt, stretch));
    local.begin(jobs, farm, index);
    EXPECT_TRUE(farm.empty());
    while (!local.run(1)) {
    }
    std::vector<proto::JobOutput> out(jobs.size());
    local.results(out);
    return out;
  };
  auto iterate_worker = [&](int step, double t, double dt, double stretch) {
    std::vector<proto::JobOutput> out;
    for (int u : units) out.push_back(worker.run(job(u, step, t, dt, stretch)));
    return out;
  };
  auto expect_same = [&](const std::vector<proto::JobOutput>& a,
                         const std::vector<proto::JobOutput>& b, const char* what) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(same_bits(a[k], b[k])) << what << ", point " << k;
  };

  // Step 0, committed, on both.
  expect_same(iterate_local(0, 0.1, 0.1, 0.05), iterate_worker(0, 0.1, 0.1, 0.05), "step 0");
  local.commit();
  worker.commit();
  // Step 1: the local points try a large step that fails elsewhere and roll back; the
  // worker never saw it. The retry must equal the worker's straight step.
  const auto failed = iterate_local(1, 0.2, 0.1, 0.4);
  local.rollback();
  const auto retry = iterate_local(1, 0.15, 0.05, 0.08);
  const auto straight = iterate_worker(1, 0.15, 0.05, 0.08);
  EXPECT_FALSE(same_bits(failed[0], straight[0]));  // the failed try did differ
  expect_same(retry, straight, "retry after rollback");
  local.commit();
  worker.commit();
  // Step 2 reads the committed history of step 1 (a lost commit would change it).
  expect_same(iterate_local(2, 0.2, 0.05, 0.1), iterate_worker(2, 0.2, 0.05, 0.1), "step 2");
}

}  // namespace
}  // namespace fe2
