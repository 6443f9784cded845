// GMRES (common/linalg/gmres.h): the true-residual test, and how many times it applies
// the operator. A Step 1 solve on a fresh factor converges in one iteration; the true
// residual after that iteration is y₀·(A z₀), the product the iteration already made,
// so the solve costs one operator application (a K product of a 26k-DOF unit), not two.
#include "common/linalg/gmres.h"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace fe2 {
namespace {

struct Problem {
  Eigen::MatrixXd A;
  Vec b;
  int applications = 0;
  LinearOp op() {
    return [this](const Vec& x, Vec& y) {
      ++applications;
      y.noalias() = A * x;
    };
  }
};

Problem spd_problem(int n) {
  Problem p;
  std::srand(7);
  const Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
  p.A = R * R.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  p.b = Vec::Random(n);
  return p;
}

double true_residual(const Problem& p, const Vec& x) { return (p.b - p.A * x).norm(); }

TEST(Gmres, OneIterationFromZeroAppliesTheOperatorOnce) {
  Problem p = spd_problem(40);
  const Eigen::LLT<Eigen::MatrixXd> exact(p.A);
  const LinearOp M = [&](const Vec& x, Vec& y) { y = exact.solve(x); };
  Vec x = Vec::Zero(40);
  const double tol = 1e-10 * p.b.norm();
  const GmresResult res = gmres(p.op(), M, p.b, x, tol, 30, 100);
  EXPECT_TRUE(res.converged);
  EXPECT_EQ(res.iterations, 1);
  EXPECT_EQ(p.applications, 1);  // no second product for the true residual
  // The residual it reports is the true one: recomputed, the same to round-off.
  EXPECT_LE(true_residual(p, x), tol);
  EXPECT_NEAR(res.residual, true_residual(p, x), 1e-13 * p.b.norm());
}

TEST(Gmres, AnInexactPreconditionerStillChecksTheTrueResidual) {
  Problem p = spd_problem(40);
  const Vec d = p.A.diagonal();
  const LinearOp jacobi = [&](const Vec& x, Vec& y) { y = x.cwiseQuotient(d); };
  Vec x = Vec::Zero(40);
  const double tol = 1e-10 * p.b.norm();
  const GmresResult res = gmres(p.op(), jacobi, p.b, x, tol, 30, 200);
  ASSERT_TRUE(res.converged);
  EXPECT_GT(res.iterations, 1);
  // One product per iteration and one per cycle for the true residual: a residual
  // recurrence in its place would save it, and could stop above tol.
  const int cycles = (res.iterations + 29) / 30;
  EXPECT_EQ(p.applications, res.iterations + cycles);
  EXPECT_LE(true_residual(p, x), tol);
  EXPECT_NEAR(res.residual, true_residual(p, x), 1e-13 * p.b.norm());
}

TEST(Gmres, ANonzeroStartAppliesTheOperatorForItsResiduals) {
  Problem p = spd_problem(40);
  const Eigen::LLT<Eigen::MatrixXd> exact(p.A);
  const LinearOp M = [&](const Vec& x, Vec& y) { y = exact.solve(x); };
  Vec x = Vec::Constant(40, 0.1);  // x ≠ 0: A x₀ for r₀, and A x for the true residual
  const double tol = 1e-10 * p.b.norm();
  const GmresResult res = gmres(p.op(), M, p.b, x, tol, 30, 100);
  EXPECT_TRUE(res.converged);
  EXPECT_EQ(res.iterations, 1);
  EXPECT_EQ(p.applications, 3);
  EXPECT_LE(true_residual(p, x), tol);
}

}  // namespace
}  // namespace fe2
