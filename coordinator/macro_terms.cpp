#include "coordinator/macro_terms.h"

#include "common/error.h"
#include "common/fem/lagrange_tet.h"
#include "coordinator/follower_pressure.h"

namespace fe2 {

std::vector<int> displacement_dofs(const std::vector<int>& nodes) {
  std::vector<int> dofs;
  dofs.reserve(3 * nodes.size());
  for (int a : nodes)
    for (int i = 0; i < 3; ++i) dofs.push_back(3 * a + i);
  return dofs;
}

namespace {

Eigen::VectorXd gather(const Eigen::VectorXd& x, const std::vector<int>& dofs) {
  Eigen::VectorXd v(dofs.size());
  for (size_t k = 0; k < dofs.size(); ++k) v[k] = x[dofs[k]];
  return v;
}

}  // namespace

// ---------------------------------------------------------------------------------
PointStressTerm::PointStressTerm(const TetMesh& mesh, const MacroPoints& points,
                                 std::vector<int> owned_elements,
                                 const std::vector<PointResponse>& responses)
    : mesh_(mesh), points_(points), owned_(std::move(owned_elements)), responses_(responses) {}

void PointStressTerm::declare(MacroSystem& system) {
  for (int e : owned_) {
    dofs_.push_back(displacement_dofs(mesh_.element_nodes(e)));
    block_.push_back(system.declare_block(dofs_.back()));
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
    out.add_tangent(block_[k], K);
    out.add_internal(dofs_[k], f, f_tilde);
  }
}

// ---------------------------------------------------------------------------------
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
  for (int e : owned_) {
    dofs_.push_back(displacement_dofs(mesh_.element_nodes(e)));
    block_.push_back(system.declare_block(dofs_.back()));
  }
}

void InertiaTerm::assemble(const MacroState& state, MacroAssembly& out) {
  for (size_t k = 0; k < owned_.size(); ++k) {
    const Eigen::MatrixXd& M = mass_[k];
    const int n = static_cast<int>(M.rows());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * n, 3 * n);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) K.block<3, 3>(3 * a, 3 * b).diagonal().setConstant(M(a, b));
    const Eigen::VectorXd f = K * gather(state.a, dofs_[k]);  // M ṻ
    out.add_tangent(block_[k], state.c_mass * K);
    out.add_internal(dofs_[k], f);
  }
}

// ---------------------------------------------------------------------------------
FollowerPressureTerm::FollowerPressureTerm(const RunSpec& spec, int part, int parts) : spec_(spec) {
  int k = 0;
  for (size_t p = 0; p < spec.pressure.size(); ++p)
    for (const auto& tri : spec.mesh.faces.at(spec.pressure[p].surface))
      if (k++ % parts == part) faces_.push_back({spec.mesh.face_nodes(tri), static_cast<int>(p)});
}

void FollowerPressureTerm::declare(MacroSystem& system) {
  for (const Face& f : faces_) {
    dofs_.push_back(displacement_dofs(f.nodes));
    block_.push_back(system.declare_block(dofs_.back()));
  }
}

void FollowerPressureTerm::assemble(const MacroState& state, MacroAssembly& out) {
  Eigen::VectorXd f;
  Eigen::MatrixXd dfdx;
  std::vector<Vec3> x;
  for (size_t k = 0; k < faces_.size(); ++k) {
    const PressureSpec& ps = spec_.pressure[faces_[k].load];
    const double p = ps.value * ramp_factor(ps.ramp, state.time, spec_.t_end);
    x.clear();
    for (int a : faces_[k].nodes) x.push_back(spec_.mesh.nodes[a] + state.x.segment<3>(3 * a));
    follower_pressure(x, p, f, dfdx);
    out.add_tangent(block_[k], -dfdx);  // R = f_int − f_ext: K gets −∂f_ext/∂ū
    out.add_external(dofs_[k], f);
  }
}

// ---------------------------------------------------------------------------------
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
  FE2_CHECK(system.has_pressure(), "the incompressibility term needs a pressure field");
  system_ = &system;
  volumes_ = Eigen::VectorXd::Zero(system.num_pressure());
  // Pressure mass on the (possibly curved) element with a degree-2 + geometry rule.
  const int order = mesh_.order();
  const auto rule = tet_rule(2 + 2 * (order - 1));
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  const double inv_kappa = std::isfinite(formulation_.bulk_modulus) ? 1.0 / formulation_.bulk_modulus : 0.0;
  const double inv_mu = formulation_.stabilization_modulus > 0 ? 1.0 / formulation_.stabilization_modulus : 0.0;
  for (int e : owned_) {
    const std::vector<int> nodes = mesh_.element_nodes(e);
    std::vector<int> dofs = displacement_dofs(nodes);
    std::vector<int> pdofs;
    for (int a = 0; a < 4; ++a) pdofs.push_back(system.pressure_dof(mesh_.tets[e][a]));
    if (system.element_pressure_dof(e) >= 0) pdofs.push_back(system.element_pressure_dof(e));
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
    for (int a = 0; a < np; ++a) volumes_[pdofs[a] - system.pressure_offset()] += m[a];
    dofs.insert(dofs.end(), pdofs.begin(), pdofs.end());
    block_.push_back(system.declare_block(dofs));
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
    out.add_tangent(block_[k], K);
    out.add_internal(dofs, R);
  }
}

}  // namespace fe2
