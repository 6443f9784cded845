// The macro side's house: fields as data (numbering, regions), constraints (prescribed
// values, ties, chains, cycles), time integration per field, and a test-only field on a
// second region tied to the wall on their interface, solved with the wall in one Newton
// loop through the field table alone (macro/macro_scene.h: MacroExtension).
#include "common/fem/lagrange_tet.h"
#include "common/fem/quadrature.h"
#include "common/mesh/box_mesh.h"
#include "common/mesh/regions.h"
#include "coordinator/LocalPoints.h"
#include "coordinator/macro/gather.h"
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace fe2 {
namespace {

json box_scene(int order, int steps = 2) {
  return {{"mesh", {{"kind", "box"}, {"hi", {1, 1, 1}}, {"divisions", {4, 2, 2}}, {"order", order}}},
          {"models", {{"m", {{"kind", "macro_law"}, {"material", test::nh(1e3, 0.0)}}}}},
          // A uniaxial stretch with symmetry planes: the deformation is homogeneous, u_x = 0.01 x t.
          {"dirichlet", {{{"set", "xmin"}, {"components", {0}}},
                         {{"set", "ymin"}, {"components", {1}}},
                         {{"set", "zmin"}, {"components", {2}}},
                         {{"set", "xmax"}, {"components", {0}}, {"value", {0.01, 0, 0}}}}},
          {"time", {{"t_end", 1.0}, {"steps", steps}}},
          {"newton", {{"rtol", 1e-11}, {"max_iterations", 20}}},
          {"output", {{"vtu", false}}}};
}

/// Region 2 is the half x > 1/2 of the box, region 1 the rest.
void split_regions(TetMesh& m) {
  for (int e = 0; e < m.num_tets(); ++e) {
    double x = 0.0;
    for (int a : m.tets[e]) x += 0.25 * m.nodes[a].x();
    m.region[e] = x > 0.5 ? 2 : 1;
  }
}

TEST(FieldTable, NumbersEachFieldAsABlockOnItsSpaceAndRegion) {
  RunSpec spec = read_run_spec(box_scene(2), "");
  split_regions(spec.mesh);
  const TetMesh& m = spec.mesh;
  FieldTable t;
  t.add({"displacement", 3, FieldSpace::nodal, {}, 0, TimeScheme::newmark, ResidualNorm::relative_to_load, 1e-8});
  t.add({"pressure", 1, FieldSpace::vertex_element, {}, 0, TimeScheme::none, ResidualNorm::scaled_l2, 1e-8});
  t.add({"cavity_pressure", 1, FieldSpace::global, {}, 2, TimeScheme::none, ResidualNorm::scaled_max, 1e-8});
  t.add({"heat", 1, FieldSpace::nodal, {2}, 0, TimeScheme::backward_euler, ResidualNorm::relative_to_load, 1e-8});
  t.number(m);
  const Field& u = t.at("displacement");
  EXPECT_EQ(u.offset(), 0);
  EXPECT_EQ(u.size(), 3 * m.num_nodes());
  EXPECT_EQ(u.node_dof(7, 2), 3 * 7 + 2);  // a field on every node: the DOF 3a + i
  const Field& p = t.at("pressure");
  const int nv = static_cast<int>(m.vertices().size());
  EXPECT_EQ(p.offset(), u.size());
  EXPECT_EQ(p.size(), nv + m.num_tets() - 1);
  EXPECT_EQ(p.element_dof(0), -1);
  EXPECT_EQ(p.element_dof(1), p.offset() + nv);
  EXPECT_FALSE(p.has_node(m.edge_nodes.begin()->second));  // P1 on a quadratic mesh
  const Field& pc = t.at("cavity_pressure");
  EXPECT_EQ(pc.global_dof(1), p.offset() + p.size() + 1);
  const Field& h = t.at("heat");
  int in_region = 0;
  std::vector<char> seen(m.num_nodes(), 0);
  for (int e = 0; e < m.num_tets(); ++e)
    if (m.region[e] == 2)
      for (int a : m.element_nodes(e)) in_region += !seen[a]++;
  EXPECT_EQ(h.size(), in_region);
  EXPECT_EQ(h.offset() + h.size(), t.num_dofs());
  EXPECT_TRUE(h.has_node(m.num_nodes() - 1) || !seen[m.num_nodes() - 1]);
  EXPECT_EQ(&t.field_of(h.offset()), &h);
  try {
    (void)t.at("pressur");
    FAIL() << "an unknown field was found";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("displacement, pressure, cavity_pressure, heat"), std::string::npos)
        << e.what();
  }
}

TEST(MacroConstraints, PrescribedTiedAndChainedDofsShareEquationsAsDeclared) {
  MacroConstraints c;
  const int g = c.add_value([](double t) { return 2.0 * t; });
  c.prescribe(0, g);
  c.tie(3, 1, 0.5);   // x3 = x1 + 0.5
  c.tie(4, 3, 0.25);  // x4 = x3 + 0.25 = x1 + 0.75 (a chain)
  c.tie(5, 0, 1.0);   // tied to a prescribed DOF: prescribed, 2t + 1
  c.close(7);
  EXPECT_EQ(c.num_free(), 3);  // DOFs 1, 2, 6
  EXPECT_EQ(c.eq(0), -1);
  EXPECT_EQ(c.eq(1), 0);
  EXPECT_EQ(c.eq(2), 1);
  EXPECT_EQ(c.eq(3), 0);
  EXPECT_EQ(c.eq(4), 0);
  EXPECT_EQ(c.eq(6), 2);
  ASSERT_EQ(c.prescribed(), (std::vector<int>{0, 5}));
  EXPECT_DOUBLE_EQ(c.prescribed_value(0, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(c.prescribed_value(1, 0.5), 2.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(7);
  x[1] = 3.0;
  c.distribute(x);
  EXPECT_DOUBLE_EQ(x[3], 3.5);
  EXPECT_DOUBLE_EQ(x[4], 3.75);
  EXPECT_TRUE(c.is_master(1));
  EXPECT_FALSE(c.is_master(3));

  MacroConstraints cycle;
  cycle.tie(0, 1);
  cycle.tie(1, 2);
  cycle.tie(2, 0);
  EXPECT_THROW(cycle.close(3), InputError);
}

TEST(TimeIntegration, EachFieldAdvancesByItsOwnScheme) {
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {1, 1, 1});
  FieldTable t;
  t.add({"second", 1, FieldSpace::global, {}, 2, TimeScheme::newmark, ResidualNorm::relative_to_load, 1e-8});
  t.add({"first", 1, FieldSpace::global, {}, 2, TimeScheme::backward_euler, ResidualNorm::relative_to_load, 1e-8});
  t.add({"none", 1, FieldSpace::global, {}, 2, TimeScheme::none, ResidualNorm::relative_to_load, 1e-8});
  t.number(m);
  const double beta = 0.3, gamma = 0.6, dt = 0.1;
  const TimeIntegration ti(beta, gamma);
  Eigen::VectorXd x(6), x_n(6), v_n(6), a_n(6), v = Eigen::VectorXd::Zero(6), a = Eigen::VectorXd::Zero(6);
  x << 1, 2, 3, 4, 5, 6;
  x_n << 0.5, 1, 2, 3, 1, 1;
  v_n << 1, -1, 2, 0, 7, 7;
  a_n << 3, 1, -2, 1, 7, 7;
  for (const Field& f : t) ti.rates(f, dt, x, x_n, v_n, a_n, x_n, 0.0, v, a);
  for (int k = 0; k < 2; ++k) {  // Newmark-β
    const double ak = (x[k] - x_n[k] - dt * v_n[k]) / (beta * dt * dt) - (0.5 / beta - 1.0) * a_n[k];
    EXPECT_NEAR(a[k], ak, 1e-9 * std::abs(ak));
    EXPECT_NEAR(v[k], v_n[k] + dt * ((1 - gamma) * a_n[k] + gamma * ak), 1e-9 * std::abs(ak));
  }
  for (int k = 2; k < 4; ++k) {  // backward Euler
    EXPECT_DOUBLE_EQ(v[k], (x[k] - x_n[k]) / dt);
    EXPECT_EQ(a[k], 0.0);
  }
  EXPECT_EQ(v[4], 0.0);  // no rate
  EXPECT_EQ(a[5], 0.0);
  EXPECT_DOUBLE_EQ(ti.coefficients(t.at("second"), dt, 0.0).da_dx, 1.0 / (beta * dt * dt));
  EXPECT_DOUBLE_EQ(ti.coefficients(t.at("second"), dt, 0.0).dv_dx, gamma / (beta * dt));
  EXPECT_DOUBLE_EQ(ti.coefficients(t.at("first"), dt, 0.0).dv_dx, 1.0 / dt);
  EXPECT_EQ(ti.coefficients(t.at("none"), dt, 0.0).dv_dx, 0.0);
}

// BDF2 at a varying step is exact on quadratics in time: x = t² gives v = 2t whatever
// Δt_{n−1} and Δt; its first step (no history) is backward Euler.
TEST(TimeIntegration, Bdf2IsExactOnQuadraticsAcrossAStepChange) {
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {1, 1, 1});
  FieldTable t;
  t.add({"fluid", 1, FieldSpace::global, {}, 1, TimeScheme::bdf2, ResidualNorm::relative_to_load, 1e-8});
  t.number(m);
  const TimeIntegration ti(0.25, 0.5);
  const Field& f = t.at("fluid");
  const double t0 = 0.3, t1 = 0.5, t2 = 0.56;  // Δt_{n−1} = 0.2, Δt = 0.06 (a cut-back)
  Eigen::VectorXd x(1), x_n(1), x_nm1(1), zero = Eigen::VectorXd::Zero(1), v(1), a(1);
  x << t2 * t2;
  x_n << t1 * t1;
  x_nm1 << t0 * t0;
  ti.rates(f, t2 - t1, x, x_n, zero, zero, x_nm1, t1 - t0, v, a);
  EXPECT_NEAR(v[0], 2 * t2, 1e-13);
  // ∂v/∂x is the weight of x, so a term's tangent is consistent with the rate.
  const double c = ti.coefficients(f, t2 - t1, t1 - t0).dv_dx;
  Eigen::VectorXd v2(1), x2 = x;
  x2[0] += 1e-3;
  ti.rates(f, t2 - t1, x2, x_n, zero, zero, x_nm1, t1 - t0, v2, a);
  EXPECT_NEAR((v2[0] - v[0]) / 1e-3, c, 1e-9 * c);
  ti.rates(f, t2 - t1, x, x_n, zero, zero, x_nm1, 0.0, v, a);  // first step
  EXPECT_DOUBLE_EQ(v[0], (x[0] - x_n[0]) / (t2 - t1));
  EXPECT_DOUBLE_EQ(ti.coefficients(f, t2 - t1, 0.0).dv_dx, 1.0 / (t2 - t1));
}

/// A test-only field: c ∂T/∂t − ∇·∇T = s on the elements of its region, P1/P2 Galerkin:
///   R = M (c v + ... ) : R_a = ∫ c N_a Ṫ + ∇N_a·∇T − N_a s,  K = c (∂v/∂T) M + D.
class ScalarDiffusionTerm final : public MacroTerm {
 public:
  ScalarDiffusionTerm(const TetMesh& mesh, std::string field, double capacity, double conductivity, double source)
      : mesh_(mesh), field_(std::move(field)), c_(capacity), k_(conductivity), s_(source) {}
  std::string name() const override { return "scalar diffusion"; }
  void declare(MacroSystem& system) override {
    T_ = &system.field(field_);
    const auto rule = tet_rule(2 * mesh_.order());
    Eigen::VectorXd N;
    Eigen::Matrix<double, 3, Eigen::Dynamic> dN;
    for (int e = 0; e < mesh_.num_tets(); ++e) {
      const auto nodes = mesh_.element_nodes(e);
      if (!T_->has_node(nodes[0]) || !T_->has_node(nodes[1]) || !T_->has_node(nodes[2]) || !T_->has_node(nodes[3]))
        continue;
      const int n = static_cast<int>(nodes.size());
      Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), D = Eigen::MatrixXd::Zero(n, n);
      Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
      for (const auto& q : rule) {
        tet_shape(mesh_.order(), q.bary, N, dN);
        Mat3 J = Mat3::Zero();
        for (int a = 0; a < n; ++a) J += mesh_.nodes[nodes[a]] * dN.col(a).transpose();
        const double dV = q.weight * J.determinant();
        const Eigen::MatrixXd grad = J.transpose().inverse() * dN;
        M += dV * N * N.transpose();
        D += dV * grad.transpose() * grad;
        f += dV * N;
      }
      mass_.push_back(std::move(M));
      stiffness_.push_back(std::move(D));
      load_.push_back(std::move(f));
      dofs_.push_back(T_->node_dofs(nodes));
      local_.push_back(system.declare_local(dofs_.back()));
    }
  }
  void assemble(const MacroState& s, MacroAssembly& out) override {
    const double dv = s.rate(*T_).dv_dx;
    for (size_t k = 0; k < dofs_.size(); ++k) {
      const Eigen::VectorXd T = gather(s.x, dofs_[k]), Tdot = gather(s.v, dofs_[k]);
      out.add_internal(dofs_[k], c_ * mass_[k] * Tdot + k_ * stiffness_[k] * T);
      out.add_external(dofs_[k], s_ * load_[k]);
      out.add_tangent(local_[k], c_ * dv * mass_[k] + k_ * stiffness_[k]);
    }
  }
  size_t elements() const { return dofs_.size(); }

 private:
  const TetMesh& mesh_;
  std::string field_;
  double c_, k_, s_;
  const Field* T_ = nullptr;
  std::vector<Eigen::MatrixXd> mass_, stiffness_;
  std::vector<Eigen::VectorXd> load_;
  std::vector<std::vector<int>> dofs_;
  std::vector<int> local_;
};

FieldDecl temperature(TimeScheme time) {
  return {"temperature", 1, FieldSpace::nodal, {2}, 0, time, ResidualNorm::relative_to_load, 1e-10};
}

// The wall (both regions, a homogeneous stretch u_x = 0.01 x t) and a steady diffusion
// field on the half x > 1/2 that follows u_x on the interface x = 1/2 (as a mesh motion
// follows the wall) and is held at 0 on x = 1: the exact field is linear,
// T = u_x(1/2) (1 − x)/(1/2), which P1 and P2 reproduce; the wall does not feel it.
TEST(TestOnlyField, FollowingTheWallOnTheInterfaceItSolvesWithTheWallInOneNewtonLoop) {
  for (int order : {1, 2}) {
    RunSpec spec = read_run_spec(box_scene(order), "");
    split_regions(spec.mesh);
    const TetMesh& m = spec.mesh;
    const std::vector<int> interface = interface_nodes(m, {1}, {2});
    ASSERT_FALSE(interface.empty());
    MacroExtension ext;
    ext.fields.push_back(temperature(TimeScheme::none));
    ext.constrain = [&](const FieldTable& fields, MacroConstraints& c) {
      const Field& T = fields.at("temperature");
      const Field& u = fields.at("displacement");
      for (int a : interface) c.follow(T.node_dof(a), u.node_dof(a, 0));
      const int zero = c.add_value([](double) { return 0.0; });
      for (int a : m.node_sets.at("xmax")) c.prescribe(T.node_dof(a), zero);
    };
    LocalEvaluator points(spec.models, spec.model_of_points());
    Simulation sim(spec, points, ext);
    auto term = std::make_unique<ScalarDiffusionTerm>(m, "temperature", 0.0, 1.0, 0.0);
    const ScalarDiffusionTerm* diffusion = term.get();
    sim.add_term(std::move(term));
    const RunResult r = sim.run();
    ASSERT_TRUE(r.converged) << r.error;
    EXPECT_GT(diffusion->elements(), 0u);
    // One Newton loop over both fields: each step's history has both, and the linear
    // coupled problem converges within a few iterations.
    for (const StepRecord& h : r.history) {
      EXPECT_FALSE(h.residual("temperature").empty());
      EXPECT_EQ(h.residual("temperature").size(), h.residual("displacement").size());
      EXPECT_LE(h.residual("temperature").back(), 1e-10);
      EXPECT_LE(h.iterations, 4);
    }
    const Field& T = sim.system().field("temperature");
    const Eigen::VectorXd u = sim.displacement();
    const Eigen::VectorXd Tv = sim.field_values("temperature");
    double u_half = 0.0;
    for (int a : interface) u_half += u[3 * a] / static_cast<double>(interface.size());
    EXPECT_NEAR(u_half, 0.005, 1e-12);  // the wall's stretch, unchanged by the field
    double worst = 0.0;
    for (int a : T.nodes()) {
      const double exact = u_half * (1.0 - m.nodes[a].x()) / 0.5;
      worst = std::max(worst, std::abs(Tv[T.node_dof(a) - T.offset()] - exact));
    }
    EXPECT_LT(worst, 1e-10 * u_half) << "order " << order;
    for (int a : interface) EXPECT_EQ(Tv[T.node_dof(a) - T.offset()], u[3 * a]) << "interface node " << a;
    // The wall alone gives the same ū (to round-off: the macro system is larger).
    LocalEvaluator alone_points(spec.models, spec.model_of_points());
    Simulation alone(spec, alone_points);
    ASSERT_TRUE(alone.run().converged);
    EXPECT_LT((alone.displacement() - u).norm(), 1e-12 * u.norm());
  }
}

// The seam with the wall on its own region: the wall is region 2 (x > 1/2) alone (its
// points and ū live there), pulled on ymax and held on xmax; a steady diffusion field on
// region 1 follows the wall's u_y on the interface x = 1/2 and is 0 on x = 0. One Newton
// loop solves both; T must equal an independent solve of the same Laplace problem with
// the wall's interface values as Dirichlet data (P1 stiffness in closed form, Eigen LDLᵀ).
TEST(TestOnlyField, OnARegionOfItsOwnNextToTheWallItMatchesAnIndependentSolve) {
  json j = box_scene(1);
  j["mesh"]["region_slabs"] = {{"axis", "x"}, {"count", 2}};
  j["mesh"]["wall_regions"] = json::array({2});
  j["dirichlet"] = {{{"set", "xmax"}}, {{"set", "ymax"}, {"value", {0.0, 0.02, 0.005}}}};
  const RunSpec spec = read_run_spec(j, "");
  const TetMesh& m = spec.mesh;
  const std::vector<int> interface = interface_nodes(m, {1}, {2});
  ASSERT_FALSE(interface.empty());
  MacroExtension ext;
  ext.fields.push_back({"temperature", 1, FieldSpace::nodal, {1}, 0, TimeScheme::none,
                        ResidualNorm::relative_to_load, 1e-10});
  ext.constrain = [&](const FieldTable& fields, MacroConstraints& c) {
    const Field& T = fields.at("temperature");
    const Field& u = fields.at("displacement");
    for (int a : interface) c.follow(T.node_dof(a), u.node_dof(a, 1));
    const int zero = c.add_value([](double) { return 0.0; });
    for (int a : m.node_sets.at("xmin")) c.prescribe(T.node_dof(a), zero);
  };
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points, ext);
  sim.add_term(std::make_unique<ScalarDiffusionTerm>(m, "temperature", 0.0, 1.0, 0.0));
  const RunResult r = sim.run();
  ASSERT_TRUE(r.converged) << r.error;
  const Field& T = sim.system().field("temperature");
  const Field& u = sim.system().field("displacement");
  EXPECT_FALSE(u.has_node(m.node_sets.at("xmin")[0]));  // no wall there
  const Eigen::VectorXd x = sim.state();
  double interface_u = 0.0;
  for (int a : interface) interface_u = std::max(interface_u, std::abs(x[u.node_dof(a, 1)]));
  ASSERT_GT(interface_u, 1e-3);  // the wall moves the interface: the coupling has work to do

  // Independent: K_ab = Σ_e V_e ∇λ_a·∇λ_b over region 1, Dirichlet at x = 0 and on the interface.
  const int n = m.num_nodes();
  std::vector<double> fixed(n, std::nan(""));
  for (int a : m.node_sets.at("xmin")) fixed[a] = 0.0;
  for (int a : interface) fixed[a] = x[u.node_dof(a, 1)];
  std::vector<int> eq(n, -1);
  int free = 0;
  for (int a : T.nodes())
    if (std::isnan(fixed[a])) eq[a] = free++;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(free, free);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(free);
  for (int e = 0; e < m.num_tets(); ++e) {
    if (m.region[e] != 1) continue;
    Eigen::Matrix4d A;
    for (int a = 0; a < 4; ++a) A.row(a) << 1.0, m.nodes[m.tets[e][a]].transpose();
    const Eigen::Matrix4d C = A.inverse();  // column a: λ_a = C(0,a) + C(1..3,a)·X
    const double V = std::abs(A.determinant()) / 6.0;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const int na = m.tets[e][a], nb = m.tets[e][b];
        if (eq[na] < 0) continue;
        const double k = V * C.col(a).tail<3>().dot(C.col(b).tail<3>());
        if (eq[nb] >= 0) K(eq[na], eq[nb]) += k;
        else f[eq[na]] -= k * fixed[nb];
      }
  }
  const Eigen::VectorXd Tfree = K.ldlt().solve(f);
  double worst = 0.0, scale = 0.0;
  for (int a : T.nodes()) {
    const double expected = eq[a] >= 0 ? Tfree[eq[a]] : fixed[a];
    worst = std::max(worst, std::abs(x[T.node_dof(a)] - expected));
    scale = std::max(scale, std::abs(expected));
  }
  EXPECT_LT(worst, 1e-9 * scale);
  for (int a : interface) EXPECT_EQ(x[T.node_dof(a)], x[u.node_dof(a, 1)]) << "interface node " << a;
}

