// JobPool, the queue a rank's helper threads drain (farm.threads_per_rank), with a
// trivial job in place of a unit's: every job runs once and its result reaches the
// source it came from; a result finished but not collected keeps the pool pending (the
// worker's main thread must not block on a message then: the race that hung a
// 3-rank, 2-coordinator run); a helper's fatal error and a frozen helper reach the
// main thread.
#include "common/error.h"
#include "worker/JobPool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <set>
#include <thread>

namespace fe2 {
namespace {

proto::JobInput job(int unit) {
  proto::JobInput in;
  in.unit = unit;
  in.step = 3;
  in.iteration = 2;
  return in;
}

proto::JobOutput answer(const proto::JobInput& in) {
  proto::JobOutput out;
  out.unit = in.unit;
  out.r_norm = 2.0 * in.unit;
  return out;
}

/// True until `seconds` have passed since the first call of this deadline: loops that
/// wait for helpers give up by the clock, not by a count (a waiting result of another
/// source wakes wait_for_a_result at once).
struct Deadline {
  std::chrono::steady_clock::time_point end =
      std::chrono::steady_clock::now() + std::chrono::seconds(20);
  bool open() const { return std::chrono::steady_clock::now() < end; }
};

/// Collects until `n` results of `source` are in (or the deadline passes).
std::vector<proto::JobOutput> collect_all(JobPool& pool, int source, size_t n) {
  std::vector<proto::JobOutput> out;
  for (Deadline d; d.open() && out.size() < n;) {
    pool.collect(source, out);
    if (out.size() < n) pool.wait_for_a_result(0.001);
  }
  return out;
}

/// `n` finished results of source 0 keep the pool pending (a result waiting for its pull
/// must keep the main thread awake) until collected.
void expect_pending_until_collected(JobPool& pool, size_t n) {
  EXPECT_EQ(pool.pending(), n) << "finished results not yet collected must count";
  std::vector<proto::JobOutput> out;
  pool.collect(0, out);
  EXPECT_EQ(out.size(), n);
  EXPECT_EQ(pool.pending(), 0u);
}

TEST(JobPool, EveryJobRunsOnceOnTheHelpersAndReachesItsSource) {
  std::atomic<int> runs{0};
  const std::thread::id main_thread = std::this_thread::get_id();
  std::atomic<bool> ran_on_main{false};
  JobPool pool(
      [&](const proto::JobInput& in) {
        ++runs;
        if (std::this_thread::get_id() == main_thread) ran_on_main = true;
        return answer(in);
      },
      2);
  EXPECT_EQ(pool.threads(), 2);
  pool.reset(2);
  for (int u = 0; u < 40; ++u) pool.push(u % 2, job(u));
  EXPECT_FALSE(pool.run_one_here()) << "with helpers the main thread runs no job";
  for (int source = 0; source < 2; ++source) {
    const std::vector<proto::JobOutput> out = collect_all(pool, source, 20);
    ASSERT_EQ(out.size(), 20u);
    std::set<int> units;
    for (const auto& o : out) {
      EXPECT_EQ(o.unit % 2, source);
      EXPECT_EQ(o.r_norm, 2.0 * o.unit);
      units.insert(o.unit);
    }
    EXPECT_EQ(units.size(), 20u) << "a job ran twice or was lost";
  }
  EXPECT_EQ(runs.load(), 40);
  EXPECT_FALSE(ran_on_main.load());
  EXPECT_EQ(pool.pending(), 0u);
  EXPECT_EQ(pool.account().jobs, 40);
}

TEST(JobPool, OneThreadRunsTheJobsOnTheCallerInQueueOrder) {
  const std::thread::id main_thread = std::this_thread::get_id();
  std::vector<int> order;
  JobPool pool(
      [&](const proto::JobInput& in) {
        EXPECT_EQ(std::this_thread::get_id(), main_thread);
        order.push_back(in.unit);
        return answer(in);
      },
      1);
  pool.reset(1);
  for (int u : {5, 1, 7}) pool.push(0, job(u));
  EXPECT_EQ(pool.pending(), 3u);
  while (pool.run_one_here()) {
  }
  EXPECT_EQ(order, (std::vector<int>{5, 1, 7}));
  expect_pending_until_collected(pool, 3);
}

TEST(JobPool, AFinishedResultNotYetCollectedKeepsThePoolPending) {
  JobPool pool(answer, 2);
  pool.reset(1);
  pool.push(0, job(4));
  // Wait until the job has finished (neither queued nor running) without collecting.
  for (Deadline d; d.open() && (pool.queued(0) > 0 || pool.running(0) > 0);)
    pool.wait_for_a_result(0.001);
  ASSERT_EQ(pool.queued(0), 0u);
  ASSERT_EQ(pool.running(0), 0);
  expect_pending_until_collected(pool, 1);
}

TEST(JobPool, AHelpersFatalErrorReachesTheMainThread) {
  JobPool pool(
      [](const proto::JobInput& in) -> proto::JobOutput {
        if (in.unit == 3) throw Error("unit 3 broke");
        return answer(in);
      },
      2);
  pool.reset(1);
  for (int u = 0; u < 6; ++u) pool.push(0, job(u));
  std::vector<proto::JobOutput> out;
  bool thrown = false;
  for (Deadline d; d.open() && !thrown;) {
    try {
      pool.collect(0, out);
      pool.wait_for_a_result(0.001);
    } catch (const Error& e) {
      thrown = true;
      EXPECT_NE(std::string(e.what()).find("unit 3 broke"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(thrown);
}

TEST(JobPool, AHelperInAJobPastTheLimitIsNamed) {
  std::atomic<bool> release{false};
  JobPool pool(
      [&](const proto::JobInput& in) {
        while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        return answer(in);
      },
      2);
  pool.reset(1);
  pool.push(0, job(8));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_NO_THROW(pool.check_alive(10.0));
  try {
    pool.check_alive(0.05);
    ADD_FAILURE() << "a job running 0.2 s passed a 0.05 s limit";
  } catch (const StallError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unit 8 (step 3, iteration 2)"), std::string::npos) << what;
    EXPECT_NE(what.find("helper thread"), std::string::npos) << what;
  }
  release = true;
  EXPECT_EQ(collect_all(pool, 0, 1).size(), 1u);
}

}  // namespace
}  // namespace fe2
