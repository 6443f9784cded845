// The Schur route (Eqs. 6–10, as the coordinator and units run it)
// gives the same Newton increment as a direct solve of the full system of Eq. (5).
#include "tests/coordinator/scene_fixtures.h"
#include "tests/support/non_potential_law.h"
#include "tests/worker/unit_fixtures.h"
#include "worker/MicroUnit.h"

#include <gtest/gtest.h>

#include <numeric>
#include <random>

namespace fe2 {
namespace {

RunSpec one_iteration_scene() {
  json j = test::beam({{"kind", "fe2"}, {"unit", test::two_cell_unit("every_iteration")}}, 1);
  j.erase("pressure");
  j["newton"]["max_iterations"] = 1;  // exactly one Newton iteration
  return read_run_spec(j, "");
}

void expect_schur_route_equals_direct_solve(const RunSpec& spec) {
  LocalEvaluator points(spec.models, spec.model_of_points());

  // A state far from equilibrium: random periodic fluctuations in every unit (ū = 0).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-0.02, 0.02);
  const int nu = points.size();
  std::vector<MicroUnit*> units(nu);
  for (int k = 0; k < nu; ++k) {
    units[k] = dynamic_cast<MicroUnit*>(&points.point(k));
    ASSERT_NE(units[k], nullptr);
    Vec w(units[k]->model().num_dofs());
    for (auto& x : w) x = uni(rng);
    units[k]->set_w(w);
  }

  // The full system of Eq. (5), assembled explicitly, with each unit's blocks at its
  // state: A_wk = |e|K, C_k = |e| G R B̄, lower-left |e| (R B̄)ᵀ H, Ā = Σ|e| (RB̄)ᵀ⟨𝔸⟩ RB̄.
  const MacroSystem sys = make_macro_system(spec);
  const MacroPoints pts(spec.mesh);
  std::vector<int> offset(nu + 1, 0);
  for (int k = 0; k < nu; ++k) offset[k + 1] = offset[k] + units[k]->model().num_dofs();
  const int nw = offset[nu], nbar = sys.num_free(), n = nw + nbar;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::MatrixXd> T(nu);  // R B̄ on free macro equations (9 x nbar)
  for (int k = 0; k < nu; ++k) {
    MicroUnit::System s;
    s.K = units[k]->model().pattern();
    units[k]->assemble_at(units[k]->w(), Vec9::Zero(), s);
    const Mat9 R = frame_rotation(spec.frame.at(pts[k].X));
    const Eigen::Matrix<double, 9, 12> RB = R * pts[k].B;
    T[k] = Eigen::MatrixXd::Zero(9, nbar);
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        const int eq = sys.eq(3 * spec.mesh.tets[k][a] + i);
        if (eq >= 0) T[k].col(eq) += RB.col(3 * a + i);
      }
    const double v = pts[k].volume;
    const int o = offset[k], nk = offset[k + 1] - o;
    M.block(o, o, nk, nk) += v * Eigen::MatrixXd(s.K);
    M.block(o, nw, nk, nbar) += v * s.G * T[k];
    M.block(nw, o, nbar, nk) += v * T[k].transpose() * s.H;
    M.block(nw, nw, nbar, nbar) += v * T[k].transpose() * s.Abar * T[k];
    rhs.segment(o, nk) = -v * s.r;
    rhs.segment(nw, nbar) -= v * T[k].transpose() * s.Pbar;
  }
  const Eigen::VectorXd direct = M.partialPivLu().solve(rhs);
  ASSERT_LT((M * direct - rhs).norm() / rhs.norm(), 1e-12);

  // The Schur route: one Newton iteration of the coordinator (ū starts at 0).
  Simulation sim(spec, points);
  StepRecord rec;
  EXPECT_FALSE(sim.newton(0, 1.0, 1.0, rec));  // one iteration cannot converge here
  Eigen::VectorXd du(nbar);
  for (int dof = 0; dof < sys.num_dofs(); ++dof)
    if (sys.eq(dof) >= 0) du[sys.eq(dof)] = sim.displacement()[dof];
  const Eigen::VectorXd du_direct = direct.tail(nbar);
  EXPECT_GT(du_direct.norm(), 1e-6);
  EXPECT_LT((du - du_direct).norm() / du_direct.norm(), 1e-10);

  // And the micro increments: δw = δw₁ − χ R B̄ Δū (Step 4) match the direct Δw_k.
  for (int k = 0; k < nu; ++k) {
    const Vec dw = units[k]->pending_dw1() - units[k]->chi() * (T[k] * du);
    const Vec dw_direct = direct.segment(offset[k], offset[k + 1] - offset[k]);
    EXPECT_LT((dw - dw_direct).norm() / dw_direct.norm(), 1e-10) << "unit " << k;
  }
}

TEST(BlockElimination, SchurRouteEqualsDirectSolveOfEquationFive) {
  expect_schur_route_equals_direct_solve(one_iteration_scene());
}

// The same with a non-potential cell law: H ≠ Gᵀ, LU factors, an unsymmetric Schur
// complement (the lower-left block above uses H, the upper-right G).
TEST(BlockElimination, UnsymmetricUnitsSchurRouteEqualsDirectSolve) {
  RunSpec spec = one_iteration_scene();
  CellLayout c;
  c.kind = "two_cells";
  c.size = Vec3(1.0, 0.4, 0.4);
  c.resolution = {4, 4, 4};
  c.gap = 0.125;
  c.cross_section = 0.5;
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::every_iteration;
  spec.models[0].micro = test::make_unit_model(
      c, {std::make_shared<NeoHookean>(2.0e3, 0.3), std::make_shared<test::NonPotentialLaw>(2.0e4, 0.4, 0.3)},
      opt);
  ASSERT_FALSE(spec.models[0].micro->symmetric());
  expect_schur_route_equals_direct_solve(spec);
  LocalEvaluator points(spec.models, spec.model_of_points());
  auto* unit = dynamic_cast<MicroUnit*>(&points.point(0));
  ASSERT_NE(unit, nullptr);
  proto::JobInput in;
  in.Zbar = Vec9::Constant(0.01);
  unit->iterate(in);
  EXPECT_EQ(unit->factor_kind(), FactorKind::lu);
  EXPECT_GT((unit->system().G - unit->system().H.transpose()).norm(), 1e-3 * unit->system().G.norm());
}

}  // namespace
}  // namespace fe2
