// Blood and wall coupled both ways (fluid.coupling "two_way", MovingWallTerm::loading_wall):
// the force each moving wall exerts on the blood acts back on the wall at the shared node.
// The check that needs no reference code: blood at rest under a pressure P is a
// hydrostatic load, so the wall it fills must deform exactly as the same wall under a
// follower pressure P on its endocardium (the lumped load the cavities have without
// blood). And Newton, with the coupling's tangent, keeps its convergence rate.
#include "common/mesh/cavity_volume.h"
#include "coordinator/LocalPoints.h"
#include "coordinator/RunSpec.h"
#include "coordinator/Simulation.h"
#include "coordinator/macro/MacroPartition.h"
#include "coordinator/macro/fluid_scene.h"
#include "coordinator/macro/macro_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace fe2 {
namespace {

using json = nlohmann::json;

/// The default beat's LV (mm), coarse and quadratic; with its cavity meshed if `blood`.
json lv_mesh(bool blood) {
  json m = {{"kind", "lv"}, {"endo", {22, 56}}, {"epi", {32, 66}}, {"base_z", 14}, {"divisions", {12, 6, 1}}, {"order", 2}};
  if (blood) {
    m["cavity"] = {{"layers", 3},
                   {"rings", {{"mitral", {{"center", {-8, 0}}, {"radius", 10}}}, {"aortic", {{"center", {13, 0}}, {"radius", 6}}}}}};
    m["wall_regions"] = {"myocardium"};
  }
  return m;
}

/// A soft neo-Hookean LV, base clamped, loaded by P on its endocardium: by blood
/// (two-way, entering through the aortic ring held at P) or by a follower pressure.
json inflated_lv(bool blood, double P, int steps) {
  json j = {{"mesh", lv_mesh(blood)},
            {"models", {{blood ? "myocardium" : "muscle", {{"kind", "macro_law"}, {"material", {{"model", "neo_hookean"}, {"E", 30000}, {"nu", 0.45}}}}}}},
            {"formulation", {{"kind", "mixed"}}},
            {"dirichlet", {{{"set", "base"}}}},
            {"cavities", {{"lv", {{"surface", "endo"}}}}},
            {"probes", {{"apex", {0, 0, -61}}, {"equator", {0, 27, 0}}}},
            // Long steps: the blood comes to rest, its viscous and inertial forces vanish.
            {"time", {{"t_end", 1.0 * steps}, {"steps", steps}}},
            {"newton", {{"rtol", 1e-10}, {"max_iterations", 20}}},
            {"output", {{"vtu", false}}}};
  if (!blood) {
    j["pressure"] = {{{"surface", "endo"}, {"value", P}, {"ramp", "constant"}}};
    return j;
  }
  j["fluid"] = {{"regions", {"blood"}},
                {"density", 1.06e-3},
                {"viscosity", 3.5e-3},
                {"time", "bdf1"},
                {"coupling", "two_way"},
                {"boundaries",
                 {{{"kind", "moving_wall"}, {"set", "endo"}},
                  {{"kind", "no_slip"}, {"set", "base_cap"}},
                  {{"kind", "no_slip"}, {"set", "mitral"}},
                  // Blood enters here: backflow stabilization (without it Newton diverges).
                  {{"kind", "pressure"}, {"set", "aortic"}, {"value", P}, {"ramp", "constant"}, {"backflow", 0.2}}}},
                {"mesh_motion",
                 {{"boundaries",
                   {{{"set", "endo"}, {"follow", "wall"}},
                    {{"set", "base_cap"}, {"follow", "fixed"}},
                    {{"set", "mitral"}, {"follow", "fixed"}},
                    {{"set", "aortic"}, {"follow", "fixed"}}}}}}};
  return j;
}

RunResult run(const json& j) {
  const RunSpec spec = read_run_spec(j, "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  return sim.run();
}

TEST(FluidTwoWay, BloodAtRestLoadsTheWallAsItsPressure) {
  const double P = 250.0;
  const RunResult lumped = run(inflated_lv(false, P, 1));
  ASSERT_TRUE(lumped.converged) << lumped.error;
  const RunResult blood = run(inflated_lv(true, P, 3));
  ASSERT_TRUE(blood.converged) << blood.error;
  const StepRecord &a = lumped.history.back(), &b = blood.history.back();
  const TetMesh& m = read_run_spec(inflated_lv(false, P, 1), "").mesh;
  const double V0 = cavity_volume(m, "endo", Eigen::VectorXd::Zero(3 * m.num_nodes())).volume;
  std::printf("cavity volume: follower pressure %.1f mm³, blood %.1f mm³ (unloaded %.1f)\n", a.cavity_volumes[0],
              b.cavity_volumes[0], V0);
  for (size_t s = 0; s < blood.history.size(); ++s)
    std::printf("step %zu: volume %.3f mm³, %zu Newton iterations\n", s, blood.history[s].cavity_volumes[0],
                blood.history[s].residual("displacement").size());
  const double swell = a.cavity_volumes[0] - V0;
  ASSERT_GT(swell, 0.03 * V0);  // the load is felt
  // At rest the blood's traction is −P n node by node: the same wall, the same answer,
  // to what is left of the flow after the long steps (measured ...).
  EXPECT_NEAR(b.cavity_volumes[0] - V0, swell, 1e-4 * swell);
  for (size_t k = 0; k < a.probes.size(); ++k)
    EXPECT_NEAR((b.probes[k] - a.probes[k]).norm(), 0.0, 1e-4 * swell / V0 * 66) << "probe " << k;
}

// The coupled block's tangent against central differences of the residual, over every
// free unknown (a wall DOF moves the mesh nodes that follow it too): the blood's
// element with its shape derivatives (geometry and mesh velocity through ∂ḋ/∂d), the
// moving wall's ties and their reaction on the wall.
TEST(FluidTwoWay, CoupledTangentMatchesFiniteDifferences) {
  for (const char* element : {"taylor_hood", "taylor_hood_supg"}) {
    SCOPED_TRACE(element);
    json j = inflated_lv(true, 250.0, 1);
    j["mesh"]["divisions"] = {4, 2, 1};
    j["mesh"]["cavity"] = {{"layers", 1}, {"rings", {{"aortic", {{"center", {10, 0}}, {"radius", 8}}}}}};
    j["fluid"]["element"] = element;
    j["fluid"]["boundaries"][2] = {{"kind", "no_slip"}, {"set", "base_cap"}};
    j["fluid"]["mesh_motion"]["boundaries"][2] = {{"set", "base_cap"}, {"follow", "fixed"}};
    const RunSpec spec = read_run_spec(j, "");
    MacroSystem system = make_macro_system(spec);  // with the fluid's fields (spec.fluid)
    ASSERT_TRUE(spec.fluid->shape_derivatives);
    auto terms = fluid_terms(spec.mesh, *spec.fluid, MacroPartition::whole(spec.mesh));
    for (auto& t : terms) t->declare(system);
    // The residual alone (the differences) needs no shape derivatives: the same terms
    // without them, five times cheaper.
    FluidSetup plain = *spec.fluid;
    plain.shape_derivatives = false;
    auto residual_terms = fluid_terms(spec.mesh, plain, MacroPartition::whole(spec.mesh));
    for (auto& t : residual_terms) t->declare(system);
    // A random state: displacements of 0.2 mm, velocities of 50 mm/s, pressures of
    // 300 Pa, multipliers of 10; rates ẋ = c x of the fields that have one (x_n = 0).
    const double c = 50.0;  // 1/Δt of BDF1 at Δt = 20 ms
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    const Field& u = system.field("displacement");
    const Field& d = system.field("mesh_displacement");
    const Field& v = system.field("fluid_velocity");
    const Field& p = system.field("fluid_pressure");
    const auto amplitude = [&](int dof) {
      return u.contains(dof) || d.contains(dof) ? 0.2 : v.contains(dof) ? 50.0 : p.contains(dof) ? 300.0 : 10.0;
    };
    Eigen::VectorXd x(system.num_dofs());
    for (int k = 0; k < system.num_dofs(); ++k) x[k] = amplitude(k) * uni(rng);
    system.constraints().distribute(x);  // the mesh follows the wall on the endocardium
    std::vector<RateCoefficients> rates(system.fields().size());
    for (const Field* f : {&v, &d}) rates[f->id()].dv_dx = c;
    const auto rate = [&](const Eigen::VectorXd& at) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(at.size());
      for (const Field* f : {&v, &d}) r.segment(f->offset(), f->size()) = c * at.segment(f->offset(), f->size());
      return r;
    };
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.num_dofs());
    std::vector<double> values(system.rows().size());
    const int n = system.num_free();
    const auto residual = [&](const Eigen::VectorXd& at, std::vector<std::unique_ptr<MacroTerm>>& with) {
      MacroAssembly out(system, values);
      const Eigen::VectorXd r = rate(at);
      for (auto& t : with) t->assemble(MacroState{at, r, zero, 0.0, 1.0 / c, rates}, out);
      Eigen::VectorXd R = Eigen::VectorXd::Zero(n);
      for (int dof = 0; dof < system.num_dofs(); ++dof)
        if (system.eq(dof) >= 0) R[system.eq(dof)] += out.internal()[dof] - out.external()[dof];
      return R;
    };
    residual(x, terms);  // the tangent at x is in `values` now
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
    for (size_t s = 0; s < values.size(); ++s) K(system.rows()[s], system.cols()[s]) += values[s];
    Eigen::MatrixXd fd = Eigen::MatrixXd::Zero(n, n);
    ASSERT_EQ(residual(x, residual_terms), residual(x, terms));
    for (int col = 0; col < n; ++col) {
      Eigen::VectorXd xp = x, xm = x;
      double h = 0.0;
      for (int dof = 0; dof < system.num_dofs(); ++dof)
        if (system.column(dof) == col) {
          h = 1e-6 * amplitude(dof);
          xp[dof] += h;
          xm[dof] -= h;
        }
      fd.col(col) = (residual(xp, residual_terms) - residual(xm, residual_terms)) / (2 * h);
    }
    const double error = (K - fd).norm() / fd.norm();
    std::printf("%s: %d free unknowns, ‖K − K_fd‖/‖K_fd‖ = %.2e\n", element, n, error);
    EXPECT_LT(error, 1e-6);
  }
}

}  // namespace
}  // namespace fe2
