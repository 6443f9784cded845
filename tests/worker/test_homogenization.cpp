// The homogenized response of a unit against exact answers.
#include "common/materials/Guccione.h"
#include "tests/support/non_potential_law.h"
#include "tests/worker/unit_fixtures.h"
#include "worker/unit_equilibrium.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

using test::gradient;
using test::rel_diff;

const std::vector<Vec9> kGradients = {
    gradient({0.1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}),
    gradient({0.12, 0.03, -0.02, 0.05, -0.08, 0.01, 0.02, 0.04, 0.06}),
    gradient({-0.15, 0.1, 0.0, -0.05, 0.2, 0.03, 0.0, -0.07, -0.1}),
};

// Test 1: a homogeneous unit has w = 0 and χ = 0, so 𝔸_hom = 𝔸(Z̄) and P̄ = Π(Z̄).
TEST(Homogenization, HomogeneousUnitReproducesItsMaterial) {
  const std::vector<MaterialPtr> laws = {std::make_shared<NeoHookean>(1.0e4, 0.3),
                                         std::make_shared<StVenantKirchhoff>(1.0e4, 0.25),
                                         std::make_shared<Guccione>(GuccioneParameters{})};
  for (const auto& law : laws) {
    CellLayout c;
    c.kind = "homogeneous";
    c.resolution = {3, 2, 2};
    MicroUnit unit(test::make_unit_model(c, {law}));
    for (const Vec9& Z : kGradients) {
      const UnitEquilibrium eq = equilibrate(unit, Z, 1e-12, 10);
      Vec9 Pi;
      Mat9 A;
      law->stress_and_tangent(Z, Pi, A);
      EXPECT_LT(rel_diff(eq.A_hom, A), 1e-10) << law->name();
      EXPECT_LT(rel_diff(eq.P_bar, Pi), 1e-10) << law->name();
      EXPECT_EQ(eq.newton_iterations, 1) << "a homogeneous unit is in equilibrium at once";
    }
  }
}

/// Exact effective tangent of a two-phase laminate with layer normal n and phase
/// fractions f, 1 − f (rank-one jumps Z_α = Z̄ + a_α ⊗ n with continuous traction).
Mat9 laminate_tangent(const Mat9& Aa, const Mat9& Ab, double f, const Vec3& n) {
  const Mat9* A[2] = {&Aa, &Ab};
  const double frac[2] = {f, 1.0 - f};
  Mat3 K[2], Kinv[2];
  for (int p = 0; p < 2; ++p) {
    K[p].setZero();
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        for (int J = 0; J < 3; ++J)
          for (int L = 0; L < 3; ++L) K[p](i, k) += (*A[p])(i + 3 * J, k + 3 * L) * n[J] * n[L];
    Kinv[p] = K[p].inverse();
  }
  const Mat3 S = (frac[0] * Kinv[0] + frac[1] * Kinv[1]).inverse();
  Mat9 Aeff;
  for (int c = 0; c < 9; ++c) {
    const Vec9 Zbar = Vec9::Unit(c);
    Vec3 s[2];
    for (int p = 0; p < 2; ++p) s[p] = as_mat3(*A[p] * Zbar) * n;  // traction of Z̄ alone
    const Vec3 t = S * (frac[0] * Kinv[0] * s[0] + frac[1] * Kinv[1] * s[1]);
    Vec9 P = Vec9::Zero();
    for (int p = 0; p < 2; ++p) {
      const Vec3 a = Kinv[p] * (t - s[p]);
      P += frac[p] * (*A[p] * (Zbar + as_vec9(a * n.transpose())));
    }
    Aeff.col(c) = P;
  }
  return Aeff;
}

// Test 2: at Z̄ = 0 (the linear-elastic limit) a laminate whose interfaces lie on
// element faces is solved exactly by trilinear hexes: 𝔸_hom equals the laminate formula.
TEST(Homogenization, LaminateMatchesExactFormulaInLinearLimit) {
  struct Case {
    int axis;
    double fraction;
    std::array<int, 3> res;
  };
  for (const Case& k : {Case{0, 0.5, {4, 2, 2}}, Case{1, 0.25, {2, 4, 3}}, Case{2, 0.75, {2, 3, 4}}}) {
    CellLayout c;
    c.kind = "laminate";
    c.size = Vec3(1.0, 0.8, 0.6);
    c.axis = k.axis;
    c.fraction = k.fraction;
    c.resolution = k.res;
    auto a = std::make_shared<StVenantKirchhoff>(2.0e4, 0.3);
    auto b = std::make_shared<StVenantKirchhoff>(1.0e3, 0.45);
    MicroUnit unit(test::make_unit_model(c, {a, b}));
    const UnitEquilibrium eq = equilibrate(unit, Vec9::Zero(), 1e-12, 5);
    const Mat9 exact = laminate_tangent(a->tangent(Vec9::Zero()), b->tangent(Vec9::Zero()),
                                        k.fraction, Vec3::Unit(k.axis));
    EXPECT_LT(rel_diff(eq.A_hom, exact), 1e-8) << "axis " << k.axis;
    // and it is genuinely between the Voigt and Reuss bounds, not one of them
    const Mat9 voigt = k.fraction * a->tangent(Vec9::Zero()) + (1 - k.fraction) * b->tangent(Vec9::Zero());
    EXPECT_GT(rel_diff(eq.A_hom, voigt), 1e-2);
  }
}

