// Single-precision factors as the unit's GMRES preconditioner, cheaper than double
// ones: the supernodal float LLᵀ and MUMPS. The answer stays the double-factor answer
// to the GMRES tolerance, the float factor is really used (it costs GMRES iterations),
// and the spec keys are checked.
#include "common/error.h"
#include "common/spec/spec_schemas.h"
#include "unit_fixtures.h"
#include "worker/MicroModel.h"
#include "worker/FloatCholeskyFactor.h"
#include "worker/MumpsSingleFactor.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fe2 {
namespace {

using test::gradient;
using test::rel_diff;

struct UnitRun {
  std::vector<proto::JobOutput> out;
  int gmres = 0;
  std::string factor;
};

// Newton iterations of one unit at two load levels: a refresh at iteration 1 of step 0
// (factor exact for K), then steps on that factor (stale K) with the update applied.
UnitRun run(MicroSolverOptions opt) {
  opt.refresh = MicroSolverOptions::Refresh::fixed;
  opt.N_t = 100;
  opt.gmres_rtol = 1e-12;
  // Compared job by job: every Step 1 to the tight tolerance, or the Newton paths of the
  // two factors part at the forcing's looser one.
  opt.gmres_forcing = MicroSolverOptions::Forcing::constant;
  MicroUnit unit(test::two_cell_model(opt));
  const Vec9 Z = gradient({0.04, 0.01, 0.0, 0.0, -0.015, 0.0, 0.01, 0.0, 0.005});
  UnitRun r;
  for (int step = 0; step < 2; ++step)
    for (int it = 1; it <= 4; ++it) {
      proto::JobInput in;
      in.step = step;
      in.iteration = it;
      in.apply_update = it > 1 || step > 0;
      in.Zbar = (1.0 + step) * Z;
      r.out.push_back(unit.iterate(in));
      r.gmres += r.out.back().gmres_iterations;
    }
  r.factor = unit.factor()->name();
  return r;
}

void expect_same_answer(const UnitRun& a, const UnitRun& b) {
  ASSERT_EQ(a.out.size(), b.out.size());
  double worst = 0;
  for (size_t i = 0; i < a.out.size(); ++i)
    worst = std::max({worst, rel_diff(a.out[i].P_bar, b.out[i].P_bar),
                      rel_diff(a.out[i].A_hom, b.out[i].A_hom)});
  fmt::print("{}: {} GMRES iterations ({} with {}), largest relative difference {:.2e}\n",
             a.factor, a.gmres, b.gmres, b.factor, worst);
  for (size_t i = 0; i < a.out.size(); ++i) {
    SCOPED_TRACE(fmt::format("job {}", i));
    EXPECT_LT(rel_diff(a.out[i].P_bar, b.out[i].P_bar), 1e-9);
    EXPECT_LT(rel_diff(a.out[i].A_hom, b.out[i].A_hom), 1e-9);
  }
}

TEST(SinglePrecisionFactor, SameHomogenizedAnswerAsDoubleFactor) {
  const UnitRun dbl = run({});
  MicroSolverOptions o;
  o.single_precision = true;
  o.single_factor_mumps = true;
  const UnitRun sgl = run(o);
  EXPECT_EQ(dbl.factor, "cholmod_llt");
  EXPECT_EQ(sgl.factor, "mumps_single_ldlt");
  // The float factor is really the preconditioner: it costs GMRES iterations, even
  // right after the refresh, where the double factor solves Step 1 in one.
  EXPECT_GT(sgl.gmres, dbl.gmres);
  EXPECT_EQ(dbl.out[0].gmres_iterations, 1);
  EXPECT_GT(sgl.out[0].gmres_iterations, 1);
  expect_same_answer(sgl, dbl);
  // Unsymmetric (LU) path as well.
  o.factorization = MicroSolverOptions::Factorization::lu;
  const UnitRun lu = run(o);
  EXPECT_EQ(lu.factor, "mumps_single_lu");
  EXPECT_GT(lu.gmres, dbl.gmres);
  expect_same_answer(lu, dbl);
}

// precision "half": the float factor kept in binary16 is a coarser preconditioner (more
// GMRES iterations than float), and the answer is still the double one.
TEST(SinglePrecisionFactor, HalfStorageGivesTheSameAnswer) {
  const UnitRun dbl = run({});
  MicroSolverOptions o;
  o.single_precision = true;
  const UnitRun sgl = run(o);
  o.half_storage = true;
  const UnitRun half = run(o);
  EXPECT_EQ(half.factor, "supernodal_single_llt_half_storage");
  EXPECT_GT(half.out[0].gmres_iterations, 1);
  EXPECT_GT(half.gmres, sgl.gmres);
  expect_same_answer(half, dbl);
}

TEST(SinglePrecisionFactor, HalfStorageSolvesChiWithTheFloatFactorThenRoundsIt) {
  // A refresh solves χ before the factor is rounded to binary16: the same χ, bit for
  // bit, as with the float factor kept as it is, and the same refinement work; the
  // factor the unit keeps afterwards is the binary16 one (half the bytes).
  MicroSolverOptions o;
  o.single_precision = true;
  o.refresh = MicroSolverOptions::Refresh::fixed;
  o.N_t = 100;
  MicroUnit sgl(test::two_cell_model(o));
  o.half_storage = true;
  MicroUnit half(test::two_cell_model(o));
  proto::JobInput in;
  in.step = 0;
  in.iteration = 1;
  in.Zbar = gradient({0.04, 0.01, 0.0, 0.0, -0.015, 0.0, 0.01, 0.0, 0.005});
  sgl.iterate(in);
  half.iterate(in);
  EXPECT_TRUE(half.chi() == sgl.chi());
  EXPECT_EQ(half.last_chi_solve().refinement_rounds, sgl.last_chi_solve().refinement_rounds);
  EXPECT_EQ(half.last_chi_solve().gmres_iterations, sgl.last_chi_solve().gmres_iterations);
  EXPECT_NEAR(half.factor_bytes() / sgl.factor_bytes(), 0.5, 0.15);
  // The next refresh as well (the float values are rebuilt, used, and rounded again),
  // at a new Z̄ and without applying δw₁ (which the two factors solved differently), so
  // both units factor the same K.
  in.force_refresh = 1;
  in.apply_update = 0;
  in.Zbar *= 1.5;
  in.iteration = 2;
  sgl.iterate(in);
  half.iterate(in);
  EXPECT_EQ(half.refresh_count(), 2);
  EXPECT_TRUE(half.chi() == sgl.chi());
  EXPECT_NEAR(half.factor_bytes() / sgl.factor_bytes(), 0.5, 0.15);
}

TEST(SinglePrecisionFactor, SupernodalFloatLltGivesTheSameAnswer) {
  const UnitRun dbl = run({});
  MicroSolverOptions o;
  o.single_precision = true;  // the LLᵀ kind's default single-precision factor
  const UnitRun sgl = run(o);
  EXPECT_EQ(sgl.factor, "supernodal_single_llt");
  // Right after the refresh the float factor needs more than one GMRES iteration.
  EXPECT_GT(sgl.out[0].gmres_iterations, 1);
  EXPECT_GT(sgl.gmres, dbl.gmres);
  expect_same_answer(sgl, dbl);
}

// χ from a float factor: block refinement (nine columns per solve) reaches the GMRES
// tolerance without per-column GMRES; an exact factor needs no round at all.
TEST(SinglePrecisionFactor, CharacteristicModesAreRefinedAsABlock) {
  for (const bool single : {false, true}) {
    MicroSolverOptions o;
    o.single_precision = single;
    o.gmres_rtol = 1e-12;
    MicroUnit unit(test::two_cell_model(o));
    proto::JobInput in;
    in.Zbar = gradient({0.05, 0.01, 0, 0, -0.02, 0, 0, 0, 0.01});
    in.force_refresh = 1;
    unit.iterate(in);
    SCOPED_TRACE(unit.factor()->name());
    const auto& chi = unit.last_chi_solve();
    if (single) {
      EXPECT_GE(chi.refinement_rounds, 1);
      EXPECT_LE(chi.refinement_rounds, 4);
    } else {
      EXPECT_EQ(chi.refinement_rounds, 0);
    }
    EXPECT_EQ(chi.gmres_iterations, 0);
    const SparseMatrix& K = unit.system().K;
    const Eigen::MatrixXd& G = unit.system().G;
    for (int c = 0; c < 9; ++c)
      EXPECT_LE((G.col(c) - K * unit.chi().col(c)).norm(), 1e-12 * G.col(c).norm()) << c;
  }
}

TEST(SinglePrecisionFactor, BlockLowRankGivesTheSameAnswer) {
  const UnitRun dbl = run({});
  MicroSolverOptions o;
  o.single_precision = true;
  o.single_factor_mumps = true;
  o.blr_tolerance = 1e-4;
  const UnitRun blr = run(o);
  EXPECT_EQ(blr.factor, "mumps_single_ldlt_blr");
  EXPECT_GT(blr.gmres, dbl.gmres);
  expect_same_answer(blr, dbl);
}

TEST(SinglePrecisionFactor, SolveIsAccurateToSinglePrecisionAndReportsCosts) {
  MicroUnit unit(test::two_cell_model());
  proto::JobInput in;
  in.Zbar = gradient({0.05, 0.01, 0, 0, -0.02, 0, 0, 0, 0.01});
  unit.iterate(in);
  const SparseMatrix& K = unit.system().K;
  const Eigen::MatrixXd& G = unit.system().G;
  std::vector<double> flops;
  for (auto* make : {+[] { return make_mumps_single_factor(true, 0.0); },
                     +[] { return make_float_cholesky_factor(); }}) {
    auto f = make();
    SCOPED_TRACE(f->name());
    f->factorize(K);
    Eigen::MatrixXd X(G.rows(), 9);
    f->solve(G.data(), X.data(), 9);
    const double rel = (K * X - G).norm() / G.norm();
    EXPECT_LT(rel, 1e-3);   // a float factor: far from double round-off ...
    EXPECT_GT(rel, 1e-12);  // ... and not a double solve in disguise
    EXPECT_GT(f->factor_flops(), 0.0);
    EXPECT_GT(f->solve_flops(), 0.0);
    EXPECT_GT(f->factor_bytes(), 0.0);
  }
}

// The MUMPS factor's fill-reducing order is fe2heart's METIS nested dissection (Debian's
// MUMPS has none of its own: asked for METIS it took PORD, silently): its flops are then
// CHOLMOD's, whose analysis picks the better of METIS and AMD. Measured on this 2,997-DOF
// unit: MUMPS LDLᵀ 7.21e8 flops against CHOLMOD's 6.47e8 (1.11×); with PORD it was 1.15e9
// (1.78×). At 27,780 DOF: 68.3 against 66.8 Gflop, PORD 81.5 (BENCHMARKS.md).
TEST(SinglePrecisionFactor, MumpsFactorsOnANestedDissectionOrderAsLeanAsCholmods) {
  MicroUnit unit(test::two_cell_model({}, {10, 10, 10}));
  proto::JobInput in;
  in.Zbar = gradient({0.05, 0.01, 0, 0, -0.02, 0, 0, 0, 0.01});
  unit.iterate(in);
  const SparseMatrix& K = unit.system().K;
  auto mumps = make_mumps_single_factor(true, 0.0), cholmod = make_float_cholesky_factor();
  mumps->factorize(K);
  cholmod->factorize(K);
  std::printf("%d DOF: %s %.3g flops, %s %.3g flops\n", static_cast<int>(K.rows()), mumps->name().c_str(),
              mumps->factor_flops(), cholmod->name().c_str(), cholmod->factor_flops());
  EXPECT_LT(mumps->factor_flops(), 1.3 * cholmod->factor_flops());
}

MicroModelPlan plan_with(const nlohmann::json& solver) {
  nlohmann::json spec = nlohmann::json::parse(R"({
      "cell": "homogeneous", "resolution": [2, 2, 2],
      "materials": {"matrix": {"model": "neo_hookean", "E": 10, "nu": 0.3}}})");
  spec["solver"] = solver;
  return MicroModel::plan(SpecNode(spec, "/unit", micro_unit_schema()), ".");
}

