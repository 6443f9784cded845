// The run's unit tolerance (newton.micro_rtol) reaches its units: Step 1's forcing
// guards it (worker/MicroModel.cpp, step1_rtol), so a unit built from a run spec must
// know the tolerance the coordinators judge it by.
#include "tests/coordinator/scene_fixtures.h"

#include <gtest/gtest.h>

namespace fe2 {
namespace {

TEST(UnitNewtonTolerance, TheRunsMicroRtolReachesEveryUnitModel) {
  json j = test::beam({{"kind", "fe2"}, {"unit", test::two_cell_unit("every_iteration")}}, 1);
  j["newton"]["micro_rtol"] = 3e-7;
  const RunSpec spec = read_run_spec(j, "");
  int units = 0;
  for (const auto& m : spec.models)
    if (m.plan) {
      ++units;
      EXPECT_EQ(m.plan->options.newton_rtol, 3e-7);
      ASSERT_TRUE(m.micro);
      EXPECT_EQ(m.micro->options().newton_rtol, 3e-7);
    }
  EXPECT_EQ(units, 1);
  // Unset, it is the documented default.
  j["newton"].erase("micro_rtol");
  const RunSpec plain = read_run_spec(j, "");
  for (const auto& m : plain.models) {
    if (m.plan) {
      EXPECT_EQ(m.micro->options().newton_rtol, 1e-8);
    }
  }
}

}  // namespace
}  // namespace fe2
