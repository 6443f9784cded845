// The rental policies' budget within a job (worker/RefreshPolicy.h): Step 1 GMRES on a
// stale factor gives up once it has cost as much as a refresh, and the unit refreshes and
// solves again, reaching the answer of a unit that refreshed at once.
#include "unit_fixtures.h"
#include "worker/MicroModel.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

using Refresh = MicroSolverOptions::Refresh;

struct StaleJob {
  proto::JobOutput out;
  int budget = 0;  ///< the policy's stale budget when the job began
};

/// A two-cell unit factored at Z (step 0), then asked at `jump`·Z (step 1, iteration 1)
/// under `policy`: the second job finds a factor of the first state.
StaleJob job_far_from_the_factor(Refresh policy, double jump) {
  MicroSolverOptions opt;
  opt.refresh = policy;
  opt.N_t = 100;  // fixed: never due in step 1
  opt.gmres_rtol = 1e-12;
  opt.gmres_forcing = MicroSolverOptions::Forcing::constant;
  opt.gmres_max_iterations = 500;
  opt.gmres_restart = 3;  // restarted often, a stale factor costs many iterations
  MicroUnit unit(test::two_cell_model(opt));
  proto::JobInput in = test::factor_at_step_zero(unit);
  StaleJob j;
  j.budget = unit.policy().stale_gmres_budget(opt.gmres_max_iterations);
  in.step = 1;
  in.Zbar = jump * in.Zbar;
  j.out = unit.iterate(in);
  return j;
}

TEST(StaleGmresBudget, AStaleSolveThatWouldCostMoreThanARefreshRefreshesAtTheBudget) {
  const double jump = -10.0;  // measured: 67 iterations on the stale factor, budget 23, fresh 1
  const StaleJob fixed = job_far_from_the_factor(Refresh::fixed, jump);
  const StaleJob adaptive = job_far_from_the_factor(Refresh::adaptive, jump);
  const StaleJob collective = job_far_from_the_factor(Refresh::collective, jump);
  const StaleJob fresh = job_far_from_the_factor(Refresh::every_iteration, jump);
  fmt::print("stale GMRES (fixed) {}, budget {}, fresh {}; adaptive {} ({}), collective {} ({})\n",
             fixed.out.gmres_iterations, adaptive.budget, fresh.out.gmres_iterations,
             adaptive.out.gmres_iterations, adaptive.out.kind == proto::Refresh::refresh ? "refresh" : "reuse",
             collective.out.gmres_iterations,
             collective.out.kind == proto::Refresh::refresh ? "refresh" : "reuse");
  // The case must be one the budget decides: fixed keeps the paper's factor to the end.
  EXPECT_EQ(fixed.budget, 500) << "fixed has no budget";
  ASSERT_EQ(fixed.out.kind, proto::Refresh::reuse);
  ASSERT_GT(fixed.out.gmres_iterations, adaptive.budget + fresh.out.gmres_iterations)
      << "the stale solve is too cheap here to show the budget";
  for (const StaleJob* j : {&adaptive, &collective}) {
    EXPECT_EQ(j->budget, adaptive.budget);
    EXPECT_LT(j->budget, 500);
    EXPECT_EQ(j->out.kind, proto::Refresh::refresh);
    // Exactly the budget on the stale factor, then the fresh unit's own solve ...
    EXPECT_EQ(j->out.gmres_iterations, j->budget + fresh.out.gmres_iterations);
    // ... and its answer, bit for bit (the same K factored, χ recomputed, δw₁ from zero).
    EXPECT_EQ(j->out.P_tilde, fresh.out.P_tilde);
    EXPECT_EQ(j->out.A_hom, fresh.out.A_hom);
  }
}

TEST(StaleGmresBudget, AStaleSolveWithinTheBudgetKeepsTheFactor) {
  const double jump = 1.05;  // close to the factored state: a few iterations
  const StaleJob fixed = job_far_from_the_factor(Refresh::fixed, jump);
  const StaleJob adaptive = job_far_from_the_factor(Refresh::adaptive, jump);
  ASSERT_LT(fixed.out.gmres_iterations, adaptive.budget);
  EXPECT_EQ(adaptive.out.kind, proto::Refresh::reuse);
  EXPECT_EQ(adaptive.out.gmres_iterations, fixed.out.gmres_iterations);
  EXPECT_EQ(adaptive.out.P_tilde, fixed.out.P_tilde);
}

}  // namespace
}  // namespace fe2
