// The supernodal single-precision LLᵀ (worker/FloatCholeskyFactor.h) on matrices built
// here: solves agree with a double factorization to float accuracy for one and many
// right-hand sides, a refactorization replaces the old values, a badly scaled matrix
// (entries beyond float's range) is solved through the diagonal scaling, and a matrix
// that is not positive definite is refused with its leading minor.
#include "common/error.h"
#include "worker/FloatCholeskyFactor.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include <cmath>
#include <random>
#include <vector>

namespace fe2 {
namespace {

// A 3-DOF-per-node elasticity-like matrix on an m×m×m grid with 27-point coupling:
// K = Σ over grid edges of k_e (e_i − e_j)(e_i − e_j)ᵀ ⊗ B_e, plus a mass term,
// with stiffness contrast `contrast` between two halves of the grid. Symmetric positive
// definite with a fill pattern like a unit's.
SparseMatrix grid_matrix(int m, double contrast, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 1.5);
  const int nodes = m * m * m, n = 3 * nodes;
  auto id = [m](int i, int j, int k) { return (k * m + j) * m + i; };
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int a = id(i, j, k);
        for (int dk = 0; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              if (dk == 0 && (dj < 0 || (dj == 0 && di <= 0))) continue;  // each edge once
              const int ii = i + di, jj = j + dj, kk = k + dk;
              if (ii < 0 || jj < 0 || ii >= m || jj >= m || kk >= m) continue;
              const int b = id(ii, jj, kk);
              const double ke = (i < m / 2 ? contrast : 1.0) * u(rng);
              Eigen::Matrix3d B = Eigen::Matrix3d::Identity();
              const Eigen::Vector3d dir(di, dj, dk);
              B += dir * dir.transpose() / dir.squaredNorm();
              for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c) {
                  const double v = ke * B(r, c);
                  t.emplace_back(3 * a + r, 3 * a + c, v);
                  t.emplace_back(3 * b + r, 3 * b + c, v);
                  t.emplace_back(3 * a + r, 3 * b + c, -v);
                  t.emplace_back(3 * b + r, 3 * a + c, -v);
                }
            }
        for (int r = 0; r < 3; ++r) t.emplace_back(3 * a + r, 3 * a + r, 0.05);
      }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  return K;
}

Eigen::MatrixXd random_columns(Eigen::Index n, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  Eigen::MatrixXd B(n, cols);
  for (Eigen::Index i = 0; i < B.size(); ++i) B.data()[i] = g(rng);
  return B;
}

double relative_error(const Eigen::MatrixXd& X, const Eigen::MatrixXd& X_ref) {
  return (X - X_ref).norm() / X_ref.norm();
}

// K⁻¹ B by a double LDLᵀ: the reference the float factors are held to.
Eigen::MatrixXd double_solve(const SparseMatrix& K, const Eigen::MatrixXd& B) {
  Eigen::SimplicialLDLT<SparseMatrix> exact(K);
  EXPECT_EQ(exact.info(), Eigen::Success);
  return exact.solve(B);
}

TEST(FloatCholeskyFactor, SolvesToFloatAccuracyForOneAndManyRightHandSides) {
  const SparseMatrix K = grid_matrix(9, 1e3, 1);
  const Eigen::MatrixXd B = random_columns(K.rows(), 9, 2);
  const Eigen::MatrixXd X_ref = double_solve(K, B);

  auto f = make_float_cholesky_factor();
  f->factorize(K);
  EXPECT_EQ(f->name(), "supernodal_single_llt");
  Eigen::MatrixXd X(K.rows(), 9);
  f->solve(B.data(), X.data(), 9);
  const double err = relative_error(X, X_ref);
  // Float round-off (6e-8) times this matrix's condition (≈ 1e5 with the contrast):
  // a missing or misplaced descendant update errs by O(1), a double solve by 1e-12.
  EXPECT_LT(err, 1e-2);
  EXPECT_GT(err, 1e-10);
  // Column by column (the strsv/sgemv path) agrees with the block path to float accuracy.
  Eigen::MatrixXd Xc(K.rows(), 9);
  for (int c = 0; c < 9; ++c) f->solve(B.col(c).data(), Xc.col(c).data(), 1);
  EXPECT_LT(relative_error(Xc, X), 1e-4);
  EXPECT_LT(relative_error(Xc, X_ref), 1e-2);
  // In place (B and X alias).
  Eigen::MatrixXd Y = B;
  f->solve(Y.data(), Y.data(), 9);
  EXPECT_EQ(relative_error(Y, X), 0.0);
  // As a preconditioner it contracts the error by orders of magnitude per refinement step.
  Eigen::MatrixXd Xr = X;
  Eigen::MatrixXd R = B - K * Xr;
  const double r0 = R.norm() / B.norm();
  Eigen::MatrixXd D(K.rows(), 9);
  f->solve(R.data(), D.data(), 9);
  Xr += D;
  const double r1 = (B - K * Xr).norm() / B.norm();
  EXPECT_LT(r1, 1e-2 * r0) << "r0 " << r0 << " r1 " << r1;
  EXPECT_GT(f->factor_flops(), 0.0);
  EXPECT_GT(f->solve_flops(), 0.0);
  EXPECT_GT(f->factor_bytes(), 0.0);
}

