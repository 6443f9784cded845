// Micro-unit machinery: periodic DOFs, factor backends, GMRES, state migration.
#include "tests/worker/unit_fixtures.h"
#include "worker/gmres.h"
#include "worker/unit_equilibrium.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fe2 {
namespace {

using test::gradient;

TEST(PeriodicDofMap, CountsOnePinnedNodeAndPeriodicImages) {
  CellLayout c;
  c.kind = "homogeneous";
  c.resolution = {5, 3, 4};
  const HexMesh mesh = make_cell_mesh(c);
  const PeriodicDofMap dofs(mesh, "grid");
  EXPECT_EQ(dofs.num_masters(), 5 * 3 * 4);
  EXPECT_EQ(dofs.num_dofs(), 3 * 5 * 3 * 4 - 3);
  // The far corner is an image of the pinned origin.
  EXPECT_EQ(dofs.master(mesh.num_nodes() - 1), dofs.pinned_node());
  EXPECT_EQ(dofs.dof(mesh.num_nodes() - 1, 0), -1);
}

TEST(PeriodicDofMap, NonPeriodicMeshIsNamedInputError) {
  CellLayout c;
  c.kind = "homogeneous";
  c.resolution = {2, 2, 2};
  HexMesh mesh = make_cell_mesh(c);
  // Move a node on face x = hi (i = 2, j = 1, k = 1) within the face.
  const int node = 2 + 3 * (1 + 3 * 1);
  mesh.nodes[node].y() += 0.01;
  try {
    PeriodicDofMap dofs(mesh, "shifted");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not periodic"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("shifted"), std::string::npos) << e.what();
  }
}

TEST(SparseFactor, CholmodAndUmfpackAgreeOnUnitMatrix) {
  MicroUnit unit(test::two_cell_model());
  proto::JobInput in;
  in.Zbar = gradient({0.05, 0.01, 0, 0, -0.02, 0, 0, 0, 0.01});
  unit.iterate(in);
  const SparseMatrix& K = unit.system().K;
  const Eigen::MatrixXd& G = unit.system().G;
  Eigen::MatrixXd X1(G.rows(), 9), X2(G.rows(), 9);
  auto chol = make_sparse_factor(FactorKind::cholesky);
  auto lu = make_sparse_factor(FactorKind::lu);
  chol->factorize(K);
  lu->factorize(K);
  chol->solve(G.data(), X1.data(), 9);
  lu->solve(G.data(), X2.data(), 9);
  EXPECT_LT((K * X1 - G).norm() / G.norm(), 1e-12);
  EXPECT_LT((K * X2 - G).norm() / G.norm(), 1e-12);
  EXPECT_GT(chol->factor_flops(), 0.0);
  EXPECT_GT(lu->solve_flops(), 0.0);
}

TEST(Gmres, SolvesUnsymmetricSystemToTrueResidual) {
  const int n = 60;
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n) * 4.0;
  for (int i = 0; i + 1 < n; ++i) A(i, i + 1) = 1.5, A(i + 1, i) = -0.7;
  const Vec b = Vec::LinSpaced(n, 1.0, 2.0);
  Vec x = Vec::Zero(n);
  const LinearOp op = [&](const Vec& v, Vec& y) { y = A * v; };
  const LinearOp id = [](const Vec& v, Vec& y) { y = v; };
  const GmresResult r = gmres(op, id, b, x, 1e-12, 10, 500);  // restarts on purpose
  EXPECT_TRUE(r.converged);
  EXPECT_LE((b - A * x).norm(), 1e-12);
  EXPECT_GT(r.iterations, 10);
}

proto::JobInput job(int step, int iteration, const Vec9& Z) {
  proto::JobInput in;
  in.step = step;
  in.iteration = iteration;
  in.apply_update = iteration > 1;
  in.Zbar = Z;
  return in;
}

