// The LV (truncated ellipsoid of Land et al. 2015) inflated with the
// Lagrange-multiplier Taylor–Hood form keeps J̄ = 1 at every point, and the cavity grows.
#include "common/mesh/cavity_volume.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace fe2 {
namespace {

json lv_scene(const json& formulation, const json& material, double pressure) {
  return {{"mesh", {{"kind", "lv"}, {"divisions", {16, 8, 2}}, {"order", 2}}},
          {"frame", {{"kind", "rule"}}},
          {"formulation", formulation},
          {"models", {{"wall", {{"kind", "macro_law"}, {"material", material}}}}},
          {"dirichlet", {{{"set", "base"}}}},
          {"pressure", {{{"surface", "endo"}, {"value", pressure}}}},
          {"cavities", {{"lv", {{"surface", "endo"}}}}},
          {"time", {{"steps", 4}}},
          {"newton", {{"rtol", 1e-10}, {"max_iterations", 25}}},
          {"output", {{"vtu", false}}}};
}

struct Inflation {
  double cavity_growth = 0, wall_volume_change = 0, mean_J_error = 0, worst_element_J_error = 0;
  double worst_point_J_error = 0;
  bool volumes_increase = true;
};

Inflation inflate(int circumferential, int longitudinal, int transmural, const char* pressure_space = "P1") {
  // Holzapfel–Ogden without a volumetric energy: only the pressure field holds J̄ = 1.
  const json ho = {{"model", "holzapfel_ogden"}, {"volumetric", "none"}};
  json j = lv_scene({{"kind", "mixed"}, {"pressure", pressure_space}}, ho, 1500.0);
  j["mesh"]["divisions"] = {circumferential, longitudinal, transmural};
  const RunSpec spec = read_run_spec(j, "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  const RunResult r = sim.run();
  EXPECT_TRUE(r.converged) << r.error;
  Inflation out;
  double V = 0, v = 0, err = 0;
  for (int e = 0; e < spec.mesh.num_tets(); ++e) {
    double Ve = 0, ve = 0;
    for (int k = sim.points().first_point(e); k < sim.points().first_point(e + 1); ++k) {
      const double J = (Mat3::Identity() + as_mat3(sim.displacement_gradient(k))).determinant();
      Ve += sim.points()[k].volume;
      ve += sim.points()[k].volume * J;
      err += sim.points()[k].volume * std::abs(J - 1);
      out.worst_point_J_error = std::max(out.worst_point_J_error, std::abs(J - 1));
    }
    V += Ve, v += ve;
    out.worst_element_J_error = std::max(out.worst_element_J_error, std::abs(ve / Ve - 1));
  }
  out.wall_volume_change = v / V - 1;
  out.mean_J_error = err / V;
  const double V0 = cavity_volume(spec.mesh, "endo", Eigen::VectorXd::Zero(3 * spec.mesh.num_nodes())).volume;
  out.cavity_growth = r.history.back().cavity_volumes[0] / V0 - 1;
  for (size_t s = 1; s < r.history.size(); ++s)
    out.volumes_increase &= r.history[s].cavity_volumes[0] > r.history[s - 1].cavity_volumes[0];
  std::printf("LV %dx%dx%d, pressure %s, at 1.5 kPa: cavity +%.1f %%, wall volume change %.1e, mean "
              "|J-1| %.2e, worst element mean |J-1| %.2e, worst point |J-1| %.2e\n",
              circumferential, longitudinal, transmural, pressure_space, 100 * out.cavity_growth,
              out.wall_volume_change, out.mean_J_error, out.worst_element_J_error, out.worst_point_J_error);
  return out;
}

// The Lagrange multiplier holds the wall's volume exactly (its P1 test functions sum to
// one, so ∫(J̄ − 1) = 0 is one of the constraints) and J̄ → 1 under refinement. Pointwise
// J̄ = 1 holds only weakly (against P1 pressures): measured here, the mean |J̄ − 1| is
// 2–3 % at these resolutions; the enriched pressure below holds every element.
TEST(LvInflation, LagrangeMultiplierHoldsWallVolumeAndJTendsToOne) {
  const Inflation coarse = inflate(8, 4, 1), fine = inflate(16, 8, 2);
  for (const Inflation* r : {&coarse, &fine}) {
    EXPECT_GT(r->cavity_growth, 0.3);  // large inflation
    EXPECT_LT(std::abs(r->wall_volume_change), 1e-10);
    EXPECT_TRUE(r->volumes_increase);
  }
  EXPECT_LT(fine.mean_J_error, 0.7 * coarse.mean_J_error);
  EXPECT_LT(fine.worst_element_J_error, coarse.worst_element_J_error);
}

}  // namespace
}  // namespace fe2

namespace fe2 {
namespace {

// The enriched pressure P1+P0 adds ∫_e q (J̄ − 1) = 0 with q = 1 on every element: each
// element's mean J̄ (the VTU's det_F) is 1 to the Newton tolerance, where P1 alone leaves
// 4–8 % (measured in the test above). Inside an element J̄ still varies with the P2
// displacement: the worst quadrature point is printed and must tend to 1 under refinement.
TEST(LvInflation, EnrichedPressureHoldsEveryElementsVolume) {
  const Inflation p1 = inflate(8, 4, 1), coarse = inflate(8, 4, 1, "P1+P0"), fine = inflate(16, 8, 2, "P1+P0");
  for (const Inflation* r : {&coarse, &fine}) {
    EXPECT_GT(r->cavity_growth, 0.3);
    EXPECT_LT(std::abs(r->wall_volume_change), 1e-10);
    EXPECT_LT(r->worst_element_J_error, 1e-9);  // 1e-3 would do; Newton's rtol is 1e-10
    EXPECT_TRUE(r->volumes_increase);
  }
  EXPECT_GT(p1.worst_element_J_error, 1e-2);  // what the enrichment removes
  EXPECT_LT(fine.worst_point_J_error, coarse.worst_point_J_error);
  // The same muscle: the cavity grows alike with either pressure space (within 10 %).
  EXPECT_NEAR(coarse.cavity_growth, p1.cavity_growth, 0.1 * p1.cavity_growth);
}

}  // namespace
}  // namespace fe2
