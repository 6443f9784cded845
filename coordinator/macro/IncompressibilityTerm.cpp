#include "coordinator/macro/IncompressibilityTerm.h"

#include "common/error.h"
#include "common/fem/lagrange_tet.h"
#include "coordinator/macro/gather.h"

#include <cmath>

namespace fe2 {

namespace {
/// The element's pressure shape functions at barycentric point λ: the P1 hats λ_a, then
/// the element's constant when the pressure is enriched (np = 5).
Eigen::VectorXd pressure_basis(const Eigen::Vector4d& bary, int np) {
  Eigen::VectorXd N(np);
  N.head<4>() = bary;
  if (np == 5) N[4] = 1.0;
  return N;
}
}  // namespace

IncompressibilityTerm::IncompressibilityTerm(const TetMesh& mesh, const MacroPoints& points,
                                             std::vector<int> owned_elements,
                                             const FormulationSpec& formulation)
    : mesh_(mesh), points_(points), owned_(std::move(owned_elements)), formulation_(formulation) {}

void IncompressibilityTerm::declare(MacroSystem& system) {
  const Field& u = system.field("displacement");
  p_ = &system.field("pressure");
  volumes_ = Eigen::VectorXd::Zero(p_->size());
  // Pressure mass on the (possibly curved) element with a degree-2 + geometry rule.
  const int order = mesh_.order();
  const auto rule = tet_rule(2 + 2 * (order - 1));
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  const double inv_kappa = std::isfinite(formulation_.bulk_modulus) ? 1.0 / formulation_.bulk_modulus : 0.0;
  const double inv_mu = formulation_.stabilization_modulus > 0 ? 1.0 / formulation_.stabilization_modulus : 0.0;
  for (int e : owned_) {
    const std::vector<int> nodes = mesh_.element_nodes(e);
    std::vector<int> dofs = u.node_dofs(nodes);
    std::vector<int> pdofs;
    for (int a = 0; a < 4; ++a) pdofs.push_back(p_->node_dof(mesh_.tets[e][a]));
    if (p_->element_dof(e) >= 0) pdofs.push_back(p_->element_dof(e));
    const int np = static_cast<int>(pdofs.size());
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(np, np);
    Eigen::VectorXd m = Eigen::VectorXd::Zero(np);
    for (const auto& q : rule) {
      tet_shape(order, q.bary, N, dN);
      Mat3 J = Mat3::Zero();
      for (size_t a = 0; a < nodes.size(); ++a) J += mesh_.nodes[nodes[a]] * dN.col(a).transpose();
      const double dV = q.weight * J.determinant();
      const Eigen::VectorXd Np = pressure_basis(q.bary, np);
      M += dV * Np * Np.transpose();
      m += dV * Np;
    }
    const double volume = m.head<4>().sum();
    // Π₀ of the stabilization: the element mean of the P1 part (the constant of an
    // enriched pressure is its own mean, untouched by the projection).
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(np, np);
    S.topLeftCorner<4, 4>() = M.topLeftCorner<4, 4>() - m.head<4>() * m.head<4>().transpose() / volume;
    pressure_matrix_.push_back(-inv_kappa * M - inv_mu * S);
    for (int a = 0; a < np; ++a) volumes_[pdofs[a] - p_->offset()] += m[a];
    dofs.insert(dofs.end(), pdofs.begin(), pdofs.end());
    local_.push_back(system.declare_local(dofs));
    dofs_.push_back(std::move(dofs));
    num_pressure_.push_back(np);
  }
}

void IncompressibilityTerm::assemble(const MacroState& state, MacroAssembly& out) {
  for (size_t k = 0; k < owned_.size(); ++k) {
    const int e = owned_[k];
    const std::vector<int>& dofs = dofs_[k];
    const int np = num_pressure_[k];
    const int nu = static_cast<int>(dofs.size()) - np;
    const Eigen::VectorXd xe = gather(state.x, dofs);
    const Eigen::VectorXd pe = xe.tail(np);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nu + np, nu + np);
    Eigen::VectorXd R = Eigen::VectorXd::Zero(nu + np);
    for (int q = points_.first_point(e); q < points_.first_point(e + 1); ++q) {
      const MacroPoint& pt = points_[q];
      const Vec9 Z = pt.B * xe.head(nu);
      const Mat3 F = Mat3::Identity() + as_mat3(Z);
      const double J = F.determinant();
      if (!(J > 0.0))
        throw NumericalError(fmt::format("macro element {} inverted at t = {:.6g} (det F̄ = {:.3e})",
                                         e, state.time, J));
      const Mat3 cof_m = J * F.inverse().transpose();
      const Vec9 cof = Eigen::Map<const Vec9>(cof_m.data());  // column-major, as Z̄
      const Eigen::VectorXd Np = pressure_basis(pt.bary, np);
      const double p = Np.dot(pe);
      Mat9 dcof;  // ∂cof_iJ/∂F_kL = (cof_iJ cof_kL − cof_iL cof_kJ)/J
      for (int i = 0; i < 3; ++i)
        for (int Jc = 0; Jc < 3; ++Jc)
          for (int kk = 0; kk < 3; ++kk)
            for (int L = 0; L < 3; ++L)
              dcof(i + 3 * Jc, kk + 3 * L) =
                  (cof_m(i, Jc) * cof_m(kk, L) - cof_m(i, L) * cof_m(kk, Jc)) / J;
      const Eigen::VectorXd Bt_cof = pt.B.transpose() * cof;
      R.head(nu) -= pt.volume * p * Bt_cof;
      R.tail(np) -= pt.volume * (J - 1.0) * Np;
      K.topLeftCorner(nu, nu).noalias() -= (pt.volume * p) * pt.B.transpose() * dcof * pt.B;
      K.topRightCorner(nu, np).noalias() -= pt.volume * Bt_cof * Np.transpose();
    }
    K.bottomLeftCorner(np, nu) = K.topRightCorner(nu, np).transpose();
    K.bottomRightCorner(np, np) = pressure_matrix_[k];
    R.tail(np) += pressure_matrix_[k] * pe;
    out.add_tangent(local_[k], K);
    out.add_internal(dofs, R);
  }
}

void IncompressibilityTerm::add_residual_scale(const Field& field, Eigen::VectorXd& scale) const {
  if (field.id() == p_->id()) scale += volumes_;
}

}  // namespace fe2
