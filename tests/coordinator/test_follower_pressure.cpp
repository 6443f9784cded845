// The follower-pressure force and tangent on linear and quadratic (curved) triangles.
#include "common/fem/follower_pressure.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

Eigen::MatrixXd finite_difference_tangent(const std::vector<Vec3>& x, double p) {
  const int n = static_cast<int>(x.size());
  const double h = 1e-6;
  Eigen::VectorXd fp, fm;
  Eigen::MatrixXd unused, fd(3 * n, 3 * n);
  for (int c = 0; c < 3 * n; ++c) {
    auto xp = x, xm = x;
    xp[c / 3][c % 3] += h;
    xm[c / 3][c % 3] -= h;
    follower_pressure(xp, p, fp, unused);
    follower_pressure(xm, p, fm, unused);
    fd.col(c) = (fp - fm) / (2 * h);
  }
  return fd;
}

TEST(FollowerPressure, LinearTriangleForceAndTangent) {
  const std::vector<Vec3> x = {Vec3(0.1, 0.0, 0.2), Vec3(1.2, 0.1, -0.1), Vec3(0.3, 0.9, 0.4)};
  const double p = 250.0;
  Eigen::VectorXd f;
  Eigen::MatrixXd K;
  follower_pressure(x, p, f, K);
  const Eigen::MatrixXd fd = finite_difference_tangent(x, p);
  EXPECT_LT((K - fd).norm() / fd.norm(), 1e-8);
  // Each node carries a third of −p × area × normal; the tangent is not symmetric.
  const Vec3 n2 = (x[1] - x[0]).cross(x[2] - x[0]);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR((f.segment<3>(3 * a) + p * n2 / 6.0).norm(), 0.0, 1e-10);
  EXPECT_GT((K - K.transpose()).norm(), 1e-3 * K.norm());
}

TEST(FollowerPressure, QuadraticTriangleForceAndTangent) {
  // Flat with edge nodes at midpoints: the total force is −p A n, carried by the edge
  // nodes alone (∫ of a vertex's P2 function over a triangle is 0).
  const std::vector<Vec3> v = {Vec3(0.1, 0.0, 0.2), Vec3(1.2, 0.1, -0.1), Vec3(0.3, 0.9, 0.4)};
  std::vector<Vec3> x = v;
  for (int k = 0; k < 3; ++k) x.push_back(0.5 * (v[k] + v[(k + 1) % 3]));
  const double p = 250.0;
  Eigen::VectorXd f;
  Eigen::MatrixXd K;
  follower_pressure(x, p, f, K);
  const Vec3 n2 = (v[1] - v[0]).cross(v[2] - v[0]);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(f.segment<3>(3 * a).norm(), 0.0, 1e-10);
  for (int a = 3; a < 6; ++a) EXPECT_NEAR((f.segment<3>(3 * a) + p * n2 / 6.0).norm(), 0.0, 1e-10);
  // Curved: move the edge nodes off the plane; the tangent stays consistent.
  x[3] += Vec3(0.05, -0.02, 0.1);
  x[4] += Vec3(-0.03, 0.04, 0.08);
  x[5] += Vec3(0.02, 0.01, -0.06);
  follower_pressure(x, p, f, K);
  const Eigen::MatrixXd fd = finite_difference_tangent(x, p);
  EXPECT_LT((K - fd).norm() / fd.norm(), 1e-8);
}

}  // namespace
}  // namespace fe2
