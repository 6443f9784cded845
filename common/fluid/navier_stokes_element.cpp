#include "common/fluid/navier_stokes_element.h"

#include "common/error.h"
#include "common/fem/lagrange_tet.h"

#include <cmath>

namespace fe2 {

namespace {

constexpr double C_t = 4.0, C_I = 36.0;  // τ_M's constants (the header)

/// An element's constants and one quadrature point's values, as the residual has them.
struct ElementConstants {
  double rho, mu, nu, temam, dw_dx;
  bool stabilized, pspg;
};
struct PointValues {
  double dV = 0.0, div_v = 0.0, p = 0.0;
  const Eigen::VectorXd* N = nullptr;
  const Eigen::VectorXd* M = nullptr;  ///< the pressure's (P1) shape functions
  const Eigen::Matrix3Xd* v_nodes = nullptr;  ///< the element's nodal velocities
  Eigen::Matrix3Xd gN;
  Eigen::Matrix<double, 3, 4> gM;
  Vec3 v, c, grad_p, r_M;
  Mat3 L, D, G;
  StabilizationParameters tau;
  Eigen::VectorXd lap_N, c_grad_N;
  std::vector<Mat3> hessians;  ///< ∂²N_a/∂x∂x (stabilized P2 only)
  Eigen::VectorXd f;           ///< the residual's integrand (R = Σ f dV)
};

// dR/dx at one point: for node b along e_j, d(f dV) = (∂_j N_b f + δf) dV with the δ's of
// the header. Column 3b + j of K_x.
void add_shape_derivatives(const PointValues& q, const ElementConstants& k, Eigen::MatrixXd& K_x) {
  const Eigen::VectorXd& N = *q.N;
  const Eigen::VectorXd& M = *q.M;
  const Eigen::Index n = N.size(), nv = 3 * n;
  const double tau_m = q.tau.tau_m, tau_c = q.tau.tau_c, trG = q.G.trace();
  const Vec3 Gc = q.G * q.c;
  Eigen::VectorXd df(nv + 4);
  for (Eigen::Index b = 0; b < n; ++b) {
    const Vec3 g_b = q.gN.col(b);
    const double beta = g_b.dot(q.c) + k.dw_dx * N[b];  // −δ((c·∇)N_a)/∂_j N_a
    for (int j = 0; j < 3; ++j) {
      const Vec3 L_j = q.L.col(j);                            // ∂_j v
      const Mat3 dL = -L_j * g_b.transpose();                 // δ(∇v)
      const double ddiv = -g_b.dot(L_j);                      // δ(div v)
      const Mat3 dD = 0.5 * (dL + dL.transpose());
      const Vec3 dinertia = -k.rho * beta * L_j;              // δ(ρ(c·∇)v), δc = −(∂v̂/∂x) N_b e_j inside β
      const Vec3 dgalerkin_v = dinertia + k.temam * ddiv * q.v;  // with δ(½ρ div v v)
      for (Eigen::Index a = 0; a < n; ++a) {
        const Vec3 g_a = q.gN.col(a), dg_a = -q.gN(j, a) * g_b;  // δ(∇N_a)
        df.segment<3>(3 * a) = N[a] * dgalerkin_v + 2.0 * k.mu * (dD * g_a + q.D * dg_a) - q.p * dg_a;
      }
      df.tail<4>() = -ddiv * M;
      if (k.stabilized) {
        // τ_M = (C_t/Δt² + c·Gc + C_I ν² G:G)^(−½): δ(c·Gc) = c·δG c + 2 Gc·δc, δ(G:G) = 2 G:δG,
        // with c·δG c = −2 (g_b·c)(G_j·c), G:δG = −2 g_b·G G_j, δ tr G = −2 g_b·G_j.
        const Vec3 G_j = q.G.col(j);
        const double dcGc = -2.0 * g_b.dot(q.c) * G_j.dot(q.c) - 2.0 * k.dw_dx * N[b] * Gc[j];
        const double dGG = -2.0 * g_b.dot(q.G * G_j);
        const double dtau_m = -0.5 * tau_m * tau_m * tau_m * (dcGc + 2.0 * C_I * k.nu * k.nu * dGG);
        const double dtau_c = -tau_c * (dtau_m / tau_m - 2.0 * g_b.dot(G_j) / trG);  // τ_C = 1/(τ_M tr G)
        // δr_M = δ(ρ(c·∇)v) + δ∇p − μ Σ_a v_a δΔN_a, δ∇p = −g_b ∂_j p.
        Vec3 dr_M = dinertia - q.grad_p[j] * g_b;
        for (size_t a = 0; a < q.hessians.size(); ++a) {
          const auto ai = static_cast<Eigen::Index>(a);
          const double dlap = -2.0 * (q.hessians[a] * g_b)[j] - q.gN(j, ai) * q.lap_N[b];
          dr_M -= k.mu * dlap * q.v_nodes->col(ai);
        }
        for (Eigen::Index a = 0; a < n; ++a) {
          const Vec3 g_a = q.gN.col(a), dg_a = -q.gN(j, a) * g_b;
          const double dc_grad_N = -beta * q.gN(j, a);
          df.segment<3>(3 * a) += (dtau_m * q.c_grad_N[a] + tau_m * dc_grad_N) * q.r_M + tau_m * q.c_grad_N[a] * dr_M +
                                  k.rho * ((dtau_c * q.div_v + tau_c * ddiv) * g_a + tau_c * q.div_v * dg_a);
        }
        for (int m = 0; k.pspg && m < 4; ++m) {  // δ(∇M_m) = −g_b ∂_j M_m
          const Vec3 gM_m = q.gM.col(m);
          df[nv + m] -= (dtau_m * gM_m.dot(q.r_M) + tau_m * (gM_m.dot(dr_M) - q.gM(j, m) * g_b.dot(q.r_M))) / k.rho;
        }
      }
      K_x.col(3 * b + j) += q.dV * (g_b[j] * q.f + df);
    }
  }
}

}  // namespace

StabilizationParameters stabilization_parameters(const Mat3& G, const Vec3& c, double nu, double dt) {
  const double transient = dt > 0.0 ? C_t / (dt * dt) : 0.0;
  const double tau_m = 1.0 / std::sqrt(transient + c.dot(G * c) + C_I * nu * nu * G.squaredNorm());
  return {tau_m, 1.0 / (tau_m * G.trace())};
}

void navier_stokes_element(FluidElementKind kind, ConvectiveForm convection, const NewtonianFluid& fluid,
                           const FluidElementState& s, Eigen::VectorXd& R, Eigen::MatrixXd* K,
                           Eigen::MatrixXd* K_x) {
  const int order = fluid_velocity_order(kind);
  const bool stabilized = kind != FluidElementKind::taylor_hood;
  const bool pspg = kind == FluidElementKind::stabilized_p1p1;  // Taylor–Hood is inf–sup stable
  const int n = tet_nodes(order);
  const int nv = 3 * n, ndof = nv + 4;
  const double temam = convection == ConvectiveForm::skew_symmetric ? 0.5 * fluid.density : 0.0;
  FE2_CHECK(s.x.cols() == n && s.v.cols() == n && s.v_rate.cols() == n && s.w.cols() == n,
            "fluid element: {} nodes expected", n);
  const double rho = fluid.density, mu = fluid.viscosity, nu = mu / rho;
  const ElementConstants constants{rho, mu, nu, temam, s.dw_dx, stabilized, pspg};
  R.setZero(ndof);
  if (K) K->setZero(ndof, ndof);
  if (K_x) K_x->setZero(ndof, nv);
  // Degree: the convective term N_a (c·∇)v is of degree 2k − 1 + k on affine elements.
  static const auto rule_p1 = tet_rule(3), rule_p2 = tet_rule(5);
  const auto& rule = order == 2 ? rule_p2 : rule_p1;
  Eigen::VectorXd N, M;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN, dM;
  PointValues pt;
  pt.N = &N;
  pt.M = &M;
  pt.v_nodes = &s.v;
  for (const auto& qp : rule) {
    tet_shape(order, qp.bary, N, dN);
    tet_shape(1, qp.bary, M, dM);
    const Mat3 J = s.x * dN.transpose();
    const double detJ = J.determinant();
    if (!(detJ > 0.0))
      throw NumericalError(fmt::format("fluid element inverted or degenerate (det J = {:.3g})", detJ));
    const Mat3 Jinv = J.inverse();
    const double dV = qp.weight * detJ;
    pt.dV = dV;
    pt.gN = Jinv.transpose() * dN;  // ∂N_a/∂x
    pt.gM = Jinv.transpose() * dM;  // ∂M_b/∂x
    const Eigen::Matrix3Xd& gN = pt.gN;
    const Eigen::Matrix<double, 3, 4>& gM = pt.gM;

    const Vec3 v = s.v * N, c = v - s.w * N, v_t = s.v_rate * N;
    const Mat3 L = s.v * gN.transpose();  // ∇v: L_ij = ∂v_i/∂x_j
    const double div_v = L.trace();
    const Mat3 D = 0.5 * (L + L.transpose());
    const double p = s.p.dot(M);
    const Vec3 grad_p = gM * s.p;
    const Vec3 inertia = rho * (v_t + L * c - s.body_force);  // ρ(a_χ − f)
    const Eigen::VectorXd c_grad_N = gN.transpose() * c;       // (c·∇)N_a

    // The integrand f (R = Σ f dV). Galerkin: momentum (with Temam's ½ρ(div v)v in the
    // skew-symmetric form) and mass.
    Eigen::VectorXd& f = pt.f;
    f.resize(ndof);
    const Vec3 skew = temam * div_v * v;
    for (int a = 0; a < n; ++a) f.segment<3>(3 * a) = N[a] * (inertia + skew) + 2.0 * mu * D * gN.col(a) - p * gN.col(a);
    f.tail<4>() = -div_v * M;

    StabilizationParameters tau;
    Vec3 r_M = Vec3::Zero();
    Eigen::VectorXd lap_N = Eigen::VectorXd::Zero(n);  // ΔN_a (0 for P1)
    pt.hessians.clear();
    // G of an element of degree k: k² J⁻ᵀJ⁻¹ (its nodes are h/k apart).
    const Mat3 G = double(order * order) * Jinv.transpose() * Jinv;
    if (stabilized) {
      tau = stabilization_parameters(G, c, nu, s.dt);
      if (order == 2) {
        pt.hessians = tet_shape_physical_hessians(order, s.x, Jinv, gN);
        for (int a = 0; a < n; ++a) lap_N[a] = pt.hessians[static_cast<size_t>(a)].trace();
      }
      r_M = inertia + grad_p - mu * (s.v * lap_N);
      for (int a = 0; a < n; ++a)
        f.segment<3>(3 * a) += tau.tau_m * c_grad_N[a] * r_M + rho * tau.tau_c * div_v * gN.col(a);
      if (pspg) f.tail<4>() -= (tau.tau_m / rho) * gM.transpose() * r_M;
    }
    R += dV * f;
    if (K_x) {
      pt.div_v = div_v;
      pt.p = p;
      pt.v = v;
      pt.c = c;
      pt.grad_p = grad_p;
      pt.r_M = r_M;
      pt.L = L;
      pt.D = D;
      pt.G = G;
      pt.tau = tau;
      pt.lap_N = lap_N;
      pt.c_grad_N = c_grad_N;
      add_shape_derivatives(pt, constants, *K_x);
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
