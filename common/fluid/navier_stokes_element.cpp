#include "common/fluid/navier_stokes_element.h"

#include "common/error.h"
#include "common/fem/lagrange_tet.h"

#include <cmath>

namespace fe2 {

StabilizationParameters stabilization_parameters(const Mat3& G, const Vec3& c, double nu, double dt) {
  constexpr double C_t = 4.0, C_I = 36.0;
  const double transient = dt > 0.0 ? C_t / (dt * dt) : 0.0;
  const double tau_m = 1.0 / std::sqrt(transient + c.dot(G * c) + C_I * nu * nu * G.squaredNorm());
  return {tau_m, 1.0 / (tau_m * G.trace())};
}

void navier_stokes_element(FluidElementKind kind, ConvectiveForm convection, const NewtonianFluid& fluid,
                           const FluidElementState& s, Eigen::VectorXd& R, Eigen::MatrixXd* K) {
  const int order = fluid_velocity_order(kind);
  const bool stabilized = kind != FluidElementKind::taylor_hood;
  const bool pspg = kind == FluidElementKind::stabilized_p1p1;  // Taylor–Hood is inf–sup stable
  const int n = tet_nodes(order);
  const int nv = 3 * n, ndof = nv + 4;
  const double temam = convection == ConvectiveForm::skew_symmetric ? 0.5 * fluid.density : 0.0;
  FE2_CHECK(s.x.cols() == n && s.v.cols() == n && s.v_rate.cols() == n && s.w.cols() == n,
            "fluid element: {} nodes expected", n);
  const double rho = fluid.density, mu = fluid.viscosity, nu = mu / rho;
  R.setZero(ndof);
  if (K) K->setZero(ndof, ndof);
  // Degree: the convective term N_a (c·∇)v is of degree 2k − 1 + k on affine elements.
  static const auto rule_p1 = tet_rule(3), rule_p2 = tet_rule(5);
  const auto& rule = order == 2 ? rule_p2 : rule_p1;
  Eigen::VectorXd N, M;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN, dM;
  for (const auto& q : rule) {
    tet_shape(order, q.bary, N, dN);
    tet_shape(1, q.bary, M, dM);
    const Mat3 J = s.x * dN.transpose();
    const double detJ = J.determinant();
    if (!(detJ > 0.0))
      throw NumericalError(fmt::format("fluid element inverted or degenerate (det J = {:.3g})", detJ));
    const Mat3 Jinv = J.inverse();
    const double dV = q.weight * detJ;
    const Eigen::Matrix3Xd gN = Jinv.transpose() * dN;  // ∂N_a/∂x
    const Eigen::Matrix<double, 3, 4> gM = Jinv.transpose() * dM;  // ∂M_b/∂x

    const Vec3 v = s.v * N, c = v - s.w * N, v_t = s.v_rate * N;
    const Mat3 L = s.v * gN.transpose();  // ∇v: L_ij = ∂v_i/∂x_j
    const double div_v = L.trace();
    const Mat3 D = 0.5 * (L + L.transpose());
    const double p = s.p.dot(M);
    const Vec3 grad_p = gM * s.p;
    const Vec3 inertia = rho * (v_t + L * c - s.body_force);  // ρ(a_χ − f)
    const Eigen::VectorXd c_grad_N = gN.transpose() * c;       // (c·∇)N_a

    // Galerkin: momentum (with Temam's ½ρ(div v)v in the skew-symmetric form) and mass.
    const Vec3 skew = temam * div_v * v;
    for (int a = 0; a < n; ++a)
      R.segment<3>(3 * a) += dV * (N[a] * (inertia + skew) + 2.0 * mu * D * gN.col(a) - p * gN.col(a));
    R.tail<4>() -= dV * div_v * M;

    StabilizationParameters tau;
    Vec3 r_M = Vec3::Zero();
    Eigen::VectorXd lap_N = Eigen::VectorXd::Zero(n);  // ΔN_a (0 for P1)
    // G of an element of degree k: k² J⁻ᵀJ⁻¹ (its nodes are h/k apart).
    const Mat3 G = double(order * order) * Jinv.transpose() * Jinv;
    if (stabilized) {
      tau = stabilization_parameters(G, c, nu, s.dt);
      if (order == 2) lap_N = tet_shape_laplacians(order, s.x, Jinv, gN);
      r_M = inertia + grad_p - mu * (s.v * lap_N);
      for (int a = 0; a < n; ++a)
        R.segment<3>(3 * a) += dV * (tau.tau_m * c_grad_N[a] * r_M + rho * tau.tau_c * div_v * gN.col(a));
      if (pspg) R.tail<4>() -= dV * (tau.tau_m / rho) * gM.transpose() * r_M;
    }
    if (!K) continue;

    // ∂(ρ a_χ)_i/∂v_bj = ρ[δ_ij (∂v_t/∂v N_b + c·∇N_b) + L_ij N_b]
    auto dinertia = [&](int b) -> Mat3 {
      return rho * ((s.dv_rate_dv * N[b] + c_grad_N[b]) * Mat3::Identity() + N[b] * L);
    };
    for (int b = 0; b < n; ++b) {
      // ∂(½ρ div v v_i)/∂v_bj = ½ρ (div v δ_ij N_b + v_i ∂_j N_b)
      const Mat3 A_b = dinertia(b) + temam * (div_v * N[b] * Mat3::Identity() + v * gN.col(b).transpose());
      for (int a = 0; a < n; ++a) {
        // Viscous: μ(δ_ij ∇N_a·∇N_b + ∂_j N_a ∂_i N_b)
        const Mat3 visc = mu * (gN.col(a).dot(gN.col(b)) * Mat3::Identity() + gN.col(b) * gN.col(a).transpose());
        K->block<3, 3>(3 * a, 3 * b) += dV * (N[a] * A_b + visc);
      }
    }
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < 4; ++b) {
        K->block<3, 1>(3 * a, nv + b) -= dV * M[b] * gN.col(a);
        K->block<1, 3>(nv + b, 3 * a) -= dV * M[b] * gN.col(a).transpose();
      }
    if (!stabilized) continue;

    // ∂τ_M/∂v_bj = −τ_M³ (G c)_j N_b (through c), ∂τ_C/∂v = −(τ_C/τ_M) ∂τ_M/∂v;
    // ∂r_M/∂v_b = A_b − μ ΔN_b I.
    const Vec3 dtau_dc = -std::pow(tau.tau_m, 3) * (G * c);
    const Vec3 dtauc_dc = -(tau.tau_c / tau.tau_m) * dtau_dc;
    for (int b = 0; b < n; ++b) {
      const Mat3 A_b = dinertia(b) - mu * lap_N[b] * Mat3::Identity();
      for (int a = 0; a < n; ++a) {
        // SUPG: τ_M (c·∇N_a) r_M; LSIC: ρ τ_C ∂_i N_a div v.
        Mat3 k = tau.tau_m * c_grad_N[a] * A_b + tau.tau_m * N[b] * r_M * gN.col(a).transpose() +
                 c_grad_N[a] * N[b] * r_M * dtau_dc.transpose();
        k += rho * (tau.tau_c * gN.col(a) * gN.col(b).transpose() + div_v * N[b] * gN.col(a) * dtauc_dc.transpose());
        K->block<3, 3>(3 * a, 3 * b) += dV * k;
      }
      // PSPG: −(τ_M/ρ) ∇M_c·r_M
      for (int m = 0; pspg && m < 4; ++m) {
        const Eigen::RowVector3d row =
            tau.tau_m * gM.col(m).transpose() * A_b + gM.col(m).dot(r_M) * N[b] * dtau_dc.transpose();
        K->block<1, 3>(nv + m, 3 * b) -= dV / rho * row;
      }
    }
    for (int a = 0; a < n; ++a)
      K->block<3, 4>(3 * a, nv) += dV * tau.tau_m * c_grad_N[a] * gM;
    if (pspg) K->block<4, 4>(nv, nv) -= dV * (tau.tau_m / rho) * gM.transpose() * gM;
  }
}

}  // namespace fe2
