// Contraction inside the cells of a micro unit, and at a macro-law point.
// The cells' Gauss points carry a cell model's state (Myocardium: passive + active
// stress + viscosity), the matrix stays passive; the unit's homogenized tangent is the
// derivative of its equilibrated stress in Z̄ and in Ż̄, and a homogeneous contracting
// unit is the macro law with the same model.
#include "common/materials/HolzapfelOgden.h"
#include "common/cellmodels/cell_model_schema.h"
#include "common/materials/Myocardium.h"
#include "common/cellmodels/cell_model_factory.h"
#include "tests/worker/unit_fixtures.h"
#include "worker/MacroLawPoint.h"
#include "worker/unit_equilibrium.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

using test::gradient;
using test::rel_diff;

constexpr double kDt = 5e-3;        // s, a beat's step
constexpr double kSystole = 0.12;   // s after activation

/// Land et al. 2017 (intact set) with its default calcium transient.
CellModelPtr contracting_cell() {
  static const json spec = {{"model", "land2017"}};  // SpecNode keeps a pointer
  SpecNode node(spec, "/active", *cell_model_schema());
  return make_cell_model(node);
}

MaterialPtr cell_material(double viscosity = 20.0) {
  return std::make_shared<Myocardium>(std::make_shared<NeoHookean>(2.0e5, 0.45),
                                      MyocardiumOptions{contracting_cell(), 0.1, viscosity});
}

MicroModelPtr contracting_two_cell_model(MaterialPtr cell, MaterialPtr ecm) {
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::every_iteration;
  CellLayout c;
  c.kind = "two_cells";
  c.size = Vec3(1.0, 0.4, 0.4);
  c.resolution = {6, 3, 3};
  c.gap = 0.1;
  c.cross_section = 0.5;
  return test::make_unit_model(c, {std::move(ecm), std::move(cell)}, opt);
}

/// Z̄(t): the fibres shorten a little while the cells contract.
Vec9 Zbar_at(double t) { return gradient({-0.4 * t, 0.01 * t, 0.0, 0.0, 0.2 * t, 0.0, 0.0, 0.05 * t, 0.2 * t}); }

proto::JobInput step_job(int step, double t, double t_act = 0.0) {
  proto::JobInput in;
  in.step = step;
  in.time = t;
  in.dt = kDt;
  in.Zbar = Zbar_at(t);
  in.Zbar_dot = (Zbar_at(t) - Zbar_at(t - kDt)) / kDt;
  in.Zbar_dot_coefficient = 1.0 / kDt;
  in.activation_time = t_act;
  return in;
}

/// Runs a point model (unit or macro-law point) through the twitch up to `t_end`.
template <class Point>
void twitch_to(Point& point, double t_end) {
  int step = 0;
  for (double t = kDt; t <= t_end + 1e-12; t += kDt) {
    if constexpr (std::is_same_v<Point, MicroUnit>) equilibrate(point, step_job(step++, t), 1e-12, 25);
    else {
      point.iterate(step_job(step++, t));
      point.commit_step();
    }
  }
}

// Tangent = central differences of the equilibrated P̄ in Z̄ (at fixed Ż̄) and in Ż̄ (at
// fixed Z̄), both from the same committed state at systole: the job's 𝔸_hom with
// c = ∂Ż̄/∂Z̄ is ∂P̄/∂Z̄ + c ∂P̄/∂Ż̄ (linear in c), so c = 0 and c = 1 separate the two.
TEST(ContractingUnit, TangentInZbarAndZbarDotEqualsFiniteDifferencesAtSystole) {
  const auto model = contracting_two_cell_model(cell_material(), std::make_shared<NeoHookean>(2.0e4, 0.3));
  ASSERT_FALSE(model->symmetric());
  MicroUnit unit(model);
  twitch_to(unit, kSystole - kDt);
  Bytes state_n;
  unit.serialize(state_n);
  const proto::JobInput job = step_job(100, kSystole);
  auto solve = [&](const proto::JobInput& in) {
    MicroUnit u(model);
    u.deserialize(state_n);
    return equilibrate(u, in, 1e-13, 25);
  };
  proto::JobInput in0 = job, in1 = job;
  in0.Zbar_dot_coefficient = 0.0;
  in1.Zbar_dot_coefficient = 1.0;
  const UnitEquilibrium e0 = solve(in0), e1 = solve(in1);
  EXPECT_EQ(unit.factor_kind(), FactorKind::lu);
  const Mat9 dP_dZ = e0.A_hom, dP_dZdot = e1.A_hom - e0.A_hom;
  // h: truncation ~h², equilibrium error 1e-13 r_ref / h; Ż̄ enters scaled by Δt.
  const double hZ = 1e-6, hZdot = 1e-4;
  Mat9 fd_Z, fd_Zdot;
  for (int c = 0; c < 9; ++c) {
    proto::JobInput p = in0, m = in0;
    p.Zbar[c] += hZ, m.Zbar[c] -= hZ;
    fd_Z.col(c) = (solve(p).P_bar - solve(m).P_bar) / (2 * hZ);
    p = in0, m = in0;
    p.Zbar_dot[c] += hZdot, m.Zbar_dot[c] -= hZdot;
    fd_Zdot.col(c) = (solve(p).P_bar - solve(m).P_bar) / (2 * hZdot);
  }
  std::printf("contracting unit: dP/dZ vs FD %.2e, dP/dZdot vs FD %.2e (|dP/dZdot| / |dP/dZ| = %.2e)\n",
              rel_diff(dP_dZ, fd_Z), rel_diff(dP_dZdot, fd_Zdot), dP_dZdot.norm() / dP_dZ.norm());
  EXPECT_LT(rel_diff(dP_dZ, fd_Z), 1e-6);
  EXPECT_LT(rel_diff(dP_dZdot, fd_Zdot), 1e-6);
  EXPECT_GT((dP_dZ - dP_dZ.transpose()).norm(), 1e-6 * dP_dZ.norm());  // really unsymmetric
}

