#include "common/fem/vertex_volumes.h"

#include "common/fem/lagrange_tet.h"

namespace fe2 {

Eigen::Vector4d vertex_volumes(const TetMesh& mesh, int element) {
  const int order = mesh.order();
  const std::vector<int> nodes = mesh.element_nodes(element);
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  Eigen::Vector4d m = Eigen::Vector4d::Zero();
  for (const auto& q : tet_rule(1 + 3 * (order - 1))) {  // λ_b det J: degree 1 + 3(k − 1)
    tet_shape(order, q.bary, N, dN);
    Mat3 J = Mat3::Zero();
    for (size_t a = 0; a < nodes.size(); ++a) J += mesh.nodes[nodes[a]] * dN.col(static_cast<Eigen::Index>(a)).transpose();
    m += q.weight * J.determinant() * q.bary;
  }
  return m;
}

}  // namespace fe2
