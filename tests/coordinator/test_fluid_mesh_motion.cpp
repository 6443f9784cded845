// The fluid mesh's motion (macro/MeshMotionTerm.h): the geometric conservation law on a
// randomly moving mesh, the extension of a boundary motion (exact for affine motion,
// stiffened where elements are small), and an inverting fluid mesh stopping the run.
//
// The scene: the channel of test_fluid.cpp, box [0, 2] x [0, 2] x [0, 0.5], fluid below
// y = 1 (region 1), a clamped wall above (region 2).
#include "common/mesh/regions.h"
#include "tests/coordinator/fluid_fixtures.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fe2 {
namespace {

json channel(int order, int n, int steps) {
  return {{"mesh", {{"kind", "box"}, {"hi", {2.0, 2.0, 0.5}}, {"divisions", {2 * n, 2 * n, n}}, {"order", order},
                    {"region_slabs", {{"axis", "y"}, {"count", 2}}}, {"wall_regions", {2}}}},
          {"models", {{"m", {{"kind", "macro_law"}, {"material", test::nh(1e3, 0.3)}}}}},
          {"dirichlet", {{{"set", "ymax"}}}},
          {"time", {{"t_end", 0.5}, {"steps", steps}}},
          {"newton", {{"rtol", 1e-10}, {"max_iterations", 12}, {"max_cutbacks", 2}}},
          {"output", {{"vtu", false}}}};
}

const char* const kChannelWalls[] = {"xmin", "xmax", "ymin", "lid", "zmin", "zmax"};

RunSpec channel_spec(int order, int n, int steps) {
  RunSpec spec = read_run_spec(channel(order, n, steps), "");
  spec.mesh.node_sets["lid"] = interface_nodes(spec.mesh, {1}, {2});
  std::vector<int> all(static_cast<size_t>(spec.mesh.num_nodes()));
  for (int a = 0; a < spec.mesh.num_nodes(); ++a) all[static_cast<size_t>(a)] = a;
  spec.mesh.node_sets["all"] = all;
  return spec;
}

/// A rough pseudo-random field of X (a hash of the coordinates), in [−1, 1]³.
Vec3 rough(const Vec3& X) {
  auto h = [](double s) { return 2.0 * (std::abs(std::fmod(std::sin(s) * 43758.5453, 1.0))) - 1.0; };
  return {h(X.dot(Vec3(12.9898, 78.233, 37.719))), h(X.dot(Vec3(39.346, 11.135, 83.155))),
          h(X.dot(Vec3(73.156, 52.235, 9.151)))};
}

// Uniform flow U on a mesh whose interior nodes move at random, in time and from node
// to node (up to a tenth of an element), stays uniform: v = U, p = 0 to round-off, with
// Taylor–Hood and with the stabilized P1/P1 element (whose SUPG/PSPG terms see c = U − v̂).
TEST(FluidMeshMotion, UniformFlowOnARandomlyMovingMeshStaysUniform) {
  const Vec3 U(1.3, -0.4, 0.2);
  for (auto kind : {FluidElementKind::taylor_hood, FluidElementKind::stabilized_p1p1}) {
    const int order = kind == FluidElementKind::taylor_hood ? 2 : 1;
    RunSpec spec = channel_spec(order, 2, 5);
    FluidSetup s;
    s.regions = {1};
    s.fluid = {1.0, 0.05};
    s.element = kind;
    s.time = TimeScheme::bdf2;
    s.rtol = 1e-11;
    s.initial_velocity = [U](const Vec3&) { return U; };
    for (const char* set : kChannelWalls)
      s.boundaries.push_back(FluidBoundary::prescribed_velocity(set, [U](const Vec3&, double) { return U; }));
    MeshMotionSetup motion;
    motion.boundaries.push_back({"all", [](const Vec3& X, double t) {
      const double bubble = 64.0 * X.x() * (2 - X.x()) * X.y() * (1 - X.y()) * X.z() * (0.5 - X.z());
      return Vec3(0.05 * std::sin(9.0 * t + 5.0 * rough(X).x()) * bubble * rough(X));
    }});
    s.mesh_motion = motion;
    test::FluidSimulation f(spec, s);
    const RunResult r = f.sim.run();
    ASSERT_TRUE(r.converged) << r.error;
    double moved = 0.0, dv = 0.0, p = 0.0;
    for (int a : f.field("fluid_velocity").nodes()) {
      moved = std::max(moved, (f.position(spec.mesh, a) - spec.mesh.nodes[a]).norm());
      dv = std::max(dv, (f.velocity(a) - U).norm());
    }
    for (int a : f.field("fluid_pressure").nodes()) p = std::max(p, std::abs(f.pressure(a)));
    EXPECT_GT(moved, 0.01) << "the mesh did not move";
    EXPECT_LT(dv, 1e-12 * U.norm()) << "order " << order;
    EXPECT_LT(p, 1e-11) << "order " << order;
  }
}

using Motion = std::function<Vec3(const Vec3&, double)>;

/// The fluid at rest and its mesh moved by its boundary: the lid (y = 1) by `lid`, the
/// other walls by `walls`.
struct Extension {
  std::unique_ptr<test::FluidSimulation> f;
  RunResult result;
};
Extension extend(RunSpec& spec, MeshMotionKind kind, double chi, const Motion& lid, const Motion& walls) {
  FluidSetup s;
  s.regions = {1};
  s.fluid = {1.0, 0.05};
  s.element = spec.mesh.order() == 2 ? FluidElementKind::taylor_hood : FluidElementKind::stabilized_p1p1;
  s.time = TimeScheme::bdf2;
  for (const char* set : kChannelWalls) s.boundaries.push_back(FluidBoundary::no_slip(set));
  MeshMotionSetup motion;
  motion.kind = kind;
  motion.stiffening = chi;
  for (const char* set : kChannelWalls) motion.boundaries.push_back({set, std::string(set) == "lid" ? lid : walls});
  s.mesh_motion = motion;
  Extension e;
  e.f = std::make_unique<test::FluidSimulation>(spec, s);
  e.result = e.f->sim.run();
  return e;
}

const Motion kHeld = [](const Vec3&, double) { return Vec3(Vec3::Zero()); };

/// The lid bulging down in the middle, by `depth` · t · sin(πx/2) sin(2πz) (zero where
/// it meets the held walls).
Motion bulging_lid(double depth) {
  return [depth](const Vec3& X, double t) {
    return Vec3(0.0, -depth * t * std::sin(M_PI * X.x() / 2) * std::sin(2 * M_PI * X.z()), 0.0);
  };
}

// An affine motion d = B X t of the whole boundary is extended exactly (affine fields are
// harmonic and in elastic equilibrium) when the stiffening is off.
TEST(FluidMeshMotion, AnAffineBoundaryMotionExtendsExactly) {
  Mat3 B;
  B << 0.02, -0.03, 0.01, 0.04, -0.1, 0.02, -0.01, 0.03, 0.05;
  const Motion affine = [B](const Vec3& X, double t) { return Vec3(t * (B * X)); };
  for (MeshMotionKind kind : {MeshMotionKind::harmonic, MeshMotionKind::elastic}) {
    RunSpec spec = channel_spec(2, 2, 2);
    const Extension e = extend(spec, kind, 0.0, affine, affine);
    ASSERT_TRUE(e.result.converged) << e.result.error;
    double worst = 0.0, interior = 0.0;
    for (int a : e.f->field("mesh_displacement").nodes()) {
      const Vec3& X = spec.mesh.nodes[a];
      const Vec3 d = e.f->position(spec.mesh, a) - X;
      worst = std::max(worst, (d - affine(X, 0.5)).norm());
      if (X.x() > 0 && X.x() < 2 && X.y() > 0 && X.y() < 1 && X.z() > 0 && X.z() < 0.5)
        interior = std::max(interior, d.norm());
    }
    EXPECT_GT(interior, 0.01) << "no interior node moved";
    EXPECT_LT(worst, 1e-12) << "kind " << static_cast<int>(kind);
  }
}

// Jacobian-based stiffening: on a mesh graded towards the moving lid (small elements
// there), the smallest elements change their volume less with χ = 1 than without.
TEST(FluidMeshMotion, StiffeningProtectsTheSmallElementsNearAMovingWall) {
  double change[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    RunSpec spec = channel_spec(1, 4, 2);  // linear: grading a quadratic mesh would curve its edges
    for (Vec3& X : spec.mesh.nodes)
      if (X.y() < 1.0) X.y() = 1.0 - (1.0 - X.y()) * (1.0 - X.y());  // y' = 1 − (1 − y)²
    const Extension e = extend(spec, MeshMotionKind::harmonic, k, bulging_lid(0.2), kHeld);
    ASSERT_TRUE(e.result.converged) << e.result.error;
    // The tenth of the fluid's elements that are smallest: their worst relative volume change.
    std::vector<std::pair<double, int>> by_volume;
    for (int el = 0; el < spec.mesh.num_tets(); ++el)
      if (spec.mesh.region[el] == 1) by_volume.push_back({tet_signed_volume(spec.mesh, el), el});
    std::sort(by_volume.begin(), by_volume.end());
    for (size_t j = 0; j < by_volume.size() / 10; ++j) {
      const auto& t = spec.mesh.tets[by_volume[j].second];
      const Vec3 x0 = e.f->position(spec.mesh, t[0]);
      const double v = (e.f->position(spec.mesh, t[1]) - x0).dot(
                           (e.f->position(spec.mesh, t[2]) - x0).cross(e.f->position(spec.mesh, t[3]) - x0)) / 6.0;
      change[k] = std::max(change[k], std::abs(v / by_volume[j].first - 1.0));
    }
  }
  std::printf("smallest elements' worst volume change: χ = 0 %.3f, χ = 1 %.3f\n", change[0], change[1]);
  EXPECT_GT(change[0], 0.05);
  EXPECT_LT(change[1], 0.7 * change[0]);
}

// A lid pushed through the channel inverts fluid elements: the fluid element says so,
// the step is cut back, and the run stops there naming it.
TEST(FluidMeshMotion, AnInvertingFluidMeshStopsTheRunSayingWhere) {
  RunSpec spec = channel_spec(1, 2, 4);
  const Extension e = extend(spec, MeshMotionKind::harmonic, 1.0, bulging_lid(2.6), kHeld);
  EXPECT_FALSE(e.result.converged);
  EXPECT_GE(e.result.steps, 1);  // t = 0.125: bulged a third of the height, still valid
  EXPECT_NE(e.result.error.find("fluid element inverted"), std::string::npos) << e.result.error;
  EXPECT_NE(e.result.error.find("element "), std::string::npos) << e.result.error;
}

}  // namespace
}  // namespace fe2