// newton.field_rtol: each field converges against its own tolerance. A step stops at
// the first iteration (after the one that applies the prescribed increment) where every
// field meets its own, and not before.
TEST(FieldTolerances, EachFieldConvergesAgainstItsOwnAndAStepStopsWhenAllDo) {
  auto run = [](const json& field_rtol) {
    json j = box_scene(1, 3);
    j["dirichlet"][3]["value"] = {0.2, 0, 0};  // 20 %: Newton needs a few iterations
    j["formulation"] = {{"kind", "mixed"}, {"stabilization_modulus", 1e3}};
    if (!field_rtol.is_null()) j["newton"]["field_rtol"] = field_rtol;
    const RunSpec spec = read_run_spec(j, "");
    LocalEvaluator points(spec.models, spec.model_of_points());
    Simulation sim(spec, points);
    std::map<std::string, double> rtol;
    for (const Field& f : sim.system().fields()) rtol[f.name()] = f.decl().rtol;
    const RunResult r = sim.run();
    EXPECT_TRUE(r.converged) << r.error;
    int total = 0;
    for (const StepRecord& h : r.history) {
      total += h.iterations;
      const size_t n = h.residual("displacement").size();
      // Iteration 0 applies the step's prescribed increment and always corrects.
      for (size_t k = 1; k < n; ++k) {
        bool all_met = true;
        for (const auto& [name, tol] : rtol) all_met = all_met && h.residual(name).at(k) <= tol;
        EXPECT_EQ(all_met, k + 1 == n) << "step " << h.step << " iteration " << k;
      }
    }
    return std::make_pair(rtol, total);
  };
  const auto [tight, tight_iterations] = run(nullptr);
  EXPECT_EQ(tight.at("displacement"), 1e-11);
  EXPECT_EQ(tight.at("pressure"), 1e-11);
  const auto [loose, loose_iterations] = run({{"displacement", 1e-3}, {"pressure", 1e-3}});
  EXPECT_EQ(loose.at("displacement"), 1e-3);
  EXPECT_EQ(loose.at("pressure"), 1e-3);
  EXPECT_LT(loose_iterations, tight_iterations);

  json j = box_scene(1);
  j["newton"]["field_rtol"] = {{"presure", 1e-3}};
  try {
    read_run_spec(j, "");
    ADD_FAILURE() << "a tolerance for a field the scene lacks was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/newton/field_rtol/presure"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("displacement"), std::string::npos) << e.what();
  }
}

