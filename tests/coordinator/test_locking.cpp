// Issue #8: a near-incompressible (κ/μ ≈ 10⁴) transversely isotropic cantilever under a
// follower pressure (the geometry, law and load of Land et al. 2015, problem 1: a
// 10 x 1 x 1 beam clamped at x = 0, Guccione C = 2 kPa, b_f = 8, b_t = 2, b_fs = 4,
// fibres along the beam, 4 Pa on the bottom face). The displacement-only linear tet
// locks; the mixed formulations converge to one answer as h → 0.
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

constexpr double kKappa = 5.0e7;  // Pa: κ/μ ≈ 10⁴ against the small-strain shear C b_fs/2

json guccione(bool penalty) {
  json m = {{"model", "guccione"}, {"C", 2000.0}, {"bf", 8.0}, {"bt", 2.0}, {"bfs", 4.0}};
  if (penalty) m["kappa"] = kKappa;
  else m["volumetric"] = "none";
  return m;
}

/// Tip deflection (z of the point (10, 0.5, 1)) for a mesh of `n` cells per unit length.
double tip_deflection(int order, int n, const std::string& formulation) {
  const bool mixed = formulation != "displacement";
  json j = {{"mesh", {{"kind", "box"}, {"hi", {10, 1, 1}}, {"divisions", {10 * n, n, n}}, {"order", order}}},
            {"models", {{"muscle", {{"kind", "macro_law"}, {"material", guccione(!mixed)}}}}},
            {"dirichlet", {{{"set", "xmin"}}}},
            {"pressure", {{{"surface", "zmin"}, {"value", 4.0}}}},
            {"time", {{"steps", 4}}},
            {"newton", {{"rtol", 1e-9}, {"max_iterations", 30}}},
            {"probes", {{"tip", {10, 0.5, 1}}}},
            {"output", {{"vtu", false}}}};
  // Perturbed Lagrangian with the same κ: the same continuous problem as the penalty.
  if (mixed) j["formulation"] = {{"kind", "mixed"}, {"bulk_modulus", kKappa}};
  if (formulation == "P1/P1") j["formulation"]["stabilization_modulus"] = 4000.0;
  const auto r = test::run_scene(j);
  EXPECT_TRUE(r.result.converged) << formulation << ": " << r.result.error;
  return r.probes[0].z() - 1.0;
}

TEST(Locking, MixedElementsConvergeWhereLinearDisplacementTetsLock) {
  const double th_coarse = tip_deflection(2, 1, "P2/P1");
  const double th_fine = tip_deflection(2, 2, "P2/P1");
  const double p1p1_coarse = tip_deflection(1, 2, "P1/P1");
  const double p1p1_fine = tip_deflection(1, 4, "P1/P1");
  const double p1 = tip_deflection(1, 4, "displacement");
  std::printf("tip deflection (z of (10, 0.5, 1) minus 1): P2/P1 h=1 %.4f, h=1/2 %.4f; P1/P1 h=1/2 %.4f, "
              "h=1/4 %.4f; displacement P1 h=1/4 %.4f\n",
              th_coarse, th_fine, p1p1_coarse, p1p1_fine, p1);
  // Taylor–Hood is within 3 % on one cell across the beam.
  EXPECT_NEAR(th_coarse / th_fine, 1.0, 0.03);
  // Stabilized P1/P1 converges towards it (first order: the gap at least halves per
  // halving of h, with slack for the pre-asymptotic range).
  EXPECT_LT(std::abs(p1p1_fine - th_fine), 0.6 * std::abs(p1p1_coarse - th_fine));
  EXPECT_GT(p1p1_fine / th_fine, 0.75);
  // The displacement-only linear tet locks: under half the deflection on the finer mesh.
  EXPECT_LT(p1 / th_fine, 0.5);
  EXPECT_GT(th_fine, 3.0);  // a visible bend of the 10-long beam
}

}  // namespace
}  // namespace fe2
