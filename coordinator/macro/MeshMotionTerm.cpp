#include "coordinator/macro/MeshMotionTerm.h"

#include "common/fem/lagrange_tet.h"
#include "common/mesh/element_quality.h"
#include "coordinator/macro/gather.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace fe2 {

MeshMotionTerm::MeshMotionTerm(const TetMesh& mesh, std::vector<int> elements, MeshMotionKind kind, double stiffening)
    : mesh_(mesh), elements_(std::move(elements)), kind_(kind), stiffening_(stiffening) {}

void MeshMotionTerm::declare(MacroSystem& system) {
  d_ = &system.field("mesh_displacement");
  // V̄ over the whole fluid (every coordinator's elements alike): the field's elements.
  double total = 0.0;
  int count = 0;
  for (int e = 0; e < mesh_.num_tets(); ++e)
    if (d_->lives_on(mesh_.region[e])) {
      total += tet_signed_volume(mesh_, e);
      ++count;
    }
  const double mean_volume = count > 0 ? total / count : 1.0;
  const double lambda = 2.0 * 0.3 / (1.0 - 2.0 * 0.3);
  const int order = mesh_.order();
  const auto rule = tet_rule(2 * (order - 1));
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  for (int e : elements_) {
    const std::vector<int> nodes = mesh_.element_nodes(e);
    const int n = static_cast<int>(nodes.size());
    const double s = std::pow(mean_volume / tet_signed_volume(mesh_, e), stiffening_);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    for (const auto& q : rule) {
      tet_shape(order, q.bary, N, dN);
      Mat3 J = Mat3::Zero();
      for (int a = 0; a < n; ++a) J += mesh_.nodes[nodes[a]] * dN.col(a).transpose();
      const double dV = s * q.weight * J.determinant();
      const Eigen::Matrix3Xd g = J.transpose().inverse() * dN;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const double gg = g.col(a).dot(g.col(b));
          if (kind_ == MeshMotionKind::harmonic) {
            K.block<3, 3>(3 * a, 3 * b).diagonal().array() += dV * gg;
          } else {  // 2ε(w):ε(d) + λ' div w div d
            K.block<3, 3>(3 * a, 3 * b) +=
                dV * (gg * Mat3::Identity() + g.col(b) * g.col(a).transpose() + lambda * g.col(a) * g.col(b).transpose());
          }
        }
    }
    dofs_.push_back(d_->node_dofs(nodes));
    stiffness_.push_back(std::move(K));
    local_.push_back(system.declare_local(dofs_.back()));
  }
}

void MeshMotionTerm::assemble(const MacroState& state, MacroAssembly& out) {
  for (size_t k = 0; k < dofs_.size(); ++k) {
    out.add_internal(dofs_[k], stiffness_[k] * gather(state.x, dofs_[k]));
    out.add_tangent(local_[k], stiffness_[k]);
  }
}

void MeshMotionTerm::observe(const MacroState& state, std::vector<Observable>& out) const {
  double worst = 1.0;
  for (int e : elements_) {
    std::array<Vec3, 4> x;
    for (int a = 0; a < 4; ++a) {
      const int node = mesh_.tets[e][a];
      x[a] = mesh_.nodes[node] + state.x.segment<3>(d_->node_dof(node));
    }
    worst = std::min(worst, tet_shape_quality(x[0], x[1], x[2], x[3]));
  }
  out.push_back({"fluid_mesh_worst_shape", worst, true});
}

}  // namespace fe2
