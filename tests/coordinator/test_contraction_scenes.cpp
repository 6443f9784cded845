// A muscle strip that contracts. Land 2017 cross-bridges at every point
// (macro law, or FE² units of the same material), excited by an eikonal front from its
// clamped end, shortens through a twitch; Newton stays quadratic at systole with the
// unsymmetric consistent tangent (stretch and stretch-rate dependence, viscosity).
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fe2 {
namespace {

json contracting_material() {
  return {{"model", "neo_hookean"},
          {"E", 1.0e5},
          {"nu", 0.45},
          {"viscosity", 200.0},
          // Substeps of 1 ms (RK4 stays stable: the stiffest rate is ~2.4/ms): cheap, and the
          // same integration for the law and the units, which is all these tests compare.
          {"active", {{"model", "land2017"}, {"transverse_fraction", 0.05}, {"max_substep", 1e-3}}}};
}

/// A strip [0,6]x[0,1]x[0,1] mm, fibres along x, clamped at x = 0, excited from there
/// at 100 mm/s (so the far end starts 60 ms later), through a twitch of 0.24 s.
json strip(const json& model, int steps = 24) {
  return {{"mesh", {{"kind", "box"}, {"hi", {6, 1, 1}}, {"divisions", {6, 1, 1}}}},
          {"frame", {{"fibre", {1, 0, 0}}, {"sheet", {0, 1, 0}}}},
          {"activation", {{"kind", "eikonal"}, {"sources", {{{"surface", "xmin"}}}}, {"velocity", 100.0}}},
          {"models", {{"m", model}}},
          {"dirichlet", {{{"set", "xmin"}}}},
          {"time", {{"t_end", 0.24}, {"steps", steps}}},
          {"newton", {{"rtol", 1e-9}, {"micro_rtol", 1e-12}, {"max_iterations", 25}}},
          {"probes", {{"tip", {6, 0.5, 0.5}}, {"mid", {3, 0.5, 0.5}}}},
          {"output", {{"vtu", false}}}};
}

struct Twitch {
  RunResult result;
  std::vector<double> tip_x;  ///< x-displacement of the tip per step
  Eigen::VectorXd u;
};

Twitch run_twitch(const json& j) {
  const RunSpec spec = read_run_spec(j, "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  Twitch t;
  t.result = sim.run([&](const StepRecord&) { t.tip_x.push_back(sim.deformed_position(Vec3(6, 0.5, 0.5))[0] - 6.0); });
  t.u = sim.state();
  return t;
}

// The strip shortens, then relaxes; at systole (largest shortening) and at every
// step Newton squares the residual in the asymptotic range.
TEST(ContractionScene, MuscleStripTwitchesWithQuadraticNewton) {
  const Twitch law = run_twitch(strip({{"kind", "macro_law"}, {"material", contracting_material()}}));
  ASSERT_TRUE(law.result.converged) << law.result.error;
  ASSERT_EQ(law.tip_x.size(), 24u);
  const auto systole = std::min_element(law.tip_x.begin(), law.tip_x.end()) - law.tip_x.begin();
  const double shortening = -law.tip_x[systole] / 6.0;
  std::printf("strip: peak shortening %.1f %% at t = %.3f s, %d Newton iterations\n", 100 * shortening,
              0.01 * (systole + 1), law.result.newton_iterations);
  EXPECT_GT(shortening, 0.05);           // the cells really pull
  EXPECT_LT(law.tip_x.back(), 0.3 * law.tip_x[systole]);  // and let go
  EXPECT_GT(systole, 5);                  // the twitch rises over tens of ms

  const auto& res = law.result.history[systole].residual("displacement");
  for (double r : res) std::printf("  systole |R|/F = %.3e\n", r);
  const int asymptotic = test::expect_quadratic_iterations(res, "systole");
  EXPECT_GT(asymptotic, 0) << "no iteration in the asymptotic range at systole";
}

// Under Newmark (inertia, γ/(βΔt) = 2/Δt weighting ∂Π/∂Ż in the tangent) the twitch is
// the same kind of motion and Newton still squares the residual at systole.
TEST(ContractionScene, NewmarkTwitchStaysQuadratic) {
  json j = strip({{"kind", "macro_law"}, {"material", contracting_material()}});
  j["time"]["scheme"] = "newmark";
  j["time"]["density"] = 1.05e-3;  // g/mm³ (with mm and Pa, mass is in g)
  const Twitch dyn = run_twitch(j);
  ASSERT_TRUE(dyn.result.converged) << dyn.result.error;
  const auto systole = std::min_element(dyn.tip_x.begin(), dyn.tip_x.end()) - dyn.tip_x.begin();
  EXPECT_GT(-dyn.tip_x[systole] / 6.0, 0.05);
  const auto& res = dyn.result.history[systole].residual("displacement");
  const int asymptotic = test::expect_quadratic_iterations(res, "systole");
  EXPECT_GT(asymptotic, 0) << "no iteration in the asymptotic range at systole";
}

// FE² units of the same contracting material (homogeneous cells) are the macro law:
// the whole twitch, to round-off.
TEST(ContractionScene, HomogeneousContractingUnitsReproduceTheMacroLaw) {
  const json material = contracting_material();
  const Twitch law = run_twitch(strip({{"kind", "macro_law"}, {"material", material}}, 8));
  const Twitch fe2 = run_twitch(strip({{"kind", "fe2"}, {"unit", test::homogeneous_unit(material)}}, 8));
  ASSERT_TRUE(law.result.converged) << law.result.error;
  ASSERT_TRUE(fe2.result.converged) << fe2.result.error;
  std::printf("FE2 %d, law %d Newton iterations\n", fe2.result.newton_iterations, law.result.newton_iterations);
  EXPECT_LT((fe2.u - law.u).norm() / law.u.norm(), 1e-9);
  EXPECT_GT(law.u.norm(), 1e-2);
}

}  // namespace
}  // namespace fe2
