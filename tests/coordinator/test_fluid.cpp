// Blood as macro fields (macro/fluid_scene.h) solved by the driver's one Newton loop next
// to a wall: exact solutions the elements reproduce, the flux constraint's multiplier,
// the pressure level of an enclosed fluid, the stabilized element's convergence order.
//
// The scene: a box [0, 2] x [0, 2] x [0, 0.5], fluid below y = 1 (region 1), a clamped,
// unloaded wall above (region 2): the fluid is a channel between the plane y = 0 and the
// wall's face y = 1, symmetry planes z = 0 and z = 0.5.
#include "common/error.h"
#include "common/mesh/regions.h"
#include "tests/coordinator/fluid_fixtures.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fe2 {
namespace {

constexpr double kL = 2.0, kH = 1.0;

json channel_scene(int order, int n) {
  return {{"mesh", {{"kind", "box"}, {"hi", {kL, 2 * kH, 0.5}}, {"divisions", {2 * n, 2 * n, 1}}, {"order", order},
                    {"region_slabs", {{"axis", "y"}, {"count", 2}}}, {"wall_regions", {2}}}},
          {"models", {{"m", {{"kind", "macro_law"}, {"material", test::nh(1e3, 0.3)}}}}},
          {"dirichlet", {{{"set", "ymax"}}}},
          {"time", {{"t_end", 1.0}, {"steps", 1}}},
          {"newton", {{"rtol", 1e-11}, {"max_iterations", 12}}},
          {"output", {{"vtu", false}}}};
}

/// Plane Poiseuille: v_x = U 4y(H − y)/H², p = P_out + G (L − x), G = 8μU/H².
struct Poiseuille {
  double U = 3.0, mu = 0.1, P_out = 5.0;
  double G() const { return 8.0 * mu * U / (kH * kH); }
  Vec3 v(const Vec3& X) const { return {U * 4.0 * X.y() * (kH - X.y()) / (kH * kH), 0.0, 0.0}; }
  double p(const Vec3& X) const { return P_out + G() * (kL - X.x()); }
};

/// The walls of the channel: no-slip below and on the wall's face ("lid"), symmetry in z.
FluidSetup channel_fluid(FluidElementKind kind, const Poiseuille& exact) {
  FluidSetup s;
  s.regions = {1};
  s.fluid = {1.0, exact.mu};
  s.element = kind;
  s.time = TimeScheme::none;
  s.rtol = 1e-10;
  using B = FluidBoundary;
  s.boundaries.push_back(B::prescribed_velocity("xmin", [exact](const Vec3& X, double) { return exact.v(X); }));
  s.boundaries.push_back(B::no_slip("zmin", {false, false, true}));
  s.boundaries.push_back(B::no_slip("zmax", {false, false, true}));
  s.boundaries.push_back(B::no_slip("xmax", {false, true, true}));  // parallel outflow
  s.boundaries.push_back(B::no_slip("ymin"));
  s.boundaries.push_back(B::no_slip("lid"));
  return s;
}

struct FluidRun {
  RunResult result;
  Eigen::VectorXd x;                 ///< every DOF
  std::vector<Vec3> velocity;        ///< per node (fluid nodes; zero elsewhere)
  std::vector<double> pressure;      ///< per node (fluid vertices; NaN elsewhere)
  std::vector<char> fluid_node;
};

FluidRun run_fluid(RunSpec& spec, const FluidSetup& setup) {
  spec.mesh.node_sets["lid"] = interface_nodes(spec.mesh, {1}, {2});
  test::FluidSimulation f(spec, setup);
  FluidRun r;
  r.result = f.sim.run();
  r.x = f.sim.state();
  const int nn = spec.mesh.num_nodes();
  r.velocity.assign(nn, Vec3::Zero());
  r.pressure.assign(nn, std::nan(""));
  r.fluid_node.assign(nn, 0);
  for (int a : f.field("fluid_velocity").nodes()) {
    r.velocity[a] = f.velocity(a);
    r.fluid_node[a] = 1;
  }
  for (int a : f.field("fluid_pressure").nodes()) r.pressure[a] = f.pressure(a);
  return r;
}

/// max over fluid nodes of |v_h − v|, and over fluid vertices of |p_h − p|.
std::pair<double, double> errors(const TetMesh& m, const FluidRun& r, const Poiseuille& exact, double p_shift = 0.0) {
  double ev = 0.0, ep = 0.0;
  for (int a = 0; a < m.num_nodes(); ++a) {
    if (!r.fluid_node[a]) continue;
    ev = std::max(ev, (r.velocity[a] - exact.v(m.nodes[a])).norm());
    if (!std::isnan(r.pressure[a])) ep = std::max(ep, std::abs(r.pressure[a] - exact.p(m.nodes[a]) - p_shift));
  }
  return {ev, ep};
}

// Taylor–Hood holds the quadratic velocity and linear pressure of plane Poiseuille
// exactly: the answer is the exact one to solver round-off, with the steady
// convective term on (zero for this flow, but in the tangent).
// The SUPG/LSIC-stabilized element too: its momentum residual r_M = ρ(c·∇)v + ∇p − μΔv
// vanishes on the exact flow (consistency; without μΔv the velocity is 0.6 % of U off).
TEST(Fluid, TaylorHoodReproducesPoiseuilleFlowExactly) {
  for (auto kind : {FluidElementKind::taylor_hood, FluidElementKind::taylor_hood_supg}) {
    RunSpec spec = read_run_spec(channel_scene(2, 2), "");
    const Poiseuille exact;
    FluidSetup setup = channel_fluid(kind, exact);
    setup.boundaries.push_back(FluidBoundary::pressure("xmax", [exact](double) { return exact.P_out; }));
    const FluidRun r = run_fluid(spec, setup);
    ASSERT_TRUE(r.result.converged) << r.result.error;
    const auto [ev, ep] = errors(spec.mesh, r, exact);
    EXPECT_LT(ev, 1e-10 * exact.U);
    EXPECT_LT(ep, 1e-10 * exact.G() * kL);
    EXPECT_LE(r.result.history[0].iterations, 3);  // linear in effect: Newton takes one step
  }
}

// The same outlet as a traction t = −P_out n (n = +x): the same exact flow. A traction
// face fixes the pressure level as a pressure face does.
TEST(Fluid, ATractionOutletActsAsItsPressure) {
  RunSpec spec = read_run_spec(channel_scene(2, 2), "");
  const Poiseuille exact;
  FluidSetup setup = channel_fluid(FluidElementKind::taylor_hood, exact);
  setup.boundaries.push_back(
      FluidBoundary::traction_of("xmax", [exact](double) { return Vec3(-exact.P_out, 0.0, 0.0); }));
  ASSERT_FALSE(setup.enclosed());
  const FluidRun r = run_fluid(spec, setup);
  ASSERT_TRUE(r.result.converged) << r.result.error;
  const auto [ev, ep] = errors(spec.mesh, r, exact);
  EXPECT_LT(ev, 1e-10 * exact.U);
  EXPECT_LT(ep, 1e-10 * exact.G() * kL);
}

// The outlet's flux tied to its multiplier: prescribing the exact flux Q = (2/3) U H W
// gives the exact flow, and the multiplier is the outlet's pressure. Without a pressure
// face the level is fixed by ∫p = 0, so p = G(L − x) − G L/2 and λ = −G L/2.
TEST(Fluid, FluxConstrainedOutletMultiplierIsTheOutletPressure) {
  RunSpec spec = read_run_spec(channel_scene(2, 2), "");
  const Poiseuille exact;
  FluidSetup setup = channel_fluid(FluidElementKind::taylor_hood, exact);
  const double Q = 2.0 / 3.0 * exact.U * kH * 0.5;
  setup.boundaries.push_back(FluidBoundary::flux("xmax", [Q](double) { return Q; }));
  ASSERT_TRUE(setup.enclosed());
  const FluidRun r = run_fluid(spec, setup);
  ASSERT_TRUE(r.result.converged) << r.result.error;
  const double shift = -exact.P_out - exact.G() * kL / 2;  // p_h = exact.p + shift
  const auto [ev, ep] = errors(spec.mesh, r, exact, shift);
  EXPECT_LT(ev, 1e-10 * exact.U);
  EXPECT_LT(ep, 1e-10 * exact.G() * kL);
  // λ: the global unknown after the velocity, pressure blocks.
  const double lambda = r.x[r.x.size() - 2];  // [..., λ, μ]
  EXPECT_NEAR(lambda, -exact.G() * kL / 2, 1e-10 * exact.G() * kL);
}

// Enclosed fluid at rest under gravity: v = 0, p = ρ g·(x − x̄) by the level constraint
// ∫p = 0 — unique, whatever the numbering. (Without the constraint S̄ is singular.)
TEST(Fluid, EnclosedFluidHasAUniquePressureByItsLevelConstraint) {
  RunSpec spec = read_run_spec(channel_scene(2, 1), "");
  FluidSetup s;
  s.regions = {1};
  s.fluid = {2.0, 0.1};
  s.element = FluidElementKind::taylor_hood;
  s.time = TimeScheme::none;
  s.body_force = Vec3(0.0, -9.81, 0.0);
  s.rtol = 1e-10;
  for (const char* set : {"xmin", "xmax", "ymin", "lid"}) s.boundaries.push_back(FluidBoundary::no_slip(set));
  // Slip on the z planes: one element across, all-no-slip would leave Taylor–Hood's
  // pressure modes of elements without a free velocity node.
  for (const char* set : {"zmin", "zmax"}) s.boundaries.push_back(FluidBoundary::no_slip(set, {false, false, true}));
  const FluidRun r = run_fluid(spec, s);
  ASSERT_TRUE(r.result.converged) << r.result.error;
  double worst_p = 0.0, worst_v = 0.0;
  for (int a = 0; a < spec.mesh.num_nodes(); ++a) {
    if (!r.fluid_node[a]) continue;
    worst_v = std::max(worst_v, r.velocity[a].norm());
    if (!std::isnan(r.pressure[a]))
      worst_p = std::max(worst_p, std::abs(r.pressure[a] - 2.0 * -9.81 * (spec.mesh.nodes[a].y() - 0.5 * kH)));
  }
  EXPECT_LT(worst_v, 1e-12);
  EXPECT_LT(worst_p, 1e-10 * 2.0 * 9.81 * kH);
}

// The stabilized P1/P1 element on linear meshes: not exact for Poiseuille, but its
// velocity error falls at second order (the nodal maximum; h halves, error ÷ ≈ 4) and
// its pressure error at least at first order.
TEST(Fluid, StabilizedP1P1ConvergesAtSecondOrderInVelocityOnPoiseuille) {
  const Poiseuille exact;
  std::vector<std::pair<double, double>> e;
  for (int n : {4, 8}) {
    RunSpec spec = read_run_spec(channel_scene(1, n), "");
    FluidSetup setup = channel_fluid(FluidElementKind::stabilized_p1p1, exact);
    setup.boundaries.push_back(FluidBoundary::pressure("xmax", [exact](double) { return exact.P_out; }));
    const FluidRun r = run_fluid(spec, setup);
    ASSERT_TRUE(r.result.converged) << r.result.error;
    e.push_back(errors(spec.mesh, r, exact));
  }
  std::printf("P1/P1 Poiseuille: |v − v_h|max %.3e → %.3e (÷%.2f), |p − p_h|max %.3e → %.3e (÷%.2f)\n",
              e[0].first, e[1].first, e[0].first / e[1].first, e[0].second, e[1].second, e[0].second / e[1].second);
  EXPECT_LT(e[0].first, 0.2 * exact.U);  // a coarse but sensible answer
  EXPECT_GT(e[0].first / e[1].first, 3.0);
  EXPECT_GT(e[0].second / e[1].second, 1.8);
}

TEST(Fluid, WrongElementForTheMeshOrderOrAMissingSetIsAnInputError) {
  RunSpec spec = read_run_spec(channel_scene(1, 1), "");
  spec.mesh.node_sets["lid"] = interface_nodes(spec.mesh, {1}, {2});
  FluidSetup s = channel_fluid(FluidElementKind::taylor_hood, Poiseuille{});
  try {
    (void)fluid_extension(spec.mesh, s);
    FAIL() << "Taylor–Hood accepted a linear mesh";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("quadratic"), std::string::npos) << e.what();
  }
  s.element = FluidElementKind::stabilized_p1p1;
  s.boundaries.push_back(FluidBoundary::pressure("outlet", [](double) { return 0.0; }));
  try {
    (void)fluid_extension(spec.mesh, s);
    FAIL() << "a missing face set was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'outlet'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fe2
