// output.units (as in the paper's Fig. 11): a unit's micro fields as written to
// units/unit_<id>_<step>.vtu. What a unit writes must be what it computed: the
// displacement of a homogeneous unit is the affine Z̄·X, and the cells' stresses
// average to the P̄ the unit reported for the step, also for cells with history and
// viscosity (the fields are taken before the step's commit).
#include "common/cellmodels/cell_model_factory.h"
#include "common/cellmodels/cell_model_schema.h"
#include "common/materials/Myocardium.h"
#include "coordinator/PointEvaluator.h"
#include "coordinator/output/UnitOutput.h"
#include "tests/worker/unit_fixtures.h"
#include "worker/unit_fields.h"

#include <gtest/gtest.h>

#include <cmath>

namespace fe2 {
namespace {

using test::gradient;

const VtuFields::Field& field(const VtuFields& f, const std::string& name) {
  for (const auto& x : f.fields())
    if (x.name == name) return x;
  throw std::runtime_error("no field " + name);
}

/// Iterates the unit at `in` until ‖r‖ <= rtol r_ref; returns the converged job's output
/// (the step is not committed).
proto::JobOutput converge(MicroUnit& unit, proto::JobInput in, double rtol) {
  for (int it = 1; it <= 25; ++it) {
    in.iteration = it;
    in.apply_update = it > 1;
    const proto::JobOutput out = unit.iterate(in);
    if (out.r_norm <= rtol * out.r_ref) return out;
  }
  throw std::runtime_error("unit did not converge");
}

MicroModelPtr two_cell_model(MaterialPtr ecm, MaterialPtr cell) {
  CellLayout c;
  c.kind = "two_cells";
  c.size = Vec3(1.0, 0.4, 0.4);
  c.resolution = {6, 3, 3};
  c.gap = 0.1;
  c.cross_section = 0.5;
  MicroSolverOptions opt;
  opt.refresh = MicroSolverOptions::Refresh::every_iteration;
  return test::make_unit_model(c, {std::move(ecm), std::move(cell)}, opt);
}

// (a) Both phases the same law: w ≈ 0 and the written displacement is Z̄·X at every node.
TEST(UnitOutput, HomogeneousUnitWritesTheAffineDisplacement) {
  const MaterialPtr law = std::make_shared<NeoHookean>(1.0e4, 0.3);
  const auto model = two_cell_model(law, law);
  MicroUnit unit(model);
  proto::JobInput in;
  in.unit = 3;
  in.Zbar = gradient({0.12, 0.03, -0.02, 0.05, -0.08, 0.01, 0.02, 0.04, 0.06});
  const proto::JobOutput out = converge(unit, in, 1e-12);
  const proto::UnitFields f = micro_fields(unit, 3, 7);
  EXPECT_EQ(f.unit, 3);
  EXPECT_EQ(f.step, 7);
  EXPECT_FALSE(f.active);
  const HexMesh& mesh = model->mesh();
  ASSERT_EQ(f.nodes(), mesh.num_nodes());
  ASSERT_EQ(f.cells(), mesh.num_hexes());
  const auto [point, cell] = unit_vtu_fields(mesh, f);
  const auto& u = field(point, "displacement").values;
  const auto& w = field(point, "fluctuation").values;
  double scale = 0.0, worst_u = 0.0, worst_w = 0.0;
  for (int a = 0; a < mesh.num_nodes(); ++a) {
    const Vec3 affine = as_mat3(in.Zbar) * mesh.nodes[a];
    scale = std::max(scale, affine.norm());
    for (int i = 0; i < 3; ++i) {
      worst_u = std::max(worst_u, std::abs(u[3 * a + i] - affine[i]));
      worst_w = std::max(worst_w, std::abs(w[3 * a + i]));
    }
  }
  std::printf("homogeneous unit: max |u - Z̄X| / max |Z̄X| = %.2e, max |w| / max |Z̄X| = %.2e\n",
              worst_u / scale, worst_w / scale);
  EXPECT_LT(worst_u, 1e-12 * scale);
  EXPECT_LT(worst_w, 1e-12 * scale);
  // Every cell carries the law's stress at Z̄, and det F of the affine map.
  Vec9 Pi;
  Mat9 A;
  law->stress_and_tangent(in.Zbar, Pi, A);
  const double J = (Mat3::Identity() + as_mat3(in.Zbar)).determinant();
  for (int e = 0; e < f.cells(); ++e) {
    EXPECT_LT((Eigen::Map<const Vec9>(&f.P[9 * e]) - Pi).norm(), 1e-10 * Pi.norm()) << e;
    EXPECT_NEAR(f.det_F[e], J, 1e-12) << e;
  }
  EXPECT_LT((f.P_bar - out.P_bar).norm(), 1e-12 * out.P_bar.norm());
}

/// Land cells with viscosity, stiff, in a soft matrix.
MaterialPtr contracting_cell() {
  static const json spec = {{"model", "land2017"}};
  SpecNode node(spec, "/active", *cell_model_schema());
  return std::make_shared<Myocardium>(std::make_shared<NeoHookean>(2.0e5, 0.45),
                                      MyocardiumOptions{make_cell_model(node), 0.1, 20.0});
}

// (b) Two phases, contracting cells: the written fields are finite, the cells' P
// volume-averages to the unit's reported P̄ of that step, and T_a lives in the cells only
// (its mean is the unit's reported T_a).
TEST(UnitOutput, TwoPhaseUnitCellStressesAverageToTheReportedStress) {
  const auto model = two_cell_model(std::make_shared<NeoHookean>(2.0e4, 0.3), contracting_cell());
  MicroUnit unit(model);
  constexpr double dt = 5e-3, rtol = 1e-10;
  auto Zbar_at = [](double t) {
    return gradient({-0.4 * t, 0.01 * t, 0.0, 0.0, 0.2 * t, 0.0, 0.0, 0.05 * t, 0.2 * t});
  };
  double worst = 0.0, worst_Ta = 0.0, peak_Ta = 0.0;
  int step = 0;
  for (double t = dt; t <= 0.12 + 1e-12; t += dt, ++step) {
    proto::JobInput in;
    in.unit = 5;
    in.step = step;
    in.time = t;
    in.dt = dt;
    in.Zbar = Zbar_at(t);
    in.Zbar_dot = (Zbar_at(t) - Zbar_at(t - dt)) / dt;
    in.Zbar_dot_coefficient = 1.0 / dt;
    const proto::JobOutput out = converge(unit, in, rtol);
    const proto::UnitFields f = micro_fields(unit, 5, step + 1);
    unit.commit_step();
    ASSERT_TRUE(f.active);
    for (const auto* v : {&f.w, &f.P, &f.det_F, &f.active_tension})
      for (double x : *v) ASSERT_TRUE(std::isfinite(x));
    // Volume average of the cell data, with the element volumes.
    Vec9 mean = Vec9::Zero();
    double volume = 0.0, Ta = 0.0;
    for (int e = 0; e < f.cells(); ++e) {
      double v = 0.0;
      for (double x : model->geometry(e).weight) v += x;
      mean += v * Eigen::Map<const Vec9>(&f.P[9 * e]);
      volume += v;
      if (model->mesh().region[e] == 1) Ta += v * f.active_tension[e];
      else EXPECT_EQ(f.active_tension[e], 0.0) << "matrix element " << e;
      EXPECT_GT(f.det_F[e], 0.5);
    }
    mean /= volume;
    double cell_volume = 0.0;
    for (int e = 0; e < f.cells(); ++e)
      if (model->mesh().region[e] == 1)
        for (double x : model->geometry(e).weight) cell_volume += x;
    worst = std::max(worst, (mean - out.P_bar).norm() / out.P_bar.norm());
    worst_Ta = std::max(worst_Ta, std::abs(Ta / cell_volume - out.active_tension));
    peak_Ta = std::max(peak_Ta, out.active_tension);
  }
  std::printf("two-phase contracting unit: |<P>_cells - P̄| / |P̄| = %.2e over %d steps; T_a %.2e of a %.1f kPa peak\n",
              worst, step, worst_Ta / peak_Ta, 1e-3 * peak_Ta);
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(worst_Ta, 1e-12 * peak_Ta);
  EXPECT_GT(peak_Ta, 1e4);
}

// The one-process evaluator answers for FE² points and refuses a macro-law point.
TEST(UnitOutput, LocalEvaluatorGivesTheFieldsOfItsUnits) {
  PointModelSpec fe2;
  fe2.micro = test::two_cell_model();
  PointModelSpec law;
  law.kind = PointModelSpec::Kind::macro_law;
  law.material = std::make_shared<NeoHookean>(1.0e3, 0.3);
  LocalEvaluator points({fe2, law}, {0, 1, 0});
  std::vector<proto::JobInput> jobs(3);
  for (int k = 0; k < 3; ++k) {
    jobs[k].unit = k;
    jobs[k].Zbar = gradient({0.01 * (k + 1), 0, 0, 0, 0, 0, 0, 0, 0});
  }
  std::vector<proto::JobOutput> out;
  points.evaluate(jobs, out);
  const auto f = points.unit_fields({2, 0}, 4);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].unit, 2);
  EXPECT_EQ(f[1].unit, 0);
  EXPECT_EQ(f[0].step, 4);
  EXPECT_EQ(f[0].Zbar, jobs[2].Zbar);
  EXPECT_EQ(f[0].P_bar, out[2].P_bar);
  EXPECT_THROW(points.unit_fields({1}, 4), Error);
}

}  // namespace
}  // namespace fe2
