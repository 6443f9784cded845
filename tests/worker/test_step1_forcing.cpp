// Step 1's tolerance over a Newton solve: with the residual
// forcing a unit solves K δw₁ = −r only as accurately as its Newton iteration can use,
// η = ‖r‖/r_ref within [gmres_rtol, gmres_forcing_max]. It must save GMRES iterations on
// a kept factor without costing Newton iterations or changing the converged answer.
#include "common/error.h"
#include "common/spec/spec_schemas.h"
#include "unit_fixtures.h"
#include "worker/MicroModel.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fe2 {
namespace {

using test::rel_diff;

TEST(Step1Forcing, ToleranceFollowsTheResidualWithinItsBounds) {
  MicroSolverOptions o;
  o.gmres_rtol = 1e-10;
  o.gmres_forcing_max = 1e-4;
  o.gmres_forcing = MicroSolverOptions::Forcing::residual;
  o.newton_rtol = 1e-30;                   // the safeguard out of the way (below)
  EXPECT_EQ(o.step1_rtol(0.3), 1e-4);      // far from the answer: the loosest
  EXPECT_EQ(o.step1_rtol(2e-6), 2e-6);     // η = ‖r‖/r_ref
  EXPECT_EQ(o.step1_rtol(1e-13), 1e-10);   // never below gmres_rtol
  // Kelley's safeguard: never a residual below 0.5·newton_rtol·r_ref, η ≥ 0.5·tol/(‖r‖/r_ref).
  o.newton_rtol = 1e-8;
  EXPECT_EQ(o.step1_rtol(2e-6), 1e-4);     // 0.5e-8/2e-6 = 2.5e-3, capped by the loosest
  EXPECT_EQ(o.step1_rtol(5e-10), 1e-4);    // converged: the loosest, not gmres_rtol
  EXPECT_EQ(o.step1_rtol(0.0), 1e-4);
  o.newton_rtol = 1e-12;
  EXPECT_DOUBLE_EQ(o.step1_rtol(1e-5), 1e-5);  // ‖r‖/r_ref above the safeguard's 5e-8
  EXPECT_DOUBLE_EQ(o.step1_rtol(1e-7), 5e-6);  // the safeguard, 0.5·1e-12/1e-7, between the bounds
  o.gmres_forcing = MicroSolverOptions::Forcing::constant;
  EXPECT_EQ(o.step1_rtol(0.3), 1e-10);
  // Bounds inverted (options built in code): the tighter gmres_rtol wins, never NaN.
  o.gmres_forcing = MicroSolverOptions::Forcing::residual;
  o.gmres_rtol = 1e-3;
  EXPECT_EQ(o.step1_rtol(0.3), 1e-3);
  EXPECT_EQ(o.step1_rtol(1e-8), 1e-3);
}

struct NewtonSolve {
  int iterations = 0;  ///< Newton iterations (Step 1 solves) up to ‖r‖/r_ref ≤ 1e-10
  int gmres = 0;
  bool converged = false;
  Vec9 P_bar;
  std::vector<double> relative;  ///< ‖r‖/r_ref per iteration
  std::vector<int> gmres_per_iteration;
};

// A unit factored at one load (step 0), then a Newton solve at three times that load
// on the kept factor (step 1): every Step 1 solve is preconditioned by a stale factor,
// where the tolerance decides how many GMRES iterations it takes.
NewtonSolve solve_on_a_stale_factor(MicroSolverOptions::Forcing forcing, double newton_rtol) {
  MicroSolverOptions opt;
  opt.newton_rtol = newton_rtol;
  opt.refresh = MicroSolverOptions::Refresh::fixed;
  opt.N_t = 100;
  opt.gmres_rtol = 1e-12;
  opt.gmres_forcing = forcing;
  MicroUnit unit(test::two_cell_model(opt));
  proto::JobInput in = test::factor_at_step_zero(unit);  // the refresh: K and χ at Z, w = 0
  in.step = 1;
  in.Zbar = 3.0 * in.Zbar;
  NewtonSolve s;
  for (in.iteration = 1; in.iteration <= 20; ++in.iteration) {
    in.apply_update = in.iteration > 1;
    const proto::JobOutput out = unit.iterate(in);
    EXPECT_EQ(out.kind, proto::Refresh::reuse) << "iteration " << in.iteration;
    s.relative.push_back(out.r_norm / out.r_ref);
    ++s.iterations;  // the converged one too: its Step 1 is solved (at gmres_rtol) before
    s.gmres += out.gmres_iterations;  // the coordinators see the residual has converged
    s.gmres_per_iteration.push_back(out.gmres_iterations);
    if (s.relative.back() <= 1e-10) {
      s.converged = true;
      s.P_bar = out.P_bar;
      break;
    }
  }
  return s;
}

TEST(Step1Forcing, SavesGmresIterationsOnAKeptFactorWithoutCostingNewton) {
  // Kelley's safeguard off (newton_rtol far below the 1e-10 the solve stops at): η
  // follows ‖r‖/r_ref all the way down.
  const NewtonSolve tight = solve_on_a_stale_factor(MicroSolverOptions::Forcing::constant, 1e-30);
  const NewtonSolve forced = solve_on_a_stale_factor(MicroSolverOptions::Forcing::residual, 1e-30);
  for (const NewtonSolve* s : {&tight, &forced})
    fmt::print("{}: {} Newton, GMRES {} (total {}), ‖r‖/r_ref {}\n",
               s == &tight ? "constant" : "residual", s->iterations,
               fmt::join(s->gmres_per_iteration, " "), s->gmres, fmt::join(s->relative, " "));
  ASSERT_TRUE(tight.converged);
  ASSERT_TRUE(forced.converged);
  // The loose early solves must show: at least one GMRES iteration per Newton iteration
  // saved on average (measured: 48 → 29 over the same 5 Newton iterations).
  EXPECT_LE(forced.gmres + forced.iterations, tight.gmres)
      << "the residual forcing did not loosen Step 1";
  // η follows ‖r‖/r_ref: loose first, then as tight as gmres_rtol where ‖r‖ is tiny (a
  // forcing stuck at gmres_forcing_max, or fed an unscaled ‖r‖, would differ here).
  EXPECT_LT(forced.gmres_per_iteration.front(), tight.gmres_per_iteration.front());
  EXPECT_EQ(forced.gmres_per_iteration.back(), tight.gmres_per_iteration.back());
  // Inexact Newton with η ∝ ‖r‖ converges as Newton does: at most one more iteration.
  EXPECT_LE(forced.iterations, tight.iterations + 1);
  // Both stop at ‖r‖/r_ref ≤ 1e-10: the same answer to about that.
  EXPECT_LT(rel_diff(forced.P_bar, tight.P_bar), 1e-9);
}

TEST(Step1Forcing, TheConvergedIterationIsSolvedOnlyToTheNewtonTolerance) {
  // The unit's Newton tolerance is the 1e-10 the solve stops at: the converged (last)
  // iteration's Step 1 then needs a residual of 0.5e-10·r_ref only, η at its loosest.
  const NewtonSolve tight = solve_on_a_stale_factor(MicroSolverOptions::Forcing::constant, 1e-10);
  const NewtonSolve plain = solve_on_a_stale_factor(MicroSolverOptions::Forcing::residual, 1e-30);
  const NewtonSolve guarded = solve_on_a_stale_factor(MicroSolverOptions::Forcing::residual, 1e-10);
  fmt::print("safeguarded: {} Newton, GMRES {}, ‖r‖/r_ref {}\n", guarded.iterations,
             fmt::join(guarded.gmres_per_iteration, " "), fmt::join(guarded.relative, " "));
  ASSERT_TRUE(guarded.converged);
  ASSERT_TRUE(plain.converged);
  // The last Step 1 is as loose as the first (a safeguard left out, or fed the wrong
  // tolerance, solves it to gmres_rtol like the plain forcing).
  EXPECT_LT(guarded.gmres_per_iteration.back(), plain.gmres_per_iteration.back());
  EXPECT_LE(guarded.gmres_per_iteration.back(), guarded.gmres_per_iteration.front());
  EXPECT_LT(guarded.gmres, plain.gmres);
  // No Newton iteration more than the plain forcing, the same answer.
  EXPECT_LE(guarded.iterations, plain.iterations);
  EXPECT_LT(rel_diff(guarded.P_bar, tight.P_bar), 1e-9);
}

MicroSolverOptions options_from(const nlohmann::json& solver) {
  nlohmann::json spec = nlohmann::json::parse(R"({
      "cell": "homogeneous", "resolution": [2, 2, 2],
      "materials": {"matrix": {"model": "neo_hookean", "E": 10, "nu": 0.3}}})");
  spec["solver"] = solver;
  return MicroModel::plan(SpecNode(spec, "/unit", micro_unit_schema()), ".").options;
}