// Kept in binary16 (precision "half"): the solves read the binary16 values in blocks of
// four columns, so the grid is large enough for supernodes of many blocks and ragged ends
// (its top separator has 363 columns). Coarser than float but still a preconditioner
// that contracts the error.
TEST(FloatCholeskyFactor, HalfStorageSolvesToHalfAccuracyInBlocks) {
  const SparseMatrix K = grid_matrix(11, 1e2, 11);
  const Eigen::MatrixXd B = random_columns(K.rows(), 9, 12);
  const Eigen::MatrixXd X_ref = double_solve(K, B);
  auto single = make_float_cholesky_factor();
  auto half = make_float_cholesky_factor(true);
  // Refactored once: the second factorization rebuilds the float values it released.
  half->factorize(grid_matrix(11, 10.0, 13));
  half->compact();
  half->factorize(K);
  single->factorize(K);
  EXPECT_EQ(half->name(), "supernodal_single_llt_half_storage");
  Eigen::MatrixXd Xs(K.rows(), 9), X(K.rows(), 9), Xc(K.rows(), 9);
  single->solve(B.data(), Xs.data(), 9);
  // Until compact() (the end of a unit's refresh: its χ solves) the factor is the float one.
  EXPECT_EQ(half->factor_bytes(), single->factor_bytes());
  half->solve(B.data(), X.data(), 9);
  EXPECT_EQ(X, Xs);
  half->compact();
  // Half the bytes per entry, and only the lower trapezoid of each supernode kept.
  const double bytes_ratio = half->factor_bytes() / single->factor_bytes();
  std::printf("binary16 factor bytes / float factor bytes: %.3f\n", bytes_ratio);
  EXPECT_LT(bytes_ratio, 0.5);
  EXPECT_GT(bytes_ratio, 0.3);
  half->solve(B.data(), X.data(), 9);
  for (int c = 0; c < 9; ++c) half->solve(B.col(c).data(), Xc.col(c).data(), 1);
  const double err_single = relative_error(Xs, X_ref), err = relative_error(X, X_ref);
  fmt::print("relative error: float {:.2e}, binary16 {:.2e}\n", err_single, err);
  // binary16 rounds L to 5e-4 relative: the answer moves from the float factor's by
  // about that (a factor silently kept in float would give the same bits), and stays far
  // better than a missing panel update (O(1)). (On this matrix the float answer errs by
  // 1.5e-4 already: K's condition times float's rounding of S K S.)
  EXPECT_GT(relative_error(X, Xs), 1e-5);
  EXPECT_GT(err, err_single);
  EXPECT_LT(err, 0.05);
  // Several right-hand sides are solved one at a time: the same bits as alone.
  EXPECT_EQ(Xc, X);
  // One refinement step contracts the residual at least tenfold.
  const Eigen::MatrixXd R = B - K * X;
  Eigen::MatrixXd D(K.rows(), 9);
  half->solve(R.data(), D.data(), 9);
  const double r0 = R.norm() / B.norm(), r1 = (B - K * (X + D)).norm() / B.norm();
  EXPECT_LT(r1, 0.1 * r0) << "r0 " << r0 << " r1 " << r1;
}

TEST(FloatCholeskyFactor, RefactorizationReplacesTheValues) {
  const SparseMatrix K1 = grid_matrix(7, 10.0, 3);
  const SparseMatrix K2 = grid_matrix(7, 1e2, 4);  // same pattern, other values
  ASSERT_EQ(K1.nonZeros(), K2.nonZeros());
  const Eigen::MatrixXd B = random_columns(K1.rows(), 2, 5);
  auto f = make_float_cholesky_factor();
  f->factorize(K1);
  f->factorize(K2);
  Eigen::MatrixXd X(K1.rows(), 2);
  f->solve(B.data(), X.data(), 2);
  EXPECT_LT(relative_error(X, double_solve(K2, B)), 1e-3);
}

