// A unit model read but not built (MicroModelPlan): its memory estimate against what
// CHOLMOD and the model really hold, and materials assigned by the
// physical names of a Gmsh cell.
#include "common/error.h"
#include "common/spec/spec_schemas.h"
#include "common/mesh/gmsh_reader.h"
#include "unit_fixtures.h"
#include "worker/MicroModel.h"
#include "worker/micro_memory.h"
#include "worker/unit_equilibrium.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fe2 {
namespace {

namespace fs = std::filesystem;

// The fill model must bound CHOLMOD's factor (METIS ordering, supernodal) from above,
// and not by so much that reasonable units are refused. Cubes and the elongated cells
// of the shipped configs.
TEST(MicroMemory, FillModelBoundsCholmodFactor) {
  MicroSolverOptions o;
  o.factorization = MicroSolverOptions::Factorization::cholesky;
  for (const std::array<int, 3> res : {std::array<int, 3>{8, 4, 4}, {16, 4, 4}, {8, 8, 8},
                                       {12, 12, 12}}) {
    SCOPED_TRACE(fmt::format("{}x{}x{}", res[0], res[1], res[2]));
    MicroUnit unit(test::two_cell_model(o, res));
    equilibrate(unit, test::gradient({0.01, 0, 0, 0, 0, 0, 0, 0, 0}), 1e-8, 30, 0);
    ASSERT_NE(unit.factor(), nullptr);
    const double actual = unit.factor()->factor_bytes() / 8.0;  // CHOLMOD xsize (entries)
    const double model = fill_entries({res[0], res[1], res[2]});
    fmt::print("cells {}x{}x{}: CHOLMOD {:.0f} entries, model {:.0f} (x{:.2f})\n", res[0], res[1],
               res[2], actual, model, model / actual);
    EXPECT_GE(model, actual);
    EXPECT_LE(model, 3.0 * actual);
  }
}

// Counts that the estimate derives (DOF, nonzeros of K) equal the built model's.
TEST(MicroMemory, CountsMatchTheBuiltModel) {
  for (const std::array<int, 3> res : {std::array<int, 3>{8, 4, 4}, {6, 6, 6}}) {
    const auto model = test::two_cell_model({}, res);
    const long long n1 = res[0], n2 = res[1], n3 = res[2];
    const MicroMemoryEstimate m =
        estimate_micro_memory({n1, n2, n3}, (n1 + 1) * (n2 + 1) * (n3 + 1), n1 * n2 * n3, false);
    EXPECT_EQ(m.dofs, model->num_dofs());
    // 81 per row, less the pinned node's couplings (27 nodes × 9 entries × 2 − 9).
    EXPECT_NEAR(m.pattern_nnz, model->pattern().nonZeros(), 27 * 9 * 2);
    EXPECT_GT(m.model_bytes, 72.0 * 4 * model->num_elements());  // at least the scatter table
  }
}

// The measured fact the model is calibrated on: a 21³ unit (27,780 DOF) has a CHOLMOD
// factor of ≈ 31 M entries (≈ 310 MB); 100³ is far beyond any one machine.
TEST(MicroMemory, PaperSizeAndHugeUnits) {
  const MicroMemoryEstimate paper = estimate_micro_memory({21, 21, 21}, 22 * 22 * 22, 9261, false);
  EXPECT_EQ(paper.dofs, 27780);
  EXPECT_GT(paper.factor_entries, 31e6);
  EXPECT_LT(paper.factor_entries, 3 * 31e6);
  const MicroMemoryEstimate huge =
      estimate_micro_memory({100, 100, 100}, 101LL * 101 * 101, 1000000, false);
  EXPECT_GT(huge.bytes_for(1), 100e9);
  EXPECT_EQ(huge.bytes_for(0), 0.0);
  EXPECT_DOUBLE_EQ(huge.bytes_for(3), huge.model_bytes + 3 * huge.unit_bytes);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Physical volumes "cell" (tag 5, the first hex) and "ecm" (tag 2, the second) name the
// regions; the spec's materials follow those names, whatever the tags' order.
TEST(MicroModelPlan, GmshPhysicalNamesSelectMaterials) {
  std::string text = slurp(std::string(FE2_SOURCE_DIR) + "/tests/data/two_hexes.msh");
  text.replace(text.find("\"matrix\""), 8, "\"ecm\"");
  const fs::path dir = fs::temp_directory_path() / fmt::format("fe2_plan_{}", getpid());
  fs::create_directories(dir);
  std::ofstream(dir / "cell_ecm.msh") << text;
  const json spec = json::parse(R"({
      "cell": "mesh_file", "mesh_file": "cell_ecm.msh",
      "materials": {"ecm": {"model": "neo_hookean", "E": 10, "nu": 0.3},
                    "cell": {"model": "neo_hookean", "E": 1000, "nu": 0.3}}})");
  const MicroModelPlan plan = MicroModel::plan(SpecNode(spec, "/unit", micro_unit_schema()), dir.string());
  EXPECT_EQ(plan.region_names, (std::vector<std::string>{"ecm", "cell"}));
  EXPECT_EQ(plan.size_key, "/unit/mesh_file");
  const auto model = plan.build();
  ASSERT_EQ(model->num_elements(), 2);
  // Hex 0 lies in "cell", hex 1 in "ecm": stiffness scales 100 apart.
  EXPECT_NEAR(model->material_of(0).stiffness_scale() / model->material_of(1).stiffness_scale(),
              100.0, 1e-9);

  // A material named by tag (the old convention) is now an unknown key, with a hint.
  json by_tag = spec;
  by_tag["materials"] = json::parse(R"({"0": {"model": "neo_hookean", "E": 10, "nu": 0.3},
                                        "1": {"model": "neo_hookean", "E": 1000, "nu": 0.3}})");
  try {
    MicroModel::plan(SpecNode(by_tag, "/unit", micro_unit_schema()), dir.string());
    ADD_FAILURE() << "materials by tag accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/unit/materials/ecm: got nothing"), std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fe2
