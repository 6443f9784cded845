#include "coordinator/macro/PointStressTerm.h"

namespace fe2 {

PointStressTerm::PointStressTerm(const TetMesh& mesh, const MacroPoints& points,
                                 std::vector<int> owned_elements,
                                 const std::vector<PointResponse>& responses)
    : mesh_(mesh), points_(points), owned_(std::move(owned_elements)), responses_(responses) {}

void PointStressTerm::declare(MacroSystem& system) {
  const Field& u = system.field("displacement");
  for (int e : owned_) {
    dofs_.push_back(u.node_dofs(mesh_.element_nodes(e)));
    local_.push_back(system.declare_local(dofs_.back()));
  }
}

void PointStressTerm::assemble(const MacroState&, MacroAssembly& out) {
  size_t slot = 0;  // owned points are the owned elements' points, in order
  for (size_t k = 0; k < owned_.size(); ++k) {
    const int e = owned_[k];
    const int n = static_cast<int>(dofs_[k].size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n), f_tilde = Eigen::VectorXd::Zero(n);
    for (int q = points_.first_point(e); q < points_.first_point(e + 1); ++q, ++slot) {
      const MacroPoint& p = points_[q];
      const PointResponse& r = responses_[slot];
      K.noalias() += p.volume * p.B.transpose() * r.A * p.B;  // |ē_k| B̄ᵀ 𝔸_hom B̄
      f.noalias() += p.volume * p.B.transpose() * r.P_bar;
      f_tilde.noalias() += p.volume * p.B.transpose() * r.P_tilde;
    }
    out.add_tangent(local_[k], K);
    out.add_internal(dofs_[k], f, f_tilde);
  }
}

}  // namespace fe2