// A unit-weight tie shares the master's row and column (the two equations add); a follow
// gives its column to the master and drops its row; both are exact after distribute().
TEST(MacroSystem, TiesShareTheMastersEquationAndFollowersOnlyItsColumn) {
  const TetMesh m = make_box_mesh(Vec3(0, 0, 0), Vec3(1, 1, 1), {1, 1, 1});
  FieldTable t;
  t.add({"s", 1, FieldSpace::global, {}, 4, TimeScheme::none, ResidualNorm::relative_to_load, 1e-8});
  MacroConstraints c;
  c.tie(1, 0);     // s1 = s0, equations summed
  c.follow(2, 0);  // s2 = s0, own equation dropped
  MacroSystem sys(m, std::move(t), std::move(c));
  ASSERT_EQ(sys.num_free(), 2);  // s0 (with s1), s3
  const int local = sys.declare_local({0, 1, 2, 3});
  std::vector<double> values(sys.rows().size(), 0.0);
  Eigen::MatrixXd K(4, 4);
  for (int r = 0; r < 4; ++r)
    for (int col = 0; col < 4; ++col) K(r, col) = 10 * (r + 1) + (col + 1);
  sys.add(local, K, values);
  Eigen::Matrix2d S = Eigen::Matrix2d::Zero();
  for (size_t k = 0; k < values.size(); ++k) S(sys.rows()[k], sys.cols()[k]) += values[k];
  // Row of s0: rows 0 and 1 (tied), row 2 dropped; column of s0: columns 0, 1 and 2.
  EXPECT_EQ(S(0, 0), K(0, 0) + K(0, 1) + K(0, 2) + K(1, 0) + K(1, 1) + K(1, 2));
  EXPECT_EQ(S(0, 1), K(0, 3) + K(1, 3));
  EXPECT_EQ(S(1, 0), K(3, 0) + K(3, 1) + K(3, 2));
  EXPECT_EQ(S(1, 1), K(3, 3));
  EXPECT_EQ(sys.eq(2), -1);
  EXPECT_EQ(sys.column(2), sys.eq(0));
}

// A first-order field without diffusion under a constant source, c Ṫ = s: backward Euler
// is exact for a constant rate, T(t) = s t / c, and the consistent rate tangent (c/Δt) M
// makes Newton converge at once.
TEST(TestOnlyField, AFirstOrderFieldAdvancesByBackwardEuler) {
  RunSpec spec = read_run_spec(box_scene(1, 4), "");
  split_regions(spec.mesh);
  MacroExtension ext;
  ext.fields.push_back(temperature(TimeScheme::backward_euler));
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points, ext);
  sim.add_term(std::make_unique<ScalarDiffusionTerm>(spec.mesh, "temperature", 2.0, 0.0, 3.0));
  const RunResult r = sim.run();
  ASSERT_TRUE(r.converged) << r.error;
  for (const StepRecord& h : r.history) EXPECT_LE(h.iterations, 3) << "step " << h.step;  // the wall's few, T's one
  const Eigen::VectorXd T = sim.field_values("temperature");
  EXPECT_NEAR(T.minCoeff(), 1.5, 1e-12);
  EXPECT_NEAR(T.maxCoeff(), 1.5, 1e-12);
}

}  // namespace
}  // namespace fe2
