#pragma once
// The spec of `fe2heart unit`: a unit, the macro gradient(s) to equilibrate it under,
// and the unit's Newton tolerance.
#include "common/spec/SpecNode.h"
#include "worker/MicroModel.h"

#include <filesystem>
#include <vector>

namespace fe2::cli {

struct UnitSpec {
  std::shared_ptr<const MicroModelPlan> plan;  ///< the unit as read, with its memory estimate
  MicroModelPtr model;                         ///< built from `plan` (null if not built)
  std::vector<Vec9> path;
  double rtol = 1e-10;
  int max_iterations = 30;
};

/// Keys are read by unit_spec_schema(); `doc`, if given, records those read.
/// `build` false: only the plan (validate, or a memory check before building).
UnitSpec read_unit_spec(const json& j, const std::string& file, SpecDoc* doc = nullptr,
                        bool build = true);

}  // namespace fe2::cli
