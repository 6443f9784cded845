// A near-incompressible (κ/μ ≈ 10⁴) transversely isotropic cantilever under a
// follower pressure (the geometry, law and load of Land et al. 2015, problem 1: a
// 10 x 1 x 1 beam clamped at x = 0, Guccione C = 2 kPa, b_f = 8, b_t = 2, b_fs = 4,
// fibres along the beam, 4 Pa on the bottom face). The displacement-only linear tet
// locks; the mixed formulations converge to one answer as h → 0.
#include "common/fem/lagrange_tet.h"
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


// --------------------------------------------------------------------------------
// Cook's membrane, incompressible: the tapered panel (0,0)-(48,44)-(48,60)-(0,44),
// clamped on the left, a shear load of 100 spread over the right edge (a dead traction
// of 100/16 per unit area in y), plane strain (uz = 0), neo-Hookean μ = 80 with J̄ = 1
// enforced by a Lagrange multiplier. The mixed forms converge to one tip deflection;
// the displacement-only linear tet with ν = 0.4999 locks.

class DeadTraction final : public MacroTerm {
 public:
  DeadTraction(const TetMesh& mesh, std::string face, Vec3 traction)
      : mesh_(mesh), face_(std::move(face)), t_(traction) {}
  std::string name() const override { return "dead traction"; }
  void declare(MacroSystem& system) override {
    Eigen::VectorXd N;
    Eigen::Matrix<double, 2, Eigen::Dynamic> dN;
    for (const auto& tri : mesh_.faces.at(face_)) {
      const auto nodes = mesh_.face_nodes(tri);
      Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * nodes.size());
      for (const auto& q : triangle_rule(4)) {
        triangle_shape(mesh_.order(), q.bary, N, dN);
        Vec3 a1 = Vec3::Zero(), a2 = Vec3::Zero();
        for (size_t a = 0; a < nodes.size(); ++a) a1 += dN(0, a) * mesh_.nodes[nodes[a]], a2 += dN(1, a) * mesh_.nodes[nodes[a]];
        const double dA = q.weight * a1.cross(a2).norm();
        for (size_t a = 0; a < nodes.size(); ++a) f.segment<3>(3 * a) += dA * N[a] * t_;
      }
      dofs_.push_back(system.field("displacement").node_dofs(nodes));
      f_.push_back(std::move(f));
    }
  }
  void assemble(const MacroState& s, MacroAssembly& out) override {
    for (size_t k = 0; k < dofs_.size(); ++k) out.add_external(dofs_[k], s.time * f_[k]);
  }

 private:
  const TetMesh& mesh_;
  std::string face_;
  Vec3 t_;
  std::vector<std::vector<int>> dofs_;
  std::vector<Eigen::VectorXd> f_;
};

/// Vertical deflection of the top right corner (48, 60).
double cook_deflection(int order, int n, const std::string& formulation) {
  const bool mixed = formulation != "displacement";
  json j = {{"mesh", {{"kind", "box"}, {"hi", {1, 1, 1}}, {"divisions", {n, n, 1}}, {"order", order}}},
            {"models", {{"m", {{"kind", "macro_law"},
                               {"material", test::nh(mixed ? 160.0 : 2 * 80.0 * 1.4999, mixed ? 0.0 : 0.4999)}}}}},
            {"dirichlet", {{{"set", "xmin"}}, {{"set", "zmin"}, {"components", {2}}}, {{"set", "zmax"}, {"components", {2}}}}},
            {"time", {{"steps", 4}}},
            {"newton", {{"rtol", 1e-9}, {"max_iterations", 30}}},
            {"output", {{"vtu", false}}}};
  if (mixed) j["formulation"] = {{"kind", "mixed"}};
  if (formulation == "P1/P1") j["formulation"]["stabilization_modulus"] = 80.0;
  RunSpec spec = read_run_spec(j, "");
  for (Vec3& X : spec.mesh.nodes) {  // the unit square onto the tapered panel
    const double s = X.x(), t = X.y();
    X = Vec3(48 * s, 44 * s + t * (44 - 28 * s), X.z());
  }
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  sim.add_term(std::make_unique<DeadTraction>(spec.mesh, "xmax", Vec3(0, 100.0 / 16.0, 0)));
  const RunResult r = sim.run();
  EXPECT_TRUE(r.converged) << formulation << ": " << r.error;
  return sim.deformed_position(Vec3(48, 60, 0.5)).y() - 60.0;
}

TEST(Locking, IncompressibleCooksMembrane) {
  const double th_coarsest = cook_deflection(2, 2, "P2/P1");
  const double th_coarse = cook_deflection(2, 4, "P2/P1"), th_fine = cook_deflection(2, 8, "P2/P1");
  const double p1p1_coarse = cook_deflection(1, 8, "P1/P1"), p1p1_fine = cook_deflection(1, 16, "P1/P1");
  const double p1 = cook_deflection(1, 16, "displacement");
  std::printf("Cook's membrane, corner deflection: P2/P1 h=1/2 %.3f, 1/4 %.3f, 1/8 %.3f; P1/P1 1/8 %.3f, "
              "1/16 %.3f; displacement P1 (ν = 0.4999) 1/16 %.3f\n",
              th_coarsest, th_coarse, th_fine, p1p1_coarse, p1p1_fine, p1);
  // Taylor–Hood converges (the re-entrant corner's singularity slows it: the change per
  // halving of h shrinks, to a few per cent at h = 1/8).
  EXPECT_LT(std::abs(th_fine - th_coarse), 0.6 * std::abs(th_coarse - th_coarsest));
  EXPECT_NEAR(th_coarse / th_fine, 1.0, 0.05);
  EXPECT_LT(std::abs(p1p1_fine - th_fine), 0.6 * std::abs(p1p1_coarse - th_fine));
  EXPECT_LT(p1 / th_fine, 0.5);
}

}  // namespace
}  // namespace fe2