std::string refusal(const nlohmann::json& solver) {
  try {
    plan_with(solver);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SinglePrecisionFactor, SpecKeysAreReadAndBadValuesRefused) {
  const MicroModelPlan p = plan_with(
      {{"precision", "single"}, {"single_factor", "mumps"}, {"blr_tolerance", 1e-6}});
  EXPECT_TRUE(p.options.single_precision);
  EXPECT_TRUE(p.options.single_factor_mumps);
  EXPECT_FALSE(plan_with({{"precision", "single"}}).options.single_factor_mumps);
  EXPECT_EQ(p.options.blr_tolerance, 1e-6);
  // The memory estimate counts the float factor at half the double one's bytes.
  const MicroModelPlan d = plan_with(nlohmann::json::object());
  EXPECT_NEAR(p.memory.factor_bytes, 0.5 * d.memory.factor_bytes, 1e-9 * d.memory.factor_bytes);

  std::string e = refusal({{"precision", "quarter"}});
  EXPECT_NE(e.find("/unit/solver/precision"), std::string::npos) << e;
  EXPECT_NE(e.find("quarter"), std::string::npos) << e;
  e = refusal({{"precision", "single"}, {"single_factor", "mumps"}, {"blr_tolerance", 1.5}});
  EXPECT_NE(e.find("/unit/solver/blr_tolerance"), std::string::npos) << e;
  e = refusal({{"blr_tolerance", 1e-6}});
  EXPECT_NE(e.find("/unit/solver/blr_tolerance"), std::string::npos) << e;
  EXPECT_NE(e.find("\"precision\" is \"single\""), std::string::npos) << e;
  // Block low-rank is MUMPS's: refused with the supernodal factor, naming the key.
  e = refusal({{"precision", "single"}, {"blr_tolerance", 1e-6}});
  EXPECT_NE(e.find("/unit/solver/blr_tolerance"), std::string::npos) << e;
  EXPECT_NE(e.find("\"single_factor\" is \"mumps\""), std::string::npos) << e;
  // "half" is the supernodal factor kept in binary16: a quarter of the double bytes.
  const MicroModelPlan h = plan_with({{"precision", "half"}});
  EXPECT_TRUE(h.options.single_precision);
  EXPECT_TRUE(h.options.half_storage);
  EXPECT_NEAR(h.memory.factor_bytes, 0.25 * d.memory.factor_bytes, 1e-9 * d.memory.factor_bytes);
  e = refusal({{"precision", "half"}, {"single_factor", "mumps"}});
  EXPECT_NE(e.find("/unit/solver/single_factor"), std::string::npos) << e;
  EXPECT_NE(e.find("\"precision\": \"half\""), std::string::npos) << e;
  e = refusal({{"precision", "single"}, {"single_factor", "pardiso"}});
  EXPECT_NE(e.find("/unit/solver/single_factor"), std::string::npos) << e;
}

}  // namespace
}  // namespace fe2
