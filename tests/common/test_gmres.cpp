// GMRES (common/linalg/gmres.h): the true-residual test, and how many times it applies
// the operator. A Step 1 solve on a fresh factor converges in one iteration; the true
// residual after that iteration is y₀·(A z₀), the product the iteration already made,
// so the solve costs one operator application (a K product of a 26k-DOF unit), not two.
#include "common/linalg/gmres.h"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <memory>

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

/// Solves p from x to 1e-10·‖b‖ with preconditioner M; checks it converged to a true
/// residual under the tolerance and reported that residual (recomputed, to round-off).
GmresResult solve_and_check(Problem& p, const LinearOp& M, Vec& x) {
  const double tol = 1e-10 * p.b.norm();
  const GmresResult res = gmres(p.op(), M, p.b, x, tol, 30, 200);
  EXPECT_TRUE(res.converged);
  EXPECT_LE(true_residual(p, x), tol);
  EXPECT_NEAR(res.residual, true_residual(p, x), 1e-13 * p.b.norm());
  return res;
}

LinearOp exact_inverse(const Problem& p) {
  auto llt = std::make_shared<const Eigen::LLT<Eigen::MatrixXd>>(p.A);
  return [llt](const Vec& x, Vec& y) { y = llt->solve(x); };
}

TEST(Gmres, OneIterationFromZeroAppliesTheOperatorOnce) {
  Problem p = spd_problem(40);
  Vec x = Vec::Zero(40);
  const GmresResult res = solve_and_check(p, exact_inverse(p), x);
  EXPECT_EQ(res.iterations, 1);
  EXPECT_EQ(p.applications, 1);  // no second product for the true residual
}

TEST(Gmres, AnInexactPreconditionerStillChecksTheTrueResidual) {
  Problem p = spd_problem(40);
  const Vec d = p.A.diagonal();
  const LinearOp jacobi = [&](const Vec& x, Vec& y) { y = x.cwiseQuotient(d); };
  Vec x = Vec::Zero(40);
  const GmresResult res = solve_and_check(p, jacobi, x);
  EXPECT_GT(res.iterations, 1);
  // One product per iteration and one per cycle for the true residual: a residual
  // recurrence in its place would save it, and could stop above tol.
  const int cycles = (res.iterations + 29) / 30;
  EXPECT_EQ(p.applications, res.iterations + cycles);
}

TEST(Gmres, ANonzeroStartAppliesTheOperatorForItsResiduals) {
  Problem p = spd_problem(40);
  Vec x = Vec::Constant(40, 0.1);  // x ≠ 0: A x₀ for r₀, and A x for the true residual
  const GmresResult res = solve_and_check(p, exact_inverse(p), x);
  EXPECT_EQ(res.iterations, 1);
  EXPECT_EQ(p.applications, 3);
}

}  // namespace
}  // namespace fe2
