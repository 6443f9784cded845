// The myocardium at a material point (common/materials/Myocardium.h): passive
// law + active stress S_a = T_a[(1 − n_t) f₀⊗f₀ + n_t I] + Kelvin–Voigt η Ė. Its two
// tangents (∂Π/∂Z at fixed Ż, ∂Π/∂Ż at fixed Z, both through the cell-state update)
// equal central finite differences; its pieces equal their formulas.
#include "common/materials/HolzapfelOgden.h"
#include "common/materials/Myocardium.h"
#include "common/materials/NeoHookean.h"
#include "tests/common/material_finite_differences.h"
#include "tests/support/mock_cell_model.h"

#include <gtest/gtest.h>

#include <cstring>

namespace fe2 {
namespace {

Vec9 some_Z() {
  Vec9 Z;
  Z << 0.06, -0.01, 0.02, 0.015, -0.03, 0.005, -0.02, 0.01, -0.025;
  return Z;
}

MaterialPointContext systole() {
  MaterialPointContext c;
  c.time = 0.21;
  c.dt = 2e-3;
  c.activation_time = 0.01;
  c.Zdot << -0.8, 0.2, 0.1, 0.05, 0.4, -0.1, 0.2, 0.0, 0.3;
  return c;
}

double relative(const Mat9& A, const Mat9& B) { return (A - B).norm() / B.norm(); }

// The step tangent of a point with history and rate: every term of it (passive, active
// through λ and λ̇ and the cell state, viscous) against central differences.
TEST(Myocardium, TangentsInZAndZdotEqualFiniteDifferences) {
  auto cell = std::make_shared<test::MockCellModel>();
  const Myocardium law(std::make_shared<HolzapfelOgden>(HolzapfelOgdenParameters{}),
                       {cell, 0.2, 150.0});
  ASSERT_EQ(law.history_size(), 2);
  EXPECT_TRUE(law.rate_dependent());
  EXPECT_FALSE(law.major_symmetric());
  std::vector<double> h_n(2), h(2);
  law.initial_history(h_n);
  EXPECT_EQ(h_n[0], cell->s_rest);
  h_n[0] = 0.7;  // a contracting cell
  const MaterialPointContext c = systole();
  Vec9 Pi;
  Mat9 A, A_rate;
  law.stress_and_tangent_at(some_Z(), c, {h_n, h}, Pi, A, A_rate);
  const auto [A_fd, A_rate_fd] = testing::fd_tangents_at(law, some_Z(), c, h_n, 1e-6, 1e-4);
  const double eA = relative(A, A_fd), eR = relative(A_rate, A_rate_fd);
  std::printf("myocardium tangent vs FD: dPi/dZ %.2e, dPi/dZdot %.2e\n", eA, eR);
  EXPECT_LT(eA, 1e-7);
  EXPECT_LT(eR, 1e-7);
  EXPECT_GT(A_rate.norm(), 1e-3 * A.norm() * c.dt);  // the rate terms are really there
  // The history slot holds the tension the point produced.
  const double T_a = h[law.tension_slot()];
  EXPECT_GT(T_a, cell->T0);
}

// P_a = T_a F[(1 − n_t) f₀⊗f₀ + n_t I] at a uniaxial fibre stretch, by hand.
TEST(Myocardium, ActiveStressAlongFibresAndItsTransverseFraction) {
  auto cell = std::make_shared<test::MockCellModel>();
  cell->a = cell->b = cell->k = cell->m = 0.0;  // T_a = T0 (1 + s)
  const auto passive = std::make_shared<NeoHookean>(1.0e4, 0.3);
  const double lambda = 0.9, n_t = 0.25;
  Vec9 Z = Vec9::Zero();
  Z[index9(0, 0)] = lambda - 1.0;
  MaterialPointContext c = systole();
  c.Zdot.setZero();
  std::vector<double> h_n = {1.5, 0.0}, h(2);
  for (double nt : {0.0, n_t}) {
    const Myocardium law(passive, {cell, nt, 0.0});
    Vec9 Pi, Pi_p;
    Mat9 A, A_rate, A_p;
    law.stress_and_tangent_at(Z, c, {h_n, h}, Pi, A, A_rate);
    passive->stress_and_tangent(Z, Pi_p, A_p);
    const double T_a = cell->T0 * 2.5;
    const Vec9 P_a = Pi - Pi_p;
    EXPECT_NEAR(P_a[index9(0, 0)], T_a * lambda, 1e-9 * T_a);
    EXPECT_NEAR(P_a[index9(1, 1)], nt * T_a, 1e-9 * T_a);
    EXPECT_NEAR(P_a[index9(2, 2)], nt * T_a, 1e-9 * T_a);
    EXPECT_NEAR(P_a[index9(0, 1)], 0.0, 1e-9 * T_a);
    EXPECT_EQ(A_rate.norm(), 0.0);  // neither rate term is on
  }
}

// S_v = η Ė: with F = I, P_v = η sym(Ż).
TEST(Myocardium, KelvinVoigtStressIsEtaTimesStrainRate) {
  const auto passive = std::make_shared<NeoHookean>(1.0e4, 0.3);
  const double eta = 80.0;
  const Myocardium law(passive, {nullptr, 0.0, eta});
  EXPECT_EQ(law.history_size(), 0);
  EXPECT_TRUE(law.rate_dependent());
  const MaterialPointContext c = systole();
  Vec9 Pi;
  Mat9 A, A_rate;
  law.stress_and_tangent_at(Vec9::Zero(), c, {}, Pi, A, A_rate);
  const Mat3 Ld = as_mat3(c.Zdot);
  const Mat3 expected = eta * 0.5 * (Ld + Ld.transpose());
  EXPECT_LT((as_mat3(Pi) - expected).norm(), 1e-12 * expected.norm());
  const auto [A_fd, A_rate_fd] = testing::fd_tangents_at(law, some_Z(), c, {}, 1e-6, 1e-4);
  law.stress_and_tangent_at(some_Z(), c, {}, Pi, A, A_rate);
  EXPECT_LT(relative(A, A_fd), 1e-7);
  EXPECT_LT(relative(A_rate, A_rate_fd), 1e-7);
}

// Nothing asked, nothing added: the wrapper without a cell model or viscosity is the
// passive law bit for bit (so the seam costs a passive heart nothing in accuracy).
TEST(Myocardium, WithoutActiveOrViscousTermsItIsThePassiveLaw) {
  const auto passive = std::make_shared<HolzapfelOgden>(HolzapfelOgdenParameters{});
  const Myocardium law(passive, {});
  EXPECT_TRUE(law.major_symmetric());
  EXPECT_FALSE(law.rate_dependent());
  Vec9 Pi, Pi_p;
  Mat9 A, A_rate, A_p;
  law.stress_and_tangent_at(some_Z(), systole(), {}, Pi, A, A_rate);
  passive->stress_and_tangent(some_Z(), Pi_p, A_p);
  EXPECT_EQ(std::memcmp(Pi.data(), Pi_p.data(), sizeof(double) * 9), 0);
  EXPECT_EQ(std::memcmp(A.data(), A_p.data(), sizeof(double) * 81), 0);
  EXPECT_EQ(A_rate.norm(), 0.0);
}

}  // namespace
}  // namespace fe2
