// The follower-pressure tangent against central differences of its force.
#include "coordinator/follower_pressure.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

TEST(FollowerPressure, TangentMatchesFiniteDifferences) {
  std::array<Vec3, 3> x = {Vec3(0.1, 0.0, 0.2), Vec3(1.2, 0.1, -0.1), Vec3(0.3, 0.9, 0.4)};
  const double p = 250.0;
  Eigen::Matrix<double, 9, 1> f, fp, fm;
  Eigen::Matrix<double, 9, 9> K, unused;
  follower_pressure(x, p, f, K);
  const double h = 1e-6;
  Eigen::Matrix<double, 9, 9> fd;
  for (int c = 0; c < 9; ++c) {
    auto xp = x, xm = x;
    xp[c / 3][c % 3] += h;
    xm[c / 3][c % 3] -= h;
    follower_pressure(xp, p, fp, unused);
    follower_pressure(xm, p, fm, unused);
    fd.col(c) = (fp - fm) / (2 * h);
  }
  EXPECT_LT((K - fd).norm() / fd.norm(), 1e-8);
  // Total force is −p × area × normal; the tangent is not symmetric.
  const Vec3 n2 = (x[1] - x[0]).cross(x[2] - x[0]);
  EXPECT_NEAR((f.segment<3>(0) + f.segment<3>(3) + f.segment<3>(6) + p * 0.5 * n2).norm(), 0.0, 1e-10);
  EXPECT_GT((K - K.transpose()).norm(), 1e-3 * K.norm());
}

}  // namespace
}  // namespace fe2