// The same at a macro-law point (no equilibrium to solve: the law's own tangents).
TEST(ContractingUnit, MacroLawPointTangentEqualsFiniteDifferencesAtSystole) {
  const MaterialPtr law = cell_material();
  MacroLawPoint point(law);
  twitch_to(point, kSystole - kDt);
  Bytes state_n;
  point.serialize(state_n);
  auto stress = [&](const proto::JobInput& in) {
    MacroLawPoint p(law);
    p.deserialize(state_n);
    return p.iterate(in);
  };
  proto::JobInput in = step_job(100, kSystole);
  const proto::JobOutput out = stress(in);
  Mat9 fd;
  const double h = 1e-6;
  for (int c = 0; c < 9; ++c) {
    // Along the rate rule Ż̄ = c (Z̄ − Z̄_n) + …: perturb both.
    proto::JobInput p = in, m = in;
    p.Zbar[c] += h, m.Zbar[c] -= h;
    p.Zbar_dot[c] += in.Zbar_dot_coefficient * h, m.Zbar_dot[c] -= in.Zbar_dot_coefficient * h;
    fd.col(c) = (stress(p).P_bar - stress(m).P_bar) / (2 * h);
  }
  std::printf("contracting macro-law point: step tangent vs FD %.2e\n", rel_diff(out.A_hom, fd));
  EXPECT_LT(rel_diff(out.A_hom, fd), 1e-6);
}

// Homogeneous contracting unit = macro law, step after step of a twitch (w stays 0).
TEST(ContractingUnit, HomogeneousUnitIsTheMacroLawOverATwitch) {
  const MaterialPtr law = cell_material();
  const auto model = contracting_two_cell_model(law, law);
  MicroUnit unit(model);
  MacroLawPoint point(law);
  double worst = 0.0, peak = 0.0, worst_Ta = 0.0, peak_Ta = 0.0;
  int step = 0;
  for (double t = kDt; t <= 0.3 + 1e-12; t += kDt, ++step) {
    const proto::JobInput in = step_job(step, t, 0.02);
    const UnitEquilibrium eq = equilibrate(unit, in, 1e-13, 25);
    const proto::JobOutput out = point.iterate(in);
    point.commit_step();
    worst = std::max(worst, rel_diff(eq.P_bar, out.P_bar));
    worst = std::max(worst, rel_diff(eq.A_hom, out.A_hom));
    peak = std::max(peak, out.P_bar.norm());
    // The tension reported for output: the unit's cell mean = the point's own T_a.
    worst_Ta = std::max(worst_Ta, std::abs(unit.mean_active_tension() - out.active_tension));
    peak_Ta = std::max(peak_Ta, out.active_tension);
  }
  std::printf("homogeneous contracting unit vs macro law over a twitch: %.2e (T_a: %.2e of a %.1f kPa peak)\n",
              worst, worst_Ta / peak_Ta, 1e-3 * peak_Ta);
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_Ta, 1e-9 * peak_Ta);
  EXPECT_GT(peak_Ta, 3e4);
}

// Contraction generated inside the cells of a two-cell unit held isometric (Z̄ = 0):
// by Hill's lemma the homogenized tension is T̄ = T_a ⟨χ_cell ε'₁₁⟩, with ε' the local
// strain under a unit macro fibre strain; cells stiffer than the matrix strain less than
// the average, so 0 < T̄ < φ T_a with φ the cell fraction (and shortening cells lose
// tension through h(λ), which only lowers T̄ further).
TEST(ContractingUnit, HomogenizedActiveTensionLiesBetweenTheCellFractionBounds) {
  const auto model = contracting_two_cell_model(cell_material(0.0), std::make_shared<NeoHookean>(2.0e4, 0.3));
  MicroUnit unit(model);
  MacroLawPoint cell(cell_material(0.0));  // an isolated cell at λ = 1
  double cell_volume = 0.0, volume = 0.0;
  for (int e = 0; e < model->num_elements(); ++e) {
    double ve = 0.0;
    for (double w : model->geometry(e).weight) ve += w;
    volume += ve;
    if (model->material_of(e).history_size() > 0) cell_volume += ve;
  }
  const double phi = cell_volume / volume;
  ASSERT_GT(phi, 0.1);
  ASSERT_LT(phi, 0.9);
  double peak_ratio = 0.0, T_peak = 0.0;
  int step = 0;
  for (double t = kDt; t <= 0.25 + 1e-12; t += kDt, ++step) {
    proto::JobInput in = step_job(step, t);
    in.Zbar.setZero();
    in.Zbar_dot.setZero();
    const double T_bar = equilibrate(unit, in, 1e-12, 25).P_bar[index9(0, 0)];
    const double T_a = cell.iterate(in).P_bar[index9(0, 0)];
    cell.commit_step();
    if (T_a < 1e3) continue;  // before the twitch rises
    ASSERT_GT(T_bar, 0.0) << "t = " << t;
    ASSERT_LT(T_bar, phi * T_a) << "t = " << t;
    if (T_a > T_peak) T_peak = T_a, peak_ratio = T_bar / (phi * T_a);
  }
  std::printf("two-cell unit, cell fraction %.3f: at the isolated cell's peak (%.1f kPa) T_bar = %.3f phi T_a\n",
              phi, 1e-3 * T_peak, peak_ratio);
  EXPECT_GT(T_peak, 3e4);  // the cells really contracted
}

}  // namespace
}  // namespace fe2
