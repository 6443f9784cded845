// Issue #11, "hard cases that stay stable" (label hard): each scene must converge and land
// within a stated tolerance of a reference — the same scene solved the expensive way, or
// with the default time step.
#include "common/circulation/beat_summary.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fe2 {
namespace {

namespace fs = std::filesystem;
using test::beam;
using test::run_scene;

double difference(const test::SceneRun& a, const test::SceneRun& b) { return (a.u - b.u).norm() / b.u.norm(); }

int refreshes(const RunResult& r) {
  int n = 0;
  for (const auto& s : r.history) n += s.refreshes;
  return n;
}

// A factor (and χ) kept 50 steps stale: the `fixed` policy with N_t = 50 over 50 load
// steps refactors only at step 0, and GMRES with that factor still reaches the answer of
// refactoring at every iteration. Both stop at |R|/F ≤ 1e-11: 1e-8 is far above that.
TEST(HardCases, FactorKeptFiftyStepsStaleReachesTheFreshAnswer) {
  const auto stale = run_scene(beam({{"kind", "fe2"}, {"unit", test::two_cell_unit("fixed", true, 50)}}, 50));
  const auto fresh = run_scene(beam({{"kind", "fe2"}, {"unit", test::two_cell_unit("every_iteration")}}, 50));
  ASSERT_TRUE(stale.result.converged) << stale.result.error;
  ASSERT_TRUE(fresh.result.converged) << fresh.result.error;
  std::printf("50 steps: stale factor %d refreshes, %d Newton iterations; fresh %d refreshes, %d; |Δu|/|u| %.1e\n",
              refreshes(stale.result), stale.result.newton_iterations, refreshes(fresh.result),
              fresh.result.newton_iterations, difference(stale, fresh));
  EXPECT_LT(difference(stale, fresh), 1e-8);
  EXPECT_EQ(refreshes(stale.result), 12) << "one refresh per unit, at step 0 only";
}

// Micro contrast 1e3 between cell and matrix (cells 2e6 Pa, matrix 2e3 Pa): with the
// `adaptive` refresh policy the units' GMRES with kept factors and the coupled Newton still
// converge, to the answer of refreshing at every iteration. (Measured and left for issue
// #11: the `fixed` policy with N_t = 4 stalls here, its units' residuals stuck at 2e-9 to
// 9e-9 of r_ref, and the run fails after four cut-backs.)
TEST(HardCases, MicroContrastOfAThousandConverges) {
  auto unit = [](const std::string& refresh) {
    json u = test::two_cell_unit(refresh, true, 4);
    u["materials"]["cell"] = test::nh(2.0e6, 0.4);
    return u;
  };
  // Tolerances 1e-9 (macro and units) rather than the fixtures' 1e-11: at this contrast a
  // unit's residual with a kept factor stalls near 2e-11 of r_ref (measured).
  auto scene = [&](const std::string& refresh) {
    json j = beam({{"kind", "fe2"}, {"unit", unit(refresh)}}, 8);
    j["newton"]["rtol"] = 1e-9;
    j["newton"]["micro_rtol"] = 1e-9;
    return run_scene(j);
  };
  const auto reuse = scene("adaptive"), fresh = scene("every_iteration");
  ASSERT_TRUE(reuse.result.converged) << reuse.result.error;
  ASSERT_TRUE(fresh.result.converged) << fresh.result.error;
  std::printf("contrast 1e3: Newton %d (adaptive) vs %d (fresh); |Δu|/|u| %.1e\n", reuse.result.newton_iterations,
              fresh.result.newton_iterations, difference(reuse, fresh));
  EXPECT_LT(difference(reuse, fresh), 1e-7);  // both stop at 1e-9 of the residual (measured 6e-12)
}

// The shipped macro beat at 4× its time step (20 steps per beat instead of 80): it still
// converges through the valve openings, and its loop stays near the default one. The
// tolerance is loose on purpose: a 40 ms step is a first-order time discretization of a
// 150 ms ejection (measured: EF 0.438 at 80 steps; the 20-step figures are printed).
TEST(HardCases, MacroBeatAtFourTimesTheTimeStep) {
  const fs::path file = fs::path(FE2_SOURCE_DIR) / "configs" / "lv-beat-macro.json";
  auto figures = [&](int steps_per_beat) {
    json j = json::parse(std::ifstream(file));
    j["output"] = {{"vtu", false}};
    j["time"]["steps_per_beat"] = steps_per_beat;
    const RunSpec spec = read_run_spec(j, file.parent_path().string());
    LocalEvaluator points(spec.models, spec.model_of_points());
    Simulation sim(spec, points);
    const RunResult r = sim.run();
    EXPECT_TRUE(r.converged) << steps_per_beat << " steps: " << r.error;
    std::vector<double> t, V, p;
    for (const StepRecord& h : r.history)
      t.push_back(h.time), V.push_back(h.cavity_volumes[0]), p.push_back(h.cavity_pressures[0]);
    return beat_figures(t, p, V, 0, t.size() - 1);
  };
  const BeatFigures fine = figures(80), coarse = figures(20);
  std::printf("macro beat: 80 steps EF %.3f peak %.2f kPa; 20 steps EF %.3f peak %.2f kPa\n", fine.EF,
              1e-3 * fine.peak_pressure, coarse.EF, 1e-3 * coarse.peak_pressure);
  EXPECT_NEAR(coarse.EF, fine.EF, 0.15 * fine.EF);
  EXPECT_NEAR(coarse.peak_pressure, fine.peak_pressure, 0.15 * fine.peak_pressure);
  EXPECT_NEAR(coarse.EDV, fine.EDV, 0.05 * fine.EDV);
}

}  // namespace
}  // namespace fe2
