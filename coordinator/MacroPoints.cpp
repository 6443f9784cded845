#include "coordinator/MacroPoints.h"

#include "common/error.h"
#include "common/fem/lagrange_tet.h"

namespace fe2 {

MacroPoints::MacroPoints(const TetMesh& mesh, int degree, const std::vector<int>& elements) {
  const int order = mesh.order();
  degree_ = degree < 0 ? default_point_degree(order) : degree;
  const auto rule = tet_rule(degree_);
  per_element_ = static_cast<int>(rule.size());
  const int ne = mesh.num_tets();
  std::vector<char> has_points(static_cast<size_t>(ne), elements.empty() ? 1 : 0);
  for (int e : elements) has_points[static_cast<size_t>(e)] = 1;
  first_.resize(ne + 1);
  points_.reserve(static_cast<size_t>(ne) * rule.size());
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  for (int e = 0; e < ne; ++e) {
    first_[e] = size();
    if (!has_points[static_cast<size_t>(e)]) continue;
    const std::vector<int> nodes = mesh.element_nodes(e);
    const int n = static_cast<int>(nodes.size());
    for (const auto& q : rule) {
      tet_shape(order, q.bary, N, dN);
      Mat3 J = Mat3::Zero();  // J_iα = Σ_a X_ai ∂N_a/∂ξ_α
      MacroPoint p;
      p.element = e;
      for (int a = 0; a < n; ++a) {
        J += mesh.nodes[nodes[a]] * dN.col(a).transpose();
        p.X += N[a] * mesh.nodes[nodes[a]];
      }
      const double det = J.determinant();
      if (!(det > 0.0))
        throw InputError(fmt::format("mesh: element {} has Jacobian determinant {:.3e} at a quadrature "
                                     "point, expected > 0 (a curved element folded over itself)",
                                     e, det));
      const Eigen::Matrix<double, 3, Eigen::Dynamic> grad = J.transpose().inverse() * dN;
      p.N = N;
      p.bary = q.bary;
      p.volume = q.weight * det;
      p.B.setZero(9, 3 * n);
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < 3; ++i)
          for (int Jc = 0; Jc < 3; ++Jc) p.B(i + 3 * Jc, 3 * a + i) = grad(Jc, a);
      points_.push_back(std::move(p));
    }
  }
  first_[ne] = size();
}

std::vector<int> MacroPoints::points_of(const std::vector<int>& elements) const {
  std::vector<int> out;
  for (int e : elements)
    for (int k = first_[e]; k < first_[e + 1]; ++k) out.push_back(k);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace fe2
