// Simulation::request_stop (a batch system's SIGTERM/SIGUSR1, tools/cmd_run.cpp): the run
// returns after the step in progress, marked stopped, unless that step was the last one,
// in which case the run is complete and there is nothing to continue.
#include "coordinator/PointEvaluator.h"
#include "tests/coordinator/scene_fixtures.h"

namespace fe2 {
namespace {

RunResult run_stopping_at(int stop_step, int steps) {
  const RunSpec spec = read_run_spec(test::beam({{"kind", "macro_law"}, {"material", test::nh(2.0e4, 0.4)}}, steps), "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  return sim.run([&](const StepRecord& r) {
    if (r.step == stop_step) sim.request_stop();
  });
}

TEST(StopRequest, StopsAfterTheStepInProgress) {
  const RunResult r = run_stopping_at(0, 3);
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.steps, 1);
  EXPECT_EQ(r.history.size(), 1u);
}

TEST(StopRequest, InTheLastStepTheRunIsComplete) {
  const RunResult r = run_stopping_at(2, 3);
  EXPECT_FALSE(r.stopped);
  EXPECT_TRUE(r.converged) << r.error;
  EXPECT_EQ(r.steps, 3);
}

}  // namespace
}  // namespace fe2