bool same_bits(const proto::JobOutput& a, const proto::JobOutput& b) {
  return std::memcmp(a.A_hom.data(), b.A_hom.data(), sizeof(double) * 81) == 0 &&
         std::memcmp(a.P_tilde.data(), b.P_tilde.data(), sizeof(double) * 9) == 0 &&
         a.gmres_iterations == b.gmres_iterations && a.r_norm == b.r_norm;
}

// A unit serialized mid-run (stale factor, pending update) and rebuilt elsewhere
// continues bit for bit like the one that stayed.
TEST(MicroUnitState, MigratedUnitContinuesBitForBit) {
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::fixed;
  opt.N_t = 100;
  const auto model = test::two_cell_model(opt);
  MicroUnit stay(model);
  const Vec9 Z1 = gradient({0.05, 0.0, 0.01, 0.0, -0.01, 0.0, 0.02, 0.0, 0.0});
  stay.iterate(job(0, 1, Z1));
  stay.iterate(job(0, 2, 1.1 * Z1));  // stale factor now, and an update pending
  Bytes state;
  stay.serialize(state);
  MicroUnit moved(model);
  moved.deserialize(state);
  for (int it = 3; it < 7; ++it) {
    const Vec9 Z = (1.0 + 0.05 * it) * Z1;
    const auto a = stay.iterate(job(0, it, Z));
    const auto b = moved.iterate(job(0, it, Z));
    EXPECT_TRUE(same_bits(a, b)) << "iteration " << it;
    EXPECT_GT(a.gmres_iterations, 1) << "the factor is stale, GMRES works";
  }
  EXPECT_EQ(std::memcmp(stay.w().data(), moved.w().data(), sizeof(double) * stay.w().size()), 0);
}

TEST(MicroUnitState, CorruptedStateIsRejected) {
  const auto model = test::two_cell_model();
  MicroUnit unit(model);
  unit.iterate(job(0, 1, gradient({0.02, 0, 0, 0, 0, 0, 0, 0, 0})));
  Bytes state;
  unit.serialize(state);
  MicroUnit other(model);
  Bytes truncated(state.begin(), state.begin() + state.size() / 2);
  EXPECT_THROW(other.deserialize(truncated), Error);
  Bytes wrong = state;
  wrong[20] ^= std::byte{0xff};  // inside the model fingerprint
  EXPECT_THROW(other.deserialize(wrong), Error);
  // A state from a different unit model is refused.
  MicroUnit coarse(test::two_cell_model({}, {4, 4, 4}));
  EXPECT_THROW(coarse.deserialize(state), Error);
}

// Rollback returns the unit to its committed state exactly.
TEST(MicroUnitState, RollbackRestoresCommittedState) {
  MicroUnit unit(test::two_cell_model());
  const Vec9 Z = gradient({0.04, 0, 0, 0.01, 0, 0, 0, 0, -0.01});
  equilibrate(unit, Z, 1e-10, 20);
  const Vec w0 = unit.w();
  unit.iterate(job(1, 1, 2 * Z));
  unit.iterate(job(1, 2, 2.5 * Z));
  EXPECT_GT((unit.w() - w0).norm(), 0.0);
  unit.rollback_step();
  EXPECT_EQ((unit.w() - w0).norm(), 0.0);
}

// The adaptive policy refreshes less often than every iteration and still converges.
TEST(MicroUnitPolicy, AdaptiveRefreshesWhenKrylovWorkOutgrowsARefresh) {
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::adaptive;
  MicroUnit unit(test::two_cell_model(opt));
  int total = 0;
  for (int s = 1; s <= 12; ++s) {
    const UnitEquilibrium eq =
        equilibrate(unit, gradient({0.02 * s, 0.0, 0.0, 0.005 * s, 0, 0, 0, 0, 0}), 1e-10, 30, s);
    total += eq.newton_iterations + 1;
  }
  // equilibrate() forces one refresh per call (exact final tangent); the policy adds
  // few beyond those.
  EXPECT_LT(unit.refresh_count(), total);
  EXPECT_GE(unit.refresh_count(), 12);
}

}  // namespace
}  // namespace fe2
