// farm.factor_memory_budget on one rank's UnitStore: three units, room for
// two factors and a half. The least recently used factor is dropped, the dropped unit
// rebuilds it on its next job, the counts say so, and every answer equals the run
// without a budget bit for bit (tolerance 0: the rebuild factors the very matrix of the
// unit's last refresh, as after a migration).
#include "tests/worker/unit_fixtures.h"
#include "worker/UnitStore.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fe2 {
namespace {

using test::gradient;

proto::JobInput job(int unit, int iteration, const Vec9& Z) {
  proto::JobInput in;
  in.unit = unit;
  in.step = 0;
  in.iteration = iteration;
  in.apply_update = iteration > 1;
  in.Zbar = Z;
  return in;
}

void expect_same_bits(const proto::JobOutput& a, const proto::JobOutput& b, const std::string& where) {
  EXPECT_EQ(std::memcmp(a.A_hom.data(), b.A_hom.data(), sizeof(double) * 81), 0) << where;
  EXPECT_EQ(std::memcmp(a.P_tilde.data(), b.P_tilde.data(), sizeof(double) * 9), 0) << where;
  EXPECT_EQ(std::memcmp(a.P_bar.data(), b.P_bar.data(), sizeof(double) * 9), 0) << where;
  EXPECT_EQ(a.r_norm, b.r_norm) << where;
  EXPECT_EQ(a.gmres_iterations, b.gmres_iterations) << where;
  EXPECT_EQ(a.kind, b.kind) << where;
}

TEST(FactorBudget, DropsLeastRecentlyUsedAndRebuildsToTheSameAnswer) {
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::fixed;
  opt.N_t = 1000;  // only the first job of each unit refreshes: later jobs reuse the factor
  PointModelSpec spec;
  spec.kind = PointModelSpec::Kind::fe2;
  spec.micro = test::two_cell_model(opt);
  const std::vector<PointModelSpec> models = {spec};
  const std::vector<int> model_of_unit = {0, 0, 0};
  const Vec9 Z0 = gradient({0.03, 0.0, 0.01, 0.0, -0.01, 0.0, 0.0, 0.0, 0.01});
  auto Z = [&](int unit) { return (1.0 + 0.5 * unit) * Z0; };

  UnitStore unlimited(models, model_of_unit), budgeted(models, model_of_unit);
  for (int u = 0; u < 3; ++u) unlimited.create(u), budgeted.create(u);
  // The size of one factor (same pattern, same CHOLMOD analysis for all three).
  std::vector<proto::JobOutput> ref(3), out(3);
  for (int u = 0; u < 3; ++u) ref[u] = unlimited.run(job(u, 1, Z(u)));
  const double factor = unlimited.held_factor_bytes() / 3;
  ASSERT_GT(factor, 0.0);
  budgeted.set_factor_budget(2.5 * factor);

  // Iteration 1 in order 0, 1, 2: the third factor does not fit; unit 0 is the LRU.
  for (int u = 0; u < 3; ++u) {
    out[u] = budgeted.run(job(u, 1, Z(u)));
    expect_same_bits(out[u], ref[u], fmt::format("iteration 1, unit {}", u));
  }
  EXPECT_EQ(out[0].factor_evictions, 0);
  EXPECT_EQ(out[1].factor_evictions, 0);
  EXPECT_EQ(out[2].factor_evictions, 1);
  EXPECT_EQ(budgeted.factor_counts(0).evictions, 1);
  EXPECT_EQ(budgeted.factor_counts(1).evictions, 0);
  EXPECT_NEAR(budgeted.held_factor_bytes(), 2 * factor, 1e-9 * factor);

  // Iteration 2 in order 1, 0, 2. Unit 1 reuses its factor; unit 0 must drop the LRU of
  // {1 (just used), 2}: unit 2; then unit 2 drops the LRU of {0, 1}: unit 1.
  for (int u : {1, 0, 2}) {
    ref[u] = unlimited.run(job(u, 2, Z(u)));
    out[u] = budgeted.run(job(u, 2, Z(u)));
    expect_same_bits(out[u], ref[u], fmt::format("iteration 2, unit {}", u));
    EXPECT_EQ(out[u].kind, proto::Refresh::reuse) << "unit " << u;
  }
  EXPECT_EQ(out[1].factor_evictions, 0);
  EXPECT_EQ(out[1].factor_rebuilt, 0);
  EXPECT_EQ(out[0].factor_evictions, 1);
  EXPECT_EQ(out[0].factor_rebuilt, 1);
  EXPECT_GT(out[0].cpu_refresh, 0.0);  // the rebuild is in the job's measured cost
  EXPECT_EQ(out[2].factor_evictions, 1);
  EXPECT_EQ(out[2].factor_rebuilt, 1);
  EXPECT_EQ(budgeted.factor_counts(2).evictions, 1);  // by unit 0, not unit 1
  EXPECT_EQ(budgeted.factor_counts(1).evictions, 1);  // by unit 2

  // Iteration 3 in order 0, 1, 2: unit 1 drops unit 2 (LRU of {0, 2}), unit 2 drops unit 0.
  int gmres = 0;
  for (int u : {0, 1, 2}) {
    ref[u] = unlimited.run(job(u, 3, Z(u)));
    out[u] = budgeted.run(job(u, 3, Z(u)));
    expect_same_bits(out[u], ref[u], fmt::format("iteration 3, unit {}", u));
    gmres += out[u].gmres_iterations;
  }
  EXPECT_GT(gmres, 0);  // the reused factors are preconditioners, so a wrong one would show
  EXPECT_EQ(out[0].factor_rebuilt, 0);
  EXPECT_EQ(out[1].factor_rebuilt, 1);
  EXPECT_EQ(out[2].factor_rebuilt, 1);

  const int evictions[3] = {2, 1, 2}, rebuilds[3] = {1, 1, 2};
  for (int u = 0; u < 3; ++u) {
    EXPECT_EQ(budgeted.factor_counts(u).evictions, evictions[u]) << "unit " << u;
    EXPECT_EQ(budgeted.factor_counts(u).rebuilds, rebuilds[u]) << "unit " << u;
  }
  EXPECT_EQ(budgeted.factor_counts().evictions, 5);
  EXPECT_EQ(budgeted.factor_counts().rebuilds, 4);
  EXPECT_LE(budgeted.peak_factor_bytes(), 2.5 * factor);
  EXPECT_EQ(unlimited.factor_counts().evictions, 0);
  EXPECT_NEAR(unlimited.peak_factor_bytes(), 3 * factor, 1e-9 * factor);

  // Counts are per rank, and per unit while it lives here: a unit that arrives starts at
  // zero, and its first job's rebuild (it arrives without a factor) is not one after a drop.
  const Bytes state = budgeted.take(2);
  budgeted.put(2, state);
  EXPECT_EQ(budgeted.factor_counts(2).evictions, 0);
  const proto::JobOutput moved = budgeted.run(job(2, 4, Z(2)));
  EXPECT_EQ(moved.factor_rebuilt, 0);
  EXPECT_EQ(budgeted.factor_counts().rebuilds, 4);
}

}  // namespace
}  // namespace fe2
