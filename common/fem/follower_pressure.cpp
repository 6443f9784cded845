#include "common/fem/follower_pressure.h"

#include "common/error.h"
#include "common/fem/lagrange_tet.h"

namespace fe2 {

namespace {

Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

void follower_pressure(const std::vector<Vec3>& x, double p, Eigen::VectorXd& f, Eigen::MatrixXd& dfdx) {
  const int n = static_cast<int>(x.size());
  FE2_CHECK(n == 3 || n == 6, "follower pressure on a {}-node triangle (expected 3 or 6)", n);
  const int order = n == 3 ? 1 : 2;
  f = Eigen::VectorXd::Zero(3 * n);
  dfdx = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  Eigen::VectorXd N;
  Eigen::Matrix<double, 2, Eigen::Dynamic> dN;
  // N_a (degree order) × a₁ × a₂ (degree 2(order − 1)).
  for (const auto& q : triangle_rule(3 * order - 2)) {
    triangle_shape(order, q.bary, N, dN);
    Vec3 a1 = Vec3::Zero(), a2 = Vec3::Zero();
    for (int b = 0; b < n; ++b) a1 += dN(0, b) * x[b], a2 += dN(1, b) * x[b];
    const Vec3 normal = a1.cross(a2);
    const Mat3 A1 = cross_matrix(a1), A2 = cross_matrix(a2);
    for (int a = 0; a < n; ++a) {
      f.segment<3>(3 * a) -= q.weight * p * N[a] * normal;
      for (int b = 0; b < n; ++b)
        dfdx.block<3, 3>(3 * a, 3 * b) -= q.weight * p * N[a] * (dN(1, b) * A1 - dN(0, b) * A2);
    }
  }
}

}  // namespace fe2
