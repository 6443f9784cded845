#include "coordinator/follower_pressure.h"

namespace fe2 {

namespace {
Mat3 cross_matrix(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}
}  // namespace

void follower_pressure(const std::array<Vec3, 3>& x, double p, Eigen::Matrix<double, 9, 1>& f,
                       Eigen::Matrix<double, 9, 9>& dfdx) {
  const Vec3 a = x[1] - x[0], b = x[2] - x[0];
  const Vec3 fa = -(p / 6.0) * a.cross(b);
  const Mat3 d0 = -(p / 6.0) * (cross_matrix(b) - cross_matrix(a));
  const Mat3 d1 = (p / 6.0) * cross_matrix(b);
  const Mat3 d2 = -(p / 6.0) * cross_matrix(a);
  for (int n = 0; n < 3; ++n) {
    f.segment<3>(3 * n) = fa;
    dfdx.block<3, 3>(3 * n, 0) = d0;
    dfdx.block<3, 3>(3 * n, 3) = d1;
    dfdx.block<3, 3>(3 * n, 6) = d2;
  }
}

}  // namespace fe2
