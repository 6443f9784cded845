// A step that fails is rolled back and retried with a smaller increment.
// The retry must start from exactly the committed unit: its factor and χ, not
// those computed at the failed (possibly inverted) iterate, and the adaptive policy's
// counters as they were. Otherwise the retry's preconditioner is the failed state's and
// the adaptive policy fails spuriously.
#include "tests/worker/unit_fixtures.h"
#include "worker/unit_equilibrium.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fe2 {
namespace {

using test::gradient;

proto::JobInput job(int step, int iteration, const Vec9& Z, bool force_refresh = false) {
  proto::JobInput in;
  in.step = step;
  in.iteration = iteration;
  in.apply_update = iteration > 1;
  in.force_refresh = force_refresh;
  in.Zbar = Z;
  return in;
}

void expect_same_bits(const proto::JobOutput& a, const proto::JobOutput& b, int it) {
  EXPECT_EQ(std::memcmp(a.A_hom.data(), b.A_hom.data(), sizeof(double) * 81), 0) << "iteration " << it;
  EXPECT_EQ(std::memcmp(a.P_tilde.data(), b.P_tilde.data(), sizeof(double) * 9), 0) << "iteration " << it;
  EXPECT_EQ(a.r_norm, b.r_norm) << "iteration " << it;
  EXPECT_EQ(a.gmres_iterations, b.gmres_iterations) << "iteration " << it;
  EXPECT_EQ(a.kind, b.kind) << "iteration " << it;
}

class RetryAfterRollback : public ::testing::TestWithParam<MicroSolverOptions::Refresh> {};

// Commit at Z1; a failing step refreshes at a far-away Z̄ (as a step that ends in an
// inverted element does); roll back; retry toward Z2. The retry equals, bit for bit, a
// unit rebuilt from the committed state doing the same retry — also when the unit
// migrated in the middle of the failing step.
TEST_P(RetryAfterRollback, EqualsFreshRunFromCommittedState) {
  MicroSolverOptions opt;
  opt.refresh = GetParam();
  opt.N_t = 1000;  // fixed: only the first job of step 0 refreshes by policy
  const auto model = test::two_cell_model(opt);
  MicroUnit unit(model);
  const Vec9 Z1 = gradient({0.03, 0.0, 0.01, 0.0, -0.01, 0.0, 0.0, 0.0, 0.01});
  const Vec9 Z_failed = gradient({-0.35, 0.1, 0.0, 0.05, 0.3, 0.0, 0.0, 0.0, -0.2});
  const Vec9 Z2 = 1.5 * Z1;
  for (int it = 1; it <= 3; ++it) unit.iterate(job(0, it, Z1));
  unit.commit_step();
  Bytes committed;
  unit.serialize(committed);
  const int refreshes_committed = unit.refresh_count();

  // The failing step: a refresh at a far-away iterate, then more work there.
  unit.iterate(job(1, 1, Z_failed, /*force_refresh=*/true));
  unit.iterate(job(1, 2, Z_failed));
  Bytes mid_failure;  // the unit migrates while the step is still failing
  unit.serialize(mid_failure);
  MicroUnit migrated(model);
  migrated.deserialize(mid_failure);
  unit.rollback_step();
  migrated.rollback_step();
  EXPECT_EQ(unit.refresh_count(), refreshes_committed);

  MicroUnit fresh(model);
  fresh.deserialize(committed);
  int gmres = 0;
  for (int it = 1; it <= 5; ++it) {
    const auto a = unit.iterate(job(1, it, Z2));
    const auto b = fresh.iterate(job(1, it, Z2));
    const auto c = migrated.iterate(job(1, it, Z2));
    expect_same_bits(a, b, it);
    expect_same_bits(c, b, it);
    gmres += b.gmres_iterations;
  }
  // Reusing the committed factor means GMRES works: the test would not see a wrong
  // preconditioner if every job refreshed.
  EXPECT_GT(gmres, 5);
}

INSTANTIATE_TEST_SUITE_P(Policies, RetryAfterRollback,
                         ::testing::Values(MicroSolverOptions::Refresh::adaptive,
                                           MicroSolverOptions::Refresh::fixed),
                         [](const auto& info) {
                           return info.param == MicroSolverOptions::Refresh::adaptive ? "adaptive"
                                                                                     : "fixed";
                         });

}  // namespace
}  // namespace fe2