// Test 3: 𝔸_hom of a heterogeneous two-cell unit at finite strain is the derivative of
// its equilibrated P̄(Z̄), checked by central differences.
TEST(HardHomogenization, TangentMatchesFiniteDifferencesOfEquilibratedStress) {
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::every_iteration;
  const auto model = test::two_cell_model(opt);
  MicroUnit unit(model);
  const Vec9 Z = kGradients[1];
  const UnitEquilibrium eq = equilibrate(unit, Z, 1e-12, 20);
  Bytes state;
  unit.serialize(state);  // start every perturbed solve from the equilibrium

  // h = 1e-5: truncation ~h² ~ 1e-10, equilibrium error / h ~ 1e-12/1e-5 = 1e-7.
  const double h = 1e-5;
  Mat9 fd;
  for (int c = 0; c < 9; ++c) {
    Vec9 P[2];
    for (int s = 0; s < 2; ++s) {
      MicroUnit u(model);
      u.deserialize(state);
      P[s] = equilibrate(u, Z + (s ? -h : h) * Vec9::Unit(c), 1e-12, 20).P_bar;
    }
    fd.col(c) = (P[0] - P[1]) / (2 * h);
  }
  EXPECT_LT(rel_diff(eq.A_hom, fd), 1e-6);
  // The unit is really heterogeneous: its tangent is not the volume average ⟨𝔸⟩.
  EXPECT_GT(rel_diff(eq.A_hom, unit.system().Abar), 1e-2);
  EXPECT_GT(eq.newton_iterations, 2);
}

// The unsymmetric path (H ≠ Gᵀ, LU): a phase with a non-potential law. The exact
// laminate formula holds for any tangent (it uses only traction continuity), and 𝔸_hom
// is still the derivative of the equilibrated P̄ — now an unsymmetric one.
MicroModelPtr laminate_with(MaterialPtr a, MaterialPtr b, int axis, double fraction,
                            std::array<int, 3> res) {
  CellLayout c;
  c.kind = "laminate";
  c.size = Vec3(1.0, 0.8, 0.6);
  c.axis = axis;
  c.fraction = fraction;
  c.resolution = res;
  return test::make_unit_model(c, {std::move(a), std::move(b)});
}

TEST(NonPotentialUnit, LawHasUnsymmetricTangentThatIsItsStressDerivative) {
  const test::NonPotentialLaw law(2.0e4, 0.3, 0.3);
  const Vec9 Z = kGradients[1];
  const Mat9 A = law.tangent(Z);
  Mat9 fd;
  for (int c = 0; c < 9; ++c)
    fd.col(c) = (law.stress(Z + 1e-6 * Vec9::Unit(c)) - law.stress(Z - 1e-6 * Vec9::Unit(c))) / 2e-6;
  EXPECT_LT(rel_diff(A, fd), 1e-7);
  EXPECT_GT((A - A.transpose()).norm(), 0.05 * A.norm());
}

TEST(NonPotentialUnit, LaminateMatchesExactFormulaThroughLUAndSeparateG) {
  auto a = std::make_shared<test::NonPotentialLaw>(2.0e4, 0.3, 0.3);
  auto b = std::make_shared<StVenantKirchhoff>(1.0e3, 0.45);
  for (int axis = 0; axis < 3; ++axis) {
    MicroUnit unit(laminate_with(a, b, axis, 0.5, {axis == 0 ? 4 : 2, axis == 1 ? 4 : 2, axis == 2 ? 4 : 2}));
    ASSERT_FALSE(unit.model().symmetric());
    const UnitEquilibrium eq = equilibrate(unit, Vec9::Zero(), 1e-12, 5);
    EXPECT_EQ(unit.factor_kind(), FactorKind::lu);
    const MicroUnit::System& s = unit.system();
    EXPECT_GT((s.G - s.H.transpose()).norm(), 1e-3 * s.G.norm()) << "G is assembled, not Hᵀ";
    const Mat9 exact = laminate_tangent(a->tangent(Vec9::Zero()), b->tangent(Vec9::Zero()), 0.5,
                                        Vec3::Unit(axis));
    EXPECT_LT(rel_diff(eq.A_hom, exact), 1e-8) << "axis " << axis;
    EXPECT_GT((exact - exact.transpose()).norm(), 1e-2 * exact.norm());
  }
}

TEST(NonPotentialUnit, TangentMatchesFiniteDifferencesOfEquilibratedStress) {
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::every_iteration;
  CellLayout c;
  c.kind = "two_cells";
  c.size = Vec3(1.0, 0.4, 0.4);
  c.resolution = {4, 3, 3};
  c.gap = 0.1;
  c.cross_section = 0.5;
  const auto model = test::make_unit_model(
      c, {std::make_shared<NeoHookean>(1.0e3, 0.3), std::make_shared<test::NonPotentialLaw>(2.0e4, 0.4, 0.3)},
      opt);
  MicroUnit unit(model);
  const Vec9 Z = kGradients[1];
  const UnitEquilibrium eq = equilibrate(unit, Z, 1e-12, 20);
  EXPECT_EQ(unit.factor_kind(), FactorKind::lu);
  Bytes state;
  unit.serialize(state);
  const double h = 1e-5;
  Mat9 fd;
  for (int col = 0; col < 9; ++col) {
    Vec9 P[2];
    for (int s = 0; s < 2; ++s) {
      MicroUnit u(model);
      u.deserialize(state);
      P[s] = equilibrate(u, Z + (s ? -h : h) * Vec9::Unit(col), 1e-12, 20).P_bar;
    }
    fd.col(col) = (P[0] - P[1]) / (2 * h);
  }
  EXPECT_LT(rel_diff(eq.A_hom, fd), 1e-6);
  EXPECT_GT((eq.A_hom - eq.A_hom.transpose()).norm(), 1e-2 * eq.A_hom.norm());
  EXPECT_GT(rel_diff(eq.A_hom, unit.system().Abar), 1e-2) << "really heterogeneous";
}

}  // namespace
}  // namespace fe2
