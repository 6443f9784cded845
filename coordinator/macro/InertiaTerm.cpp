#include "coordinator/macro/InertiaTerm.h"

#include "common/fem/lagrange_tet.h"
#include "coordinator/macro/gather.h"

namespace fe2 {

InertiaTerm::InertiaTerm(const TetMesh& mesh, std::vector<int> owned_elements, double density)
    : mesh_(mesh), owned_(std::move(owned_elements)) {
  const int order = mesh.order();
  const auto rule = tet_rule(2 * order);
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  for (int e : owned_) {
    const std::vector<int> nodes = mesh.element_nodes(e);
    const int n = static_cast<int>(nodes.size());
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
    for (const auto& q : rule) {
      tet_shape(order, q.bary, N, dN);
      Mat3 J = Mat3::Zero();
      for (int a = 0; a < n; ++a) J += mesh.nodes[nodes[a]] * dN.col(a).transpose();
      M.noalias() += (density * q.weight * J.determinant()) * N * N.transpose();
    }
    mass_.push_back(std::move(M));
  }
}

void InertiaTerm::declare(MacroSystem& system) {
  u_ = &system.field("displacement");
  for (int e : owned_) {
    dofs_.push_back(u_->node_dofs(mesh_.element_nodes(e)));
    local_.push_back(system.declare_local(dofs_.back()));
  }
}

void InertiaTerm::assemble(const MacroState& state, MacroAssembly& out) {
  const double da_du = state.rate(*u_).da_dx;
  for (size_t k = 0; k < owned_.size(); ++k) {
    const Eigen::MatrixXd& M = mass_[k];
    const int n = static_cast<int>(M.rows());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) K.block<3, 3>(3 * a, 3 * b).diagonal().setConstant(M(a, b));
    const Eigen::VectorXd f = K * gather(state.a, dofs_[k]);  // M ṻ
    out.add_tangent(local_[k], da_du * K);
    out.add_internal(dofs_[k], f);
  }
}

void InertiaTerm::observe(const MacroState& state, std::vector<Observable>& out) const {
  double kinetic = 0.0;
  for (size_t k = 0; k < owned_.size(); ++k) {
    const Eigen::VectorXd v = gather(state.v, dofs_[k]);  // node-major (x, y, z)
    const Eigen::Map<const Eigen::Matrix3Xd> V(v.data(), 3, v.size() / 3);
    kinetic += 0.5 * (V * mass_[k] * V.transpose()).trace();  // ½ Σ_ab M_ab v_a·v_b
  }
  out.push_back({"wall_kinetic_energy", kinetic});
}

}  // namespace fe2
