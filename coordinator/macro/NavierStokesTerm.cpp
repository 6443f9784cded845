#include "coordinator/macro/NavierStokesTerm.h"

#include "common/error.h"
#include "common/fem/lagrange_tet.h"
#include "common/fem/vertex_volumes.h"

namespace fe2 {

NavierStokesTerm::NavierStokesTerm(const TetMesh& mesh, std::vector<int> elements, FluidElementKind kind,
                                   ConvectiveForm convection, NewtonianFluid fluid, Vec3 body_force,
                                   double residual_pressure, bool shape_derivatives)
    : mesh_(mesh), elements_(std::move(elements)), kind_(kind), convection_(convection), fluid_(fluid),
      body_force_(body_force),
      residual_pressure_(residual_pressure), shape_derivatives_(shape_derivatives) {}

void NavierStokesTerm::declare(MacroSystem& system) {
  v_ = &system.field("fluid_velocity");
  p_ = &system.field("fluid_pressure");
  d_ = system.fields().find("mesh_displacement");
  for (int e : elements_) {
    nodes_.push_back(mesh_.element_nodes(e));
    std::vector<int> dofs = v_->node_dofs(nodes_.back());
    const std::vector<int> vertices(mesh_.tets[e].begin(), mesh_.tets[e].end());
    const std::vector<int> p = p_->node_dofs(vertices);
    dofs.insert(dofs.end(), p.begin(), p.end());
    if (shape_derivatives_ && d_) {
      // Columns v, p, then d at every node (the mesh moves on the whole fluid).
      std::vector<int> columns = dofs;
      mesh_dofs_.push_back(d_->node_dofs(nodes_.back()));
      columns.insert(columns.end(), mesh_dofs_.back().begin(), mesh_dofs_.back().end());
      local_.push_back(system.declare_local(dofs, columns));
    } else {
      local_.push_back(system.declare_local(dofs));
    }
    dofs_.push_back(std::move(dofs));
  }
}

void NavierStokesTerm::add_residual_scale(const Field& field, Eigen::VectorXd& scale) const {
  if (field.id() == v_->id()) {
    const int order = mesh_.order();
    Eigen::VectorXd N;
    Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
    for (size_t k = 0; k < elements_.size(); ++k) {
      const std::vector<int>& nodes = nodes_[k];
      for (const auto& q : tet_rule(2 * (order - 1))) {
        tet_shape(order, q.bary, N, dN);
        Mat3 J = Mat3::Zero();
        for (size_t a = 0; a < nodes.size(); ++a) J += mesh_.nodes[nodes[a]] * dN.col(static_cast<Eigen::Index>(a)).transpose();
        const Eigen::Matrix3Xd g = (J.transpose().inverse() * dN).cwiseAbs();
        for (size_t a = 0; a < nodes.size(); ++a)
          scale.segment<3>(v_->node_dof(nodes[a]) - field.offset()) +=
              residual_pressure_ * q.weight * J.determinant() * g.col(static_cast<Eigen::Index>(a));
      }
    }
    return;
  }
  if (field.id() != p_->id()) return;
  for (size_t k = 0; k < elements_.size(); ++k) {
    const Eigen::Vector4d m = vertex_volumes(mesh_, elements_[k]);
    for (int b = 0; b < 4; ++b) scale[dofs_[k][dofs_[k].size() - 4 + b] - field.offset()] += m[b];
  }
}

void NavierStokesTerm::gather_element(size_t k, const MacroState& state, FluidElementState& s) const {
  const std::vector<int>& nodes = nodes_[k];
  const int n = static_cast<int>(nodes.size());
  s.x.resize(3, n);
  s.v.resize(3, n);
  s.v_rate.resize(3, n);
  s.w.resize(3, n);
  for (int a = 0; a < n; ++a) {
    const int dof = v_->node_dof(nodes[a]);
    s.v.col(a) = state.x.segment<3>(dof);
    s.v_rate.col(a) = state.v.segment<3>(dof);
    s.x.col(a) = mesh_.nodes[nodes[a]];
    s.w.col(a).setZero();
    if (d_ && d_->has_node(nodes[a])) {
      const int m = d_->node_dof(nodes[a]);
      s.x.col(a) += state.x.segment<3>(m);
      s.w.col(a) = state.v.segment<3>(m);
    }
  }
  for (int b = 0; b < 4; ++b) s.p[b] = state.x[dofs_[k][3 * n + b]];
}

void NavierStokesTerm::assemble(const MacroState& state, MacroAssembly& out) {
  const double dv_rate_dv = state.rate(*v_).dv_dx;
  FluidElementState s;
  s.dv_rate_dv = dv_rate_dv;
  s.dw_dx = d_ ? state.rate(*d_).dv_dx : 0.0;  // ∂ḋ/∂d: v̂ = ḋ follows x = X + d
  s.dt = dv_rate_dv > 0.0 ? state.dt : 0.0;    // steady: no transient term in τ_M
  s.body_force = body_force_;
  const bool shape = !mesh_dofs_.empty();
  Eigen::VectorXd R;
  Eigen::MatrixXd K, K_x, KK;
  for (size_t k = 0; k < elements_.size(); ++k) {
    gather_element(k, state, s);
    try {
      navier_stokes_element(kind_, convection_, fluid_, s, R, &K, shape ? &K_x : nullptr);
    } catch (const NumericalError& e) {
      throw NumericalError(fmt::format("{} (element {})", e.what(), elements_[k]));
    }
    out.add_internal(dofs_[k], R);
    if (!shape) {
      out.add_tangent(local_[k], K);
      continue;
    }
    // Columns [v, p | d]: ∂R/∂d_b = ∂R/∂x_b + (∂ḋ/∂d) ∂R/∂v̂_b, which K_x holds (s.dw_dx).
    KK.resize(K.rows(), K.cols() + K_x.cols());
    KK << K, K_x;
    out.add_tangent(local_[k], KK);
  }
}

void NavierStokesTerm::observe(const MacroState& state, std::vector<Observable>& out) const {
  // On the current geometry: V = ∫dV, E_k = ½ρ∫|v|² dV, and the viscous dissipation
  // rate D = ∫2μ ε(v):ε(v) dV (the power the blood's viscosity turns into heat; what it
  // leaves out of the energy balance, SUPG/LSIC and BDF's own damping, is the scheme's).
  const int order = mesh_.order();
  FluidElementState s;
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  double volume = 0.0, kinetic = 0.0, dissipation = 0.0;
  for (size_t k = 0; k < elements_.size(); ++k) {
    gather_element(k, state, s);
    for (const auto& q : tet_rule(2 * order + 2 * (order - 1))) {
      tet_shape(order, q.bary, N, dN);
      const Mat3 J = s.x * dN.transpose();
      const double dV = q.weight * J.determinant();
      const Mat3 grad_v = s.v * (J.transpose().inverse() * dN).transpose();  // ∂v/∂x
      const Mat3 eps = 0.5 * (grad_v + grad_v.transpose());
      volume += dV;
      kinetic += 0.5 * fluid_.density * dV * (s.v * N).squaredNorm();
      dissipation += 2.0 * fluid_.viscosity * dV * eps.squaredNorm();
    }
  }
  out.push_back({"fluid_volume", volume});
  out.push_back({"fluid_kinetic_energy", kinetic});
  out.push_back({"fluid_dissipation_rate", dissipation});
}

}  // namespace fe2