TEST(Step1Forcing, SpecKeysAreReadAndBadValuesRefused) {
  EXPECT_EQ(options_from(nlohmann::json::object()).gmres_forcing,
            MicroSolverOptions::Forcing::residual);
  const MicroSolverOptions o =
      options_from({{"gmres_forcing", "constant"}, {"gmres_forcing_max", 1e-3}});
  EXPECT_EQ(o.gmres_forcing, MicroSolverOptions::Forcing::constant);
  EXPECT_EQ(o.gmres_forcing_max, 1e-3);
  auto refusal = [](const nlohmann::json& solver) -> std::string {
    try {
      options_from(solver);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  std::string e = refusal({{"gmres_forcing", "eisenstat"}});
  EXPECT_NE(e.find("/unit/solver/gmres_forcing"), std::string::npos) << e;
  EXPECT_NE(e.find("eisenstat"), std::string::npos) << e;
  e = refusal({{"gmres_forcing_max", 1.0}});
  EXPECT_NE(e.find("/unit/solver/gmres_forcing_max"), std::string::npos) << e;
  // gmres_rtol alone looser than 1e-4 stays valid (valid before the forcing existed):
  // the loosest tolerance follows it.
  EXPECT_EQ(options_from({{"gmres_rtol", 1e-3}}).gmres_forcing_max, 1e-3);
  EXPECT_EQ(options_from({{"gmres_rtol", 1e-3}}).step1_rtol(0.5), 1e-3);
  // Set explicitly looser than the loosest, it would invert the bounds.
  e = refusal({{"gmres_rtol", 1e-3}, {"gmres_forcing_max", 1e-5}});
  EXPECT_NE(e.find("/unit/solver/gmres_forcing_max"), std::string::npos) << e;
  EXPECT_NE(e.find("gmres_rtol (0.001)"), std::string::npos) << e;
}

}  // namespace
}  // namespace fe2
