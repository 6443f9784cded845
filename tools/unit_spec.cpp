// Reading a unit spec (`fe2heart unit`); its keys are declared in
// common/spec/spec_schemas.cpp, which gives this reader their defaults and ranges.
#include "tools/unit_spec.h"

#include "common/spec/spec_schemas.h"

#include <cmath>
#include <filesystem>

namespace fe2::cli {

UnitSpec read_unit_spec(const json& j, const std::string& file, SpecDoc* doc, bool build) {
  UnitSpec u;
  std::string base = std::filesystem::path(file).parent_path().string();
  SpecNode root(j, "", unit_spec_schema(), doc);
  root.string("title");
  root.string("description");
  MicroModelPlan plan = MicroModel::plan(root.child("unit"), base.empty() ? "." : base);
  // A lone unit is a model of one unit: the coordinators' collective rental is its own.
  if (plan.options.refresh == MicroSolverOptions::Refresh::collective)
    plan.options.refresh = MicroSolverOptions::Refresh::adaptive;
  const bool one = root.has("Zbar"), path = root.has("Zbar_path");
  if (one == path)
    root.fail(one ? "Zbar_path" : "Zbar",
              "exactly one of 'Zbar' (9 numbers) or 'Zbar_path' (an array of 9-number arrays)");
  if (one) {
    const auto z = root.numbers("Zbar");
    u.path.push_back(Eigen::Map<const Vec9>(z.data()));
  } else {
    const json* arr = root.declared_value("Zbar_path");
    const std::string what = "a non-empty array of arrays of 9 finite numbers";
    if (!arr->is_array() || arr->empty()) root.fail("Zbar_path", what);
    for (const auto& z : *arr) {
      if (!z.is_array() || z.size() != 9) root.fail("Zbar_path", what);
      Vec9 v;
      for (int i = 0; i < 9; ++i) {
        if (!z[i].is_number() || !std::isfinite(z[i].get<double>())) root.fail("Zbar_path", what);
        v[i] = z[i].get<double>();
      }
      u.path.push_back(v);
    }
  }
  SpecNode n = root.child("newton");
  u.rtol = n.number("rtol");
  u.max_iterations = n.integer("max_iterations");
  n.finish();
  root.finish();
  plan.options.newton_rtol = u.rtol;  // Step 1's forcing never solves below half of it
  u.plan = std::make_shared<const MicroModelPlan>(std::move(plan));
  if (build) u.model = u.plan->build();
  return u;
}

}  // namespace fe2::cli