// Entries from 1e-50 to 1e50 times a well-conditioned matrix: unscaled, the products
// overflow and underflow float (range 1e±38); with K̃ = S K S the factor is that of the
// well-conditioned matrix.
TEST(FloatCholeskyFactor, DiagonalScalingKeepsBadlyScaledMatricesInRange) {
  const SparseMatrix K0 = grid_matrix(6, 1.0, 6);
  const Eigen::Index n = K0.rows();
  Eigen::VectorXd d(n);
  for (Eigen::Index i = 0; i < n; ++i) d[i] = std::pow(10.0, -25.0 + 50.0 * double(i % 7) / 6.0);
  SparseMatrix K = K0;
  for (int k = 0; k < K.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(K, k); it; ++it) it.valueRef() *= d[it.row()] * d[it.col()];
  const Eigen::MatrixXd B = random_columns(n, 3, 7);
  Eigen::SimplicialLDLT<SparseMatrix> exact(K);
  ASSERT_EQ(exact.info(), Eigen::Success);
  auto f = make_float_cholesky_factor();
  f->factorize(K);
  Eigen::MatrixXd X(n, 3);
  f->solve(B.data(), X.data(), 3);
  // Compared in the scaled unknowns, where all components are of one size.
  const Eigen::MatrixXd ref = d.asDiagonal() * exact.solve(B);
  EXPECT_LT(relative_error(d.asDiagonal() * X, ref), 1e-3);
  // Right-hand sides beyond float's range are normalised before they are rounded.
  for (const double size : {1e45, 1e-45}) {
    const Eigen::MatrixXd Bs = size * B;
    Eigen::MatrixXd Xs(n, 3);
    f->solve(Bs.data(), Xs.data(), 3);
    EXPECT_LT(relative_error(d.asDiagonal() * Xs, size * ref), 1e-3) << size;
  }
}

// The NumericalError factorizing K throws ("factored" if none); the factor must not be
// left ready.
std::string refusal(const SparseMatrix& K) {
  auto f = make_float_cholesky_factor();
  try {
    f->factorize(K);
  } catch (const NumericalError& e) {
    EXPECT_FALSE(f->ready());
    return e.what();
  }
  return "factored";
}

TEST(FloatCholeskyFactor, NonFiniteEntriesAreRefusedNamingTheEntry) {
  SparseMatrix K = grid_matrix(4, 1.0, 10);
  K.coeffRef(7, 4) = std::nan("");
  const std::string e = refusal(K);
  EXPECT_NE(e.find("entry (7, 4) = nan"), std::string::npos) << e;
}

TEST(FloatCholeskyFactor, NotPositiveDefiniteIsRefusedNamingTheMinor) {
  SparseMatrix K = grid_matrix(5, 1.0, 8);
  // Make the 3×3 block of node 10 indefinite: a negative pivot appears while factoring.
  for (int r = 30; r < 33; ++r) K.coeffRef(r, r) = -50.0;
  std::string e = refusal(K);
  EXPECT_NE(e.find("diagonal entry 30"), std::string::npos) << e;
  // Positive diagonal but indefinite: the breakdown is found by spotrf.
  SparseMatrix J = grid_matrix(5, 1.0, 9);
  for (int k = 0; k < J.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(J, k); it; ++it)
      if (it.row() != it.col()) it.valueRef() *= -3.0;
  e = refusal(J);
  EXPECT_NE(e.find("leading minor"), std::string::npos) << e;
  EXPECT_NE(e.find("at DOF"), std::string::npos) << e;
}

TEST(FloatCholeskyFactor, AChangedPatternIsRefused) {
  const SparseMatrix K = grid_matrix(4, 1.0, 11);
  SparseMatrix K2 = K;
  K2.coeffRef(0, K.cols() - 1) = 0.0;  // a new entry, upper triangle only: nnz + 1
  K2.makeCompressed();
  auto f = make_float_cholesky_factor();
  f->factorize(K);
  EXPECT_THROW(f->factorize(K2), Error);
  EXPECT_TRUE(f->ready());  // refused before anything is overwritten: K's factor stays
  f->factorize(K);          // and the analysis is intact
  EXPECT_TRUE(f->ready());
}

}  // namespace
}  // namespace fe2
