// |K| products (worker/abs_products.h), from which a unit's residual floor is made:
// the row sums of |K| taken as column sums must equal the row sums whenever the unit
// calls K symmetric, so the assembly must make K symmetric (to round-off: the element's
// diagonal blocks are summed in different orders for (a, b) and (b, a)).
#include "unit_fixtures.h"
#include "worker/MicroUnit.h"
#include "worker/abs_products.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace fe2 {
namespace {

SparseMatrix random_sparse(int n, bool symmetric) {
  std::srand(11);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      if ((i * 7 + j * 3) % 5 != 0 && i != j) continue;
      const double v = Eigen::VectorXd::Random(1)[0] * (1 + i % 4);
      t.emplace_back(i, j, v);
      if (symmetric && i != j) t.emplace_back(j, i, v);
    }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

Vec dense_abs_row_sums(const SparseMatrix& K) {
  return Eigen::MatrixXd(K).cwiseAbs().rowwise().sum();
}

TEST(AbsProducts, RowSumsOfASymmetricMatrixAreItsColumnSums) {
  const SparseMatrix K = random_sparse(60, true);
  ASSERT_EQ((Eigen::MatrixXd(K) - Eigen::MatrixXd(K).transpose()).norm(), 0.0);
  const Vec expected = dense_abs_row_sums(K);
  EXPECT_LE((abs_row_sums(K, true) - expected).norm(), 1e-14 * expected.norm());
  EXPECT_LE((abs_times(K, Vec::Ones(60)) - expected).norm(), 1e-14 * expected.norm());
}

TEST(AbsProducts, AnUnsymmetricMatrixGetsItsRowSums) {
  const SparseMatrix K = random_sparse(60, false);
  const Vec expected = dense_abs_row_sums(K);
  const Vec column_sums = Eigen::MatrixXd(K).cwiseAbs().colwise().sum().transpose();
  ASSERT_GT((column_sums - expected).norm(), 0.1 * expected.norm());  // the two differ here
  EXPECT_LE((abs_row_sums(K, false) - expected).norm(), 1e-14 * expected.norm());
}

TEST(AbsProducts, AbsTimesTakesAbsoluteValuesOfTheVector) {
  const SparseMatrix K = random_sparse(30, false);
  const Vec v = Vec::Random(30);
  const Vec expected = Eigen::MatrixXd(K).cwiseAbs() * v.cwiseAbs();
  EXPECT_LE((abs_times(K, v) - expected).norm(), 1e-14 * expected.norm());
}

TEST(AbsProducts, ASymmetricUnitAssemblesASymmetricK) {
  // The residual floor takes |K|'s row sums as column sums when the model is symmetric.
  MicroUnit unit(test::two_cell_model({}));
  ASSERT_TRUE(unit.model().symmetric());
  proto::JobInput in;
  in.step = 0;
  in.iteration = 1;
  in.Zbar = test::gradient({0.05, 0.02, -0.01, 0.0, -0.02, 0.01, 0.03, 0.0, 0.01});
  unit.iterate(in);
  in.apply_update = 1;
  in.iteration = 2;
  unit.iterate(in);  // w ≠ 0: a deformed, heterogeneous state
  const SparseMatrix& K = unit.system().K;
  const SparseMatrix Kt = K.transpose();
  EXPECT_GT(K.norm(), 0.0);
  EXPECT_LE((K - Kt).norm(), 1e-14 * K.norm());
  const Vec rows = abs_row_sums(K, false), columns = abs_row_sums(K, true);
  EXPECT_LE((rows - columns).norm(), 1e-14 * rows.norm());
}

TEST(AbsProducts, TheFusedProductGivesTheSameBitsAsTheSeparateOnes) {
  for (const bool symmetric : {true, false}) {
    const SparseMatrix K = random_sparse(50, symmetric);
    const Vec x = Vec::LinSpaced(50, -1.0, 2.0);
    Vec y, sums;
    times_and_abs_row_sums(K, x, y, sums, symmetric);
    const Vec y_eigen = K * x;
    EXPECT_TRUE(y == y_eigen) << "symmetric " << symmetric;
    EXPECT_TRUE(sums == abs_row_sums(K, symmetric)) << "symmetric " << symmetric;
  }
}

TEST(AbsProducts, EachIterationsResidualFloorIsOfItsOwnK) {
  // The floor's |K|𝟙 comes from Step 1's first product: after a new assembly it must be
  // that of the new K, not the last one's. States far apart, so the floors differ.
  MicroUnit unit(test::two_cell_model({}));
  proto::JobInput in;
  in.step = 0;
  in.iteration = 1;
  const auto expected_floor = [&] {
    const MicroModel& m = unit.model();
    const double h = std::cbrt(1.0 / (m.inv_volume() * m.num_elements()));
    const double nodes_moved =
        std::numeric_limits<double>::epsilon() * (1.0 + unit.Zbar().norm()) * h;
    return nodes_moved * abs_row_sums(unit.system().K, m.symmetric()).norm();
  };
  in.Zbar = test::gradient({0.01, 0, 0, 0, 0, 0, 0, 0, 0});
  const double first = unit.iterate(in).r_floor;
  EXPECT_EQ(first, expected_floor());
  in.Zbar = test::gradient({0.3, 0.05, 0, 0, -0.1, 0, 0, 0, -0.1});
  in.iteration = 2;
  const double second = unit.iterate(in).r_floor;
  EXPECT_EQ(second, expected_floor());
  EXPECT_GT(std::abs(second - first), 1e-3 * first);
}

}  // namespace
}  // namespace fe2
