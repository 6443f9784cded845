// The fluid element (common/fluid/navier_stokes_element.h, fluid_boundary.h): its
// tangent against central differences of its residual — Galerkin and stabilized, with
// moving mesh, convection and the τ's dependence on the velocity — and the pieces a
// reader can check by hand (τ_M's transient limit, the face integrals).
#include "common/error.h"
#include "common/fem/lagrange_tet.h"
#include "common/fluid/fluid_boundary.h"
#include "common/fluid/navier_stokes_element.h"

#include <gtest/gtest.h>

#include <random>

namespace fe2 {
namespace {

/// A distorted tet (straight or, for order 2, with displaced edge nodes), n x 3 random fields.
FluidElementState random_element(int order, unsigned seed, double speed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = tet_nodes(order);
  FluidElementState s;
  s.x.resize(3, n);
  s.x.col(0) << 0, 0, 0;
  s.x.col(1) << 1.2, 0.1, 0;
  s.x.col(2) << 0.2, 0.9, 0.1;
  s.x.col(3) << 0.1, 0.2, 1.1;
  if (order == 2) {
    const int edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
    for (int k = 0; k < 6; ++k)
      s.x.col(4 + k) = 0.5 * (s.x.col(edges[k][0]) + s.x.col(edges[k][1])) + 0.04 * Vec3(u(rng), u(rng), u(rng));
  }
  s.v = s.v_rate = s.w = Eigen::Matrix3Xd(3, n);
  for (int a = 0; a < n; ++a) {
    s.v.col(a) = speed * Vec3(u(rng), u(rng), u(rng));
    s.v_rate.col(a) = Vec3(u(rng), u(rng), u(rng));
    s.w.col(a) = 0.3 * speed * Vec3(u(rng), u(rng), u(rng));
  }
  for (int b = 0; b < 4; ++b) s.p[b] = 10.0 * u(rng);
  s.dt = 0.05;
  s.dv_rate_dv = 1.5 / s.dt;  // BDF2's coefficient
  s.body_force = Vec3(0.3, -0.2, 0.1);
  return s;
}

/// The residual at the element's unknowns `z` (velocity node-major, then pressure); the
/// rate moves with v by the scheme's coefficient, as the time integration makes it.
Eigen::VectorXd residual_at(FluidElementKind kind, ConvectiveForm form, const NewtonianFluid& f,
                            FluidElementState s, const Eigen::VectorXd& z) {
  const int n = static_cast<int>(s.v.cols());
  for (int a = 0; a < n; ++a) {
    const Vec3 dv = z.segment<3>(3 * a) - s.v.col(a);
    s.v.col(a) += dv;
    s.v_rate.col(a) += s.dv_rate_dv * dv;
  }
  s.p = z.tail<4>();
  Eigen::VectorXd R;
  navier_stokes_element(kind, form, f, s, R, nullptr);
  return R;
}

TEST(FluidElement, TangentIsTheDerivativeOfTheResidualGalerkinAndStabilized) {
  const NewtonianFluid blood{1.06, 0.04};
  for (auto kind : {FluidElementKind::taylor_hood, FluidElementKind::taylor_hood_supg,
                    FluidElementKind::stabilized_p1p1})
  for (auto form : {ConvectiveForm::advective, ConvectiveForm::skew_symmetric}) {
    const int order = fluid_velocity_order(kind);
    for (double speed : {0.0, 1.0, 30.0}) {  // Stokes-like to convection-dominated
      const FluidElementState s = random_element(order, 7, speed);
      const int n = tet_nodes(order);
      Eigen::VectorXd z(3 * n + 4), R;
      for (int a = 0; a < n; ++a) z.segment<3>(3 * a) = s.v.col(a);
      z.tail<4>() = s.p;
      Eigen::MatrixXd K;
      navier_stokes_element(kind, form, blood, s, R, &K);
      ASSERT_EQ(R.size(), fluid_element_dofs(kind));
      EXPECT_LT((R - residual_at(kind, form, blood, s, z)).norm(), 1e-14 * R.norm());
      Eigen::MatrixXd K_fd(K.rows(), K.cols());
      const double h = 1e-6 * (1.0 + speed);
      for (int j = 0; j < z.size(); ++j) {
        Eigen::VectorXd zp = z, zm = z;
        zp[j] += h;
        zm[j] -= h;
        K_fd.col(j) = (residual_at(kind, form, blood, s, zp) - residual_at(kind, form, blood, s, zm)) / (2 * h);
      }
      EXPECT_LT((K - K_fd).norm(), 1e-7 * K.norm())
          << "kind " << static_cast<int>(kind) << ", form " << static_cast<int>(form) << ", speed " << speed;
    }
  }
}

// The shape derivatives K_x = dR/dx (the ALE coupling's block: the mesh follows the wall)
// against central differences of the residual in the node positions, the mesh velocity
// moving with x by the scheme's ∂v̂/∂x, as the coupled system's d moves both. Curved P2
// (Δ of the basis depends on x's second derivatives) and every term of every kind.
TEST(FluidElement, ShapeDerivativesAreTheDerivativeOfTheResidualInTheNodePositions) {
  const NewtonianFluid blood{1.06, 0.04};
  for (auto kind : {FluidElementKind::taylor_hood, FluidElementKind::taylor_hood_supg,
                    FluidElementKind::stabilized_p1p1})
    for (auto form : {ConvectiveForm::advective, ConvectiveForm::skew_symmetric})
      for (double speed : {0.0, 1.0, 30.0}) {
        FluidElementState s = random_element(fluid_velocity_order(kind), 5, speed);
        s.dw_dx = 1.5 / s.dt;  // BDF2 on the mesh displacement
        Eigen::VectorXd R, Rp, Rm;
        Eigen::MatrixXd K, K_x;
        navier_stokes_element(kind, form, blood, s, R, &K, &K_x);
        Eigen::VectorXd R_alone;
        navier_stokes_element(kind, form, blood, s, R_alone, nullptr);
        EXPECT_EQ((R - R_alone).norm(), 0.0);  // asking for K_x does not change R
        ASSERT_EQ(K_x.rows(), fluid_element_dofs(kind));
        ASSERT_EQ(K_x.cols(), 3 * s.x.cols());
        Eigen::MatrixXd K_fd(K_x.rows(), K_x.cols());
        const double h = 1e-6;  // of an element of unit size: central differences' error ~h²
        for (Eigen::Index b = 0; b < s.x.cols(); ++b)
          for (int j = 0; j < 3; ++j) {
            FluidElementState sp = s, sm = s;
            sp.x(j, b) += h, sp.w(j, b) += s.dw_dx * h;
            sm.x(j, b) -= h, sm.w(j, b) -= s.dw_dx * h;
            navier_stokes_element(kind, form, blood, sp, Rp, nullptr);
            navier_stokes_element(kind, form, blood, sm, Rm, nullptr);
            K_fd.col(3 * b + j) = (Rp - Rm) / (2 * h);
          }
        // ~2e-10 measured (central differences in x with h = 1e-6); a dropped term shows as ≥ 1e-3
        EXPECT_LT((K_x - K_fd).norm(), 1e-8 * K_x.norm())
            << "kind " << static_cast<int>(kind) << ", form " << static_cast<int>(form) << ", speed " << speed;
      }
}

// The stabilized P2 element's residual needs μΔv (else it is inconsistent: Poiseuille's
// ∇p = μΔv would be penalized). Δ of the isoparametric basis reproduces Δf exactly for a
// quadratic f on a straight element and Δ(linear) = 0 on a curved one (where dropping
// the geometry's second derivatives would not).
TEST(FluidElement, ShapeLaplaciansAreExactForWhatTheElementReproduces) {
  auto laplacians_at = [](const Eigen::Matrix3Xd& x, const Vec4& bary) {
    Eigen::VectorXd N;
    Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
    tet_shape(2, bary, N, dN);
    const Mat3 Jinv = (x * dN.transpose()).inverse();
    return tet_shape_laplacians(2, x, Jinv, Jinv.transpose() * dN);
  };
  const Vec4 point(0.1, 0.2, 0.3, 0.4);
  for (double bulge : {0.0, 1.0}) {
    FluidElementState s = random_element(2, 11, 1.0);
    if (bulge == 0.0)  // straight: edge nodes at the midpoints
      for (int k = 0; k < 6; ++k) {
        const int e[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
        s.x.col(4 + k) = 0.5 * (s.x.col(e[k][0]) + s.x.col(e[k][1]));
      }
    const Eigen::VectorXd lap = laplacians_at(s.x, point);
    // Σ_a x_a ΔN_a = Δx = 0 on any element.
    EXPECT_LT((s.x * lap).norm(), 1e-12) << "bulge " << bulge;
    if (bulge != 0.0) continue;
    // f = x² + 2y² − 3xz + z: Δf = 2 + 4 = 6.
    Eigen::VectorXd f(10);
    for (int a = 0; a < 10; ++a) {
      const Vec3 X = s.x.col(a);
      f[a] = X.x() * X.x() + 2 * X.y() * X.y() - 3 * X.x() * X.z() + X.z();
    }
    EXPECT_NEAR(f.dot(lap), 6.0, 1e-11);
  }
  // The curved element's geometry term matters: without it Σ x_a ΔN_a ≠ 0.
  const FluidElementState curved = random_element(2, 11, 1.0);
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
  tet_shape(2, point, N, dN);
  const Mat3 Jinv = (curved.x * dN.transpose()).inverse();
  const std::vector<Mat3> H = tet_shape_hessians(2);
  Vec3 without = Vec3::Zero();
  for (int a = 0; a < 10; ++a) without += curved.x.col(a) * (Jinv.transpose() * H[a] * Jinv).trace();
  EXPECT_GT(without.norm(), 1e-3);
}

TEST(FluidElement, GalerkinBlockIsSymmetricInVelocityAndPressure) {
  const FluidElementState s = random_element(2, 3, 1.0);
  Eigen::VectorXd R;
  Eigen::MatrixXd K;
  navier_stokes_element(FluidElementKind::taylor_hood, ConvectiveForm::skew_symmetric, {1.0, 0.1}, s, R, &K);
  EXPECT_LT((K.topRightCorner(30, 4) - K.bottomLeftCorner(4, 30).transpose()).norm(), 1e-14 * K.norm());
  EXPECT_EQ(K.bottomRightCorner(4, 4).norm(), 0.0);
}

TEST(FluidElement, StabilizationTimeScaleIsHalfTheStepWhenTheStepIsShort) {
  const Mat3 G = Mat3::Identity() * 4.0;
  const double dt = 1e-6;
  const StabilizationParameters t = stabilization_parameters(G, Vec3(1, 2, 3), 0.01, dt);
  EXPECT_NEAR(t.tau_m, dt / 2, 1e-6 * dt);
  EXPECT_DOUBLE_EQ(t.tau_c, 1.0 / (t.tau_m * 12.0));
  // Steady and convective: τ_M = 1/|c|_G.
  const StabilizationParameters s = stabilization_parameters(G, Vec3(3, 0, 4), 0.0, 0.0);
  EXPECT_NEAR(s.tau_m, 1.0 / 10.0, 1e-15);
}

TEST(FluidElement, InvertedElementIsANumericalError) {
  FluidElementState s = random_element(1, 1, 1.0);
  s.x.col(3).z() = -1.0;
  Eigen::VectorXd R;
  EXPECT_THROW(
      navier_stokes_element(FluidElementKind::stabilized_p1p1, ConvectiveForm::advective, {1.0, 0.1}, s, R, nullptr),
      NumericalError);
}

TEST(FluidBoundary, NormalIntegralsSumToTheAreaVectorAndWeighVerticesAsTheBasis) {
  Eigen::Matrix3Xd x(3, 3);
  x << 0, 2, 0,  //
      0, 0, 3,   //
      1, 1, 1;
  const Eigen::Matrix3Xd S1 = face_normal_integrals(1, x);
  EXPECT_LT((S1.rowwise().sum() - Vec3(0, 0, 3)).norm(), 1e-14);
  EXPECT_NEAR(S1(2, 0), 1.0, 1e-14);  // ∫ λ_a da = area/3
  Eigen::Matrix3Xd x2(3, 6);
  x2.leftCols(3) = x;
  x2.col(3) = 0.5 * (x.col(0) + x.col(1));
  x2.col(4) = 0.5 * (x.col(1) + x.col(2));
  x2.col(5) = 0.5 * (x.col(2) + x.col(0));
  const Eigen::Matrix3Xd S2 = face_normal_integrals(2, x2);
  EXPECT_LT((S2.rowwise().sum() - Vec3(0, 0, 3)).norm(), 1e-14);
  EXPECT_NEAR(S2(2, 0), 0.0, 1e-14);  // P2 vertex functions integrate to 0 on a triangle
  EXPECT_NEAR(S2(2, 3), 1.0, 1e-14);  // edge functions to area/3
}

TEST(FluidBoundary, BackflowActsOnlyOnInflowAndItsTangentIsTheDerivative) {
  Eigen::Matrix3Xd x(3, 6), w = Eigen::Matrix3Xd::Zero(3, 6), v(3, 6);
  x.leftCols(3) << 0, 1, 0, 0, 0, 1, 0, 0, 0.1;
  x.col(3) = 0.5 * (x.col(0) + x.col(1));
  x.col(4) = 0.5 * (x.col(1) + x.col(2));
  x.col(5) = 0.5 * (x.col(2) + x.col(0));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int a = 0; a < 6; ++a) v.col(a) = Vec3(u(rng), u(rng), 0.2 + 0.1 * u(rng));  // leaves (n ≈ +z)
  Eigen::VectorXd R;
  Eigen::MatrixXd K;
  backflow_face(2, 1.0, 0.5, x, v, w, R, &K);
  EXPECT_EQ(R.norm(), 0.0);
  v.row(2) *= -1.0;  // comes back in
  v(2, 4) = 0.3;     // partly
  backflow_face(2, 1.0, 0.5, x, v, w, R, &K);
  EXPECT_GT(R.norm(), 0.0);
  // Dissipative, as the viscous term: R·v = −βρ ∫ (c·n)₋ |v|² da ≥ 0.
  EXPECT_GT(R.dot(Eigen::Map<Eigen::VectorXd>(v.data(), 18)), 0.0);
  const double h = 1e-7;
  Eigen::MatrixXd K_fd(18, 18);
  for (int j = 0; j < 18; ++j) {
    Eigen::Matrix3Xd vp = v, vm = v;
    vp(j % 3, j / 3) += h;
    vm(j % 3, j / 3) -= h;
    Eigen::VectorXd Rp, Rm;
    backflow_face(2, 1.0, 0.5, x, vp, w, Rp, nullptr);
    backflow_face(2, 1.0, 0.5, x, vm, w, Rm, nullptr);
    K_fd.col(j) = (Rp - Rm) / (2 * h);
  }
  EXPECT_LT((K - K_fd).norm(), 1e-6 * K.norm());
}

}  // namespace
}  // namespace fe2
