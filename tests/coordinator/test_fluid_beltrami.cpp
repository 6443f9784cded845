// Ethier & Steinman's 3D Beltrami flow (Int J Numer Meth Fluids 19:369, 1994): an exact
// unsteady solution of the incompressible Navier–Stokes equations with convection, on
// the cube [−1, 1]³, velocity prescribed on its whole boundary:
//   u = −a[e^{ax} sin(ay + dz) + e^{az} cos(ax + dy)] e^{−νd²t}   (v, w: cyclic x → y → z)
//   p = −ρ(a²/2)[e^{2ax} + e^{2ay} + e^{2az} + 2 sin(ax + dy) cos(az + dx) e^{a(y+z)}
//        + 2 sin(ay + dz) cos(ax + dy) e^{a(z+x)} + 2 sin(az + dx) cos(ay + dz) e^{a(x+y)}] e^{−2νd²t}
// with a = π/4, d = π/2. Taylor–Hood P2/P1 converges at third order in velocity and
// second in pressure (L²) in space; BDF2 at second order in time; a prescribed interior
// mesh motion (ALE) changes the answer only by discretization error.
//
// The scene: box [−1, 1]² x [−1, 2], the fluid below z = 1 (regions 1 and 2), a clamped
// wall slab above (region 3); the pressure level is fixed by ∫p = 0, so pressures are
// compared up to their mean.
#include "common/fem/lagrange_tet.h"
#include "common/mesh/regions.h"
#include "tests/coordinator/fluid_fixtures.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fe2 {
namespace {

struct Beltrami {
  double rho = 1.0, nu = 0.5;
  static constexpr double a = M_PI / 4, d = M_PI / 2;
  Vec3 v(const Vec3& X, double t) const {
    const double x = X.x(), y = X.y(), z = X.z(), f = std::exp(-nu * d * d * t);
    return -a * f *
           Vec3(std::exp(a * x) * std::sin(a * y + d * z) + std::exp(a * z) * std::cos(a * x + d * y),
                std::exp(a * y) * std::sin(a * z + d * x) + std::exp(a * x) * std::cos(a * y + d * z),
                std::exp(a * z) * std::sin(a * x + d * y) + std::exp(a * y) * std::cos(a * z + d * x));
  }
  double p(const Vec3& X, double t) const {
    const double x = X.x(), y = X.y(), z = X.z();
    return -rho * a * a / 2 * std::exp(-2 * nu * d * d * t) *
           (std::exp(2 * a * x) + std::exp(2 * a * y) + std::exp(2 * a * z) +
            2 * std::sin(a * x + d * y) * std::cos(a * z + d * x) * std::exp(a * (y + z)) +
            2 * std::sin(a * y + d * z) * std::cos(a * x + d * y) * std::exp(a * (z + x)) +
            2 * std::sin(a * z + d * x) * std::cos(a * y + d * z) * std::exp(a * (x + y)));
  }
};

json cube_scene(int n, double t_end, int steps) {
  return {{"mesh", {{"kind", "box"}, {"lo", {-1, -1, -1}}, {"hi", {1, 1, 2}}, {"divisions", {n, n, 3 * n / 2}},
                    {"order", 2}, {"region_slabs", {{"axis", "z"}, {"count", 3}}}, {"wall_regions", {3}}}},
          {"models", {{"m", {{"kind", "macro_law"}, {"material", test::nh(1e3, 0.3)}}}}},
          {"dirichlet", {{{"set", "zmax"}}}},
          {"time", {{"t_end", t_end}, {"steps", steps}}},
          {"newton", {{"rtol", 1e-10}, {"max_iterations", 12}}},
          {"output", {{"vtu", false}}}};
}

/// A smooth interior mesh motion vanishing on the cube's boundary.
Vec3 mesh_motion(const Vec3& X, double t) {
  const double bubble = (1 - X.x() * X.x()) * (1 - X.y() * X.y()) * (1 - X.z() * X.z());
  return 0.15 * std::sin(2 * M_PI * t / 0.2) * bubble * Vec3(1.0, 0.6, -0.8);
}

struct Errors {
  double v = 0.0, p = 0.0;  ///< L² norms of v_h − v and of p_h − p less its mean
};

struct BeltramiRun {
  RunResult result;
  Errors error;
  Eigen::VectorXd velocity;  ///< the fluid_velocity block at t_end
  int iterations = 0;
};

BeltramiRun run_beltrami(int n, double t_end, int steps, bool moving, TimeScheme scheme = TimeScheme::bdf2,
                         double nu = Beltrami{}.nu) {
  RunSpec spec = read_run_spec(cube_scene(n, t_end, steps), "");
  TetMesh& m = spec.mesh;
  m.node_sets["lid"] = interface_nodes(m, {1, 2}, {3});
  std::vector<int> all(static_cast<size_t>(m.num_nodes()));
  for (int a = 0; a < m.num_nodes(); ++a) all[static_cast<size_t>(a)] = a;
  m.node_sets["all"] = all;
  Beltrami exact;
  exact.nu = nu;
  FluidSetup s;
  s.regions = {1, 2};
  s.fluid = {exact.rho, exact.rho * exact.nu};
  s.element = FluidElementKind::taylor_hood;
  s.time = scheme;
  s.rtol = 1e-10;
  s.initial_velocity = [exact](const Vec3& X) { return exact.v(X, 0.0); };
  if (moving) {
    // Every fluid node prescribed: the ALE map is exactly the given motion; the
    // velocity's boundary values are taken at the moved positions (the boundary does
    // not move, so they are the reference ones).
    MeshMotionSetup motion;
    motion.boundaries.push_back({"all", mesh_motion});
    s.mesh_motion = motion;
  }
  for (const char* set : {"xmin", "xmax", "ymin", "ymax", "zmin", "lid"})
    s.boundaries.push_back(
        FluidBoundary::prescribed_velocity(set, [exact](const Vec3& X, double t) { return exact.v(X, t); }));
  test::FluidSimulation f(spec, s);
  const Simulation& sim = f.sim;
  const RunResult r = f.sim.run();
  EXPECT_TRUE(r.converged) << r.error;
  BeltramiRun out;
  out.result = r;
  out.iterations = r.newton_iterations;
  const Field& vf = sim.system().field("fluid_velocity");
  const Field& pf = sim.system().field("fluid_pressure");
  const Field* df = sim.system().fields().find("mesh_displacement");
  const Eigen::VectorXd& x = sim.state();
  out.velocity = sim.field_values("fluid_velocity");
  // L² on the current geometry, by a degree-6 rule: ∫|v_h − v|², ∫(p_h − p), ∫(p_h − p)², V.
  double ev2 = 0, ep = 0, ep2 = 0, volume = 0;
  const auto rule = tet_rule(6);
  Eigen::VectorXd N, M;
  Eigen::Matrix<double, 3, Eigen::Dynamic> dN, dM;
  for (int e = 0; e < m.num_tets(); ++e) {
    if (m.region[e] == 3) continue;
    const std::vector<int> nodes = m.element_nodes(e);
    for (const auto& q : rule) {
      tet_shape(2, q.bary, N, dN);
      tet_shape(1, q.bary, M, dM);
      Mat3 J = Mat3::Zero();
      Vec3 xq = Vec3::Zero(), vq = Vec3::Zero();
      for (int a = 0; a < 10; ++a) {
        Vec3 xa = m.nodes[nodes[a]];
        if (df) xa += x.segment<3>(df->node_dof(nodes[a]));
        J += xa * dN.col(a).transpose();
        xq += N[a] * xa;
        vq += N[a] * x.segment<3>(vf.node_dof(nodes[a]));
      }
      double pq = 0;
      for (int b = 0; b < 4; ++b) pq += M[b] * x[pf.node_dof(m.tets[e][b])];
      const double dV = q.weight * J.determinant();
      ev2 += dV * (vq - exact.v(xq, t_end)).squaredNorm();
      const double dp = pq - exact.p(xq, t_end);
      ep += dV * dp;
      ep2 += dV * dp * dp;
      volume += dV;
    }
  }
  out.error = {std::sqrt(ev2), std::sqrt(std::max(0.0, ep2 - ep * ep / volume))};
  return out;
}

double rate(double coarse, double fine) { return std::log2(coarse / fine); }

// Space: a short time (10 BDF2 steps of 0.005) keeps the time error below the space
// error of the finest mesh (checked: halving Δt changes the n = 8 errors by < 1 %).
void expect_space_orders(bool moving, const std::vector<int>& sizes) {
  std::vector<Errors> e;
  for (int n : sizes) e.push_back(run_beltrami(n, 0.05, 10, moving).error);
  for (size_t k = 0; k < e.size(); ++k)
    std::printf("Beltrami%s n = %d: ‖v − v_h‖ %.3e, ‖p − p_h‖ %.3e\n", moving ? " (moving mesh)" : "", sizes[k],
                e[k].v, e[k].p);
  for (size_t k = 1; k < e.size(); ++k) {
    std::printf("  orders: velocity %.2f, pressure %.2f\n", rate(e[k - 1].v, e[k].v), rate(e[k - 1].p, e[k].p));
    // P2/P1: 3 and 2 asymptotically; the coarsest pair is pre-asymptotic.
    EXPECT_GT(rate(e[k - 1].v, e[k].v), 2.6) << "n = " << sizes[k];
    EXPECT_GT(rate(e[k - 1].p, e[k].p), 1.7) << "n = " << sizes[k];
  }
}

TEST(FluidBeltrami, TaylorHoodConvergesAtThirdOrderInVelocityAndSecondInPressure) {
  expect_space_orders(false, {2, 4});
}

TEST(FluidBeltrami, AMovingMeshChangesTheAnswerOnlyByDiscretizationError) {
  const Errors fixed = run_beltrami(4, 0.05, 10, false).error;
  const Errors moving = run_beltrami(4, 0.05, 10, true).error;
  std::printf("n = 4: fixed mesh ‖v − v_h‖ %.3e ‖p − p_h‖ %.3e; moving %.3e %.3e\n", fixed.v, fixed.p, moving.v,
              moving.p);
  // Same order of accuracy on a mesh distorted by up to 15 % of its size: within 2x.
  EXPECT_LT(moving.v, 2.0 * fixed.v);
  EXPECT_LT(moving.p, 2.0 * fixed.p);
  expect_space_orders(true, {2, 4});
}

// Time: self-convergence on one mesh (the space error cancels): the difference to a
// run at Δt/16 falls by ≈ 4 per halving with BDF2 (its backward-Euler first step does
// not spoil the order), by ≈ 2 with BDF1.
TEST(FluidBeltrami, Bdf2ConvergesAtSecondOrderInTimeAndBdf1AtFirst) {
  const double t_end = 0.2;
  for (TimeScheme scheme : {TimeScheme::bdf2, TimeScheme::backward_euler}) {
    const Eigen::VectorXd reference = run_beltrami(2, t_end, 64, false, scheme).velocity;
    std::vector<double> e;
    for (int steps : {4, 8, 16})
      e.push_back((run_beltrami(2, t_end, steps, false, scheme).velocity - reference).norm());
    const bool bdf2 = scheme == TimeScheme::bdf2;
    std::printf("%s: |v_Δt − v_ref| %.3e %.3e %.3e (orders %.2f, %.2f)\n", bdf2 ? "BDF2" : "BDF1", e[0], e[1], e[2],
                rate(e[0], e[1]), rate(e[1], e[2]));
    const double lo = bdf2 ? 1.8 : 0.8, hi = bdf2 ? 3.2 : 1.4;
    for (double r : {rate(e[0], e[1]), rate(e[1], e[2])}) {
      EXPECT_GT(r, lo) << (bdf2 ? "BDF2" : "BDF1");
      EXPECT_LT(r, hi) << (bdf2 ? "BDF2" : "BDF1");
    }
  }
}

// Newton with the consistent tangent (convection and the τ's included) converges
// quadratically on a convection-dominated flow (ν = 0.02: Re ≈ 170 on the cube): wherever
// the relative residual is below 0.05 and above round-off, r_{k+1} ≤ 20 r_k².
TEST(FluidBeltrami, NewtonConvergesQuadraticallyOnAConvectiveFlow) {
  const BeltramiRun b = run_beltrami(2, 0.1, 4, true, TimeScheme::bdf2, 0.02);
  ASSERT_TRUE(b.result.converged);
  int pairs = 0;
  for (const StepRecord& h : b.result.history) {
    const std::vector<double>& r = h.residual("fluid_velocity");
    std::printf("step %d:", h.step);
    for (double x : r) std::printf(" %.2e", x);
    std::printf("\n");
    for (size_t k = 0; k + 1 < r.size(); ++k)
      if (r[k] < 0.05 && r[k + 1] > 1e-13) {
        EXPECT_LT(r[k + 1], 20 * r[k] * r[k]) << "step " << h.step << " iteration " << k + 1;
        ++pairs;
      }
  }
  EXPECT_GE(pairs, 3);
}

// Three nested meshes (n = 8; fixed and moving: about 65 s on one core): label long, `ctest -L long -R Beltrami`.
TEST(LongFluidBeltrami, ThreeNestedMeshesFixedAndMoving) {
  expect_space_orders(false, {2, 4, 8});
  expect_space_orders(true, {2, 4, 8});
}

}  // namespace
}  // namespace fe2
