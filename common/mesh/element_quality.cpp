#include "common/mesh/element_quality.h"

#include "common/fem/lagrange_tet.h"

#include "common/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fe2 {

namespace {

/// det J at barycentric point λ of element e with nodes X (in element_nodes order).
double det_J(int order, const std::vector<Vec3>& X, const Vec4& bary) {
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  tet_shape(order, bary, N, dN);
  Mat3 J = Mat3::Zero();
  for (size_t a = 0; a < X.size(); ++a) J += X[a] * dN.col(static_cast<Eigen::Index>(a)).transpose();
  return J.determinant();
}

}  // namespace

ElementQuality element_quality(const TetMesh& m, int e) {
  ElementQuality q;
  q.element = e;
  const std::vector<int> nodes = m.element_nodes(e);
  std::vector<Vec3> X;
  for (int a : nodes) X.push_back(m.nodes[a]);
  for (int a = 0; a < 4; ++a) q.centroid += 0.25 * m.nodes[m.tets[e][a]];
  q.min_det_J = std::numeric_limits<double>::infinity();
  q.max_det_J = -std::numeric_limits<double>::infinity();
  // The order-4 lattice: λ = (i, j, k, l)/4 with i + j + k + l = 4.
  constexpr int n = 4;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j)
      for (int k = 0; i + j + k <= n; ++k) {
        const Vec4 bary(i, j, k, n - i - j - k);
        const double d = det_J(m.order(), X, bary / n);
        q.min_det_J = std::min(q.min_det_J, d);
        q.max_det_J = std::max(q.max_det_J, d);
      }
  q.jacobian_ratio = q.max_det_J > 0.0 ? q.min_det_J / q.max_det_J : -1.0;
  const auto& t = m.tets[e];
  q.shape = tet_shape_quality(m.nodes[t[0]], m.nodes[t[1]], m.nodes[t[2]], m.nodes[t[3]]);
  return q;
}

double tet_shape_quality(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const std::array<Vec3, 4> x = {x0, x1, x2, x3};
  double l2 = 0.0;
  for (const auto& edge : kTetEdges) l2 += (x[edge[1]] - x[edge[0]]).squaredNorm();
  const double l_rms = std::sqrt(l2 / 6.0);
  const double volume = (x1 - x0).dot((x2 - x0).cross(x3 - x0)) / 6.0;
  return 6.0 * std::sqrt(2.0) * volume / (l_rms * l_rms * l_rms);
}

std::string describe(const ElementQuality& q) {
  return fmt::format("element {} (centroid ({:.3g}, {:.3g}, {:.3g}), Jacobian ratio min/max det J = {:.3g}, "
                     "shape 6√2 V/l³ = {:.3g})",
                     q.element, q.centroid[0], q.centroid[1], q.centroid[2], q.jacobian_ratio, q.shape);
}

ElementQuality worst_element(const TetMesh& m) {
  ElementQuality worst;
  worst.jacobian_ratio = std::numeric_limits<double>::infinity();
  for (int e = 0; e < m.num_tets(); ++e) {
    const ElementQuality q = element_quality(m, e);
    if (q.jacobian_ratio < worst.jacobian_ratio ||
        (q.jacobian_ratio == worst.jacobian_ratio && q.shape < worst.shape))
      worst = q;
  }
  return worst;
}

}  // namespace fe2
