// The macro factor kept across Newton iterations and steps (MacroSolver,
// `newton.macro_solver.refresh: adaptive`). GMRES on the current S̄, preconditioned by
// the kept MUMPS factor, solves each Newton system to 1e-12: the run takes the same Newton
// iterations to the same answer as factoring every iteration, with fewer factorizations.
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

json inflated_lv(const char* refresh) {
  return {{"mesh", {{"kind", "lv"}, {"divisions", {8, 4, 1}}, {"order", 2}}},
          {"frame", {{"kind", "rule"}}},
          {"formulation", {{"kind", "mixed"}}},
          {"models", {{"wall", {{"kind", "macro_law"}, {"material", {{"model", "holzapfel_ogden"}, {"volumetric", "none"}}}}}}},
          {"dirichlet", {{{"set", "base"}}}},
          {"pressure", {{{"surface", "endo"}, {"value", 1500.0}}}},
          {"cavities", {{"lv", {{"surface", "endo"}}}}},
          {"time", {{"steps", 8}}},
          {"newton", {{"rtol", 1e-10}, {"max_iterations", 25}, {"macro_solver", {{"refresh", refresh}}}}},
          {"output", {{"vtu", false}}}};
}

struct Solved {
  RunResult result;
  Eigen::VectorXd x;
  MacroSolver::Stats stats;
};

Solved solve(const json& j) {
  const RunSpec spec = read_run_spec(j, "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  Solved s{sim.run(), sim.state(), sim.macro_solver_stats()};
  EXPECT_TRUE(s.result.converged) << s.result.error;
  return s;
}

TEST(MacroSolver, KeptFactorGivesTheSameNewtonRunWithFewerFactorizations) {
  const Solved every = solve(inflated_lv("every_iteration")), kept = solve(inflated_lv("adaptive"));
  const int solves = kept.stats.factorizations + kept.stats.reused;
  std::printf("every iteration: %d factorizations; adaptive: %d factorizations, %d solves with a kept factor "
              "(%d GMRES iterations); |x − x_ref|/|x_ref| = %.1e\n",
              every.stats.factorizations, kept.stats.factorizations, kept.stats.reused, kept.stats.gmres_iterations,
              (kept.x - every.x).norm() / every.x.norm());
  EXPECT_EQ(every.stats.reused, 0);
  EXPECT_EQ(every.stats.factorizations, solves);  // the same number of Newton solves
  EXPECT_EQ(kept.result.newton_iterations, every.result.newton_iterations);
  EXPECT_LT(kept.stats.factorizations, solves / 2);
  EXPECT_LT((kept.x - every.x).norm(), 1e-9 * every.x.norm());
  // Newton still squares its residual with the kept factor (GMRES to 1e-12 of ‖b‖).
  int checked = 0;
  for (const StepRecord& h : kept.result.history)
    checked += test::expect_quadratic_iterations(h.residual("displacement"), "step " + std::to_string(h.step));
  EXPECT_GT(checked, 4);
}

TEST(MacroSolver, SpecReadsThePolicyAndRefusesABadTolerance) {
  json j = inflated_lv("adaptive");
  j["newton"]["macro_solver"]["max_gmres_iterations"] = 7;
  const RunSpec spec = read_run_spec(j, "");
  EXPECT_EQ(spec.macro_solver.refresh, MacroSolverOptions::Refresh::adaptive);
  EXPECT_EQ(spec.macro_solver.max_gmres_iterations, 7);
  j["newton"]["macro_solver"]["gmres_rtol"] = 0.5;
  try {
    read_run_spec(j, "");
    ADD_FAILURE() << "gmres_rtol 0.5 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/newton/macro_solver/gmres_rtol"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fe2
