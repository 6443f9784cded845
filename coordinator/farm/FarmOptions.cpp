#include "coordinator/farm/FarmOptions.h"

#include "common/spec/memory_size.h"
#include "worker/micro_memory.h"

#include <cmath>

namespace fe2 {

namespace {
const char* const kBudgetType = "bytes: a number > 0 or a size such as \"2G\", \"500M\"";
const char* const kBudgetHelp =
    "sparse factors a worker rank may hold; past it the least recently used factors of other "
    "units are dropped and rebuilt on their next job (counted in summary.factor_memory); "
    "default: unlimited";
}  // namespace

const std::vector<std::string>& FarmOptions::policy_names() {
  static const std::vector<std::string> names = {"round_robin", "contiguous", "cost_based"};
  return names;
}

FarmOptions::Policy FarmOptions::policy_of(const std::string& name) {
  const auto& n = policy_names();
  for (size_t i = 0; i < n.size(); ++i)
    if (n[i] == name) return static_cast<Policy>(i);
  throw InputError(fmt::format("placement policy '{}': expected {}", name, known_names("one of", name, n)));
}

const char* FarmOptions::name_of(Policy p) {
  return policy_names().at(static_cast<size_t>(p)).c_str();
}

FarmOptions FarmOptions::from_spec(SpecNode farm) {
  FarmOptions fo;
  fo.coordinators = farm.integer("coordinators");
  fo.coordinators_work = farm.boolean("coordinators_work");
  fo.policy = policy_of(farm.choice("policy"));
  fo.rebalance_at = farm.choice("rebalance_at") == "iteration"
                        ? FarmOptions::When::iteration
                        : FarmOptions::When::step;
  fo.batch = farm.integer("batch");
  fo.threads_per_rank = farm.integer("threads_per_rank");
  fo.min_gain = farm.number("min_gain");
  fo.tolerated_imbalance = farm.number("tolerated_imbalance");
  fo.latency = farm.number("latency");
  fo.bandwidth = farm.number("bandwidth");
  fo.stall_timeout = farm.number("stall_timeout");
  if (const json* b = farm.declared_value("factor_memory_budget")) {
    const std::string key = farm.key_path("factor_memory_budget");
    if (b->is_string()) {
      fo.factor_memory_budget_text = b->dump();  // quoted, as in the spec
      fo.factor_memory_budget = parse_memory_size(b->get<std::string>(), key);
    } else if (b->is_number() && b->get<double>() > 0 && std::isfinite(b->get<double>())) {
      fo.factor_memory_budget = b->get<double>();
      fo.factor_memory_budget_text = b->dump();
    } else {
      farm.fail("factor_memory_budget", std::string(kBudgetType) + " (" + kBudgetHelp + ")");
    }
  }
  fo.macro_law_points =
      farm.choice("macro_law_points") ==
              "local"
          ? MacroLawPoints::local
          : MacroLawPoints::farm;
  farm.finish();
  return fo;
}

void FarmOptions::check_factor_budget(const std::vector<PointModelSpec>& models,
                                      const std::vector<int>& model_of_point) const {
  if (factor_memory_budget <= 0) return;
  std::vector<bool> used(models.size(), false);
  for (int m : model_of_point) used.at(static_cast<size_t>(m)) = true;
  double need = 0;
  const PointModelSpec* largest = nullptr;
  for (size_t m = 0; m < models.size(); ++m)
    if (used[m] && models[m].plan && models[m].plan->memory.factor_bytes > need) {
      need = models[m].plan->memory.factor_bytes;
      largest = &models[m];
    }
  if (largest && factor_memory_budget < need)
    throw InputError(fmt::format(
        "/farm/factor_memory_budget: got {} ({}), expected at least {:.0f} bytes (≈ {}, one "
        "factor of model '{}' by the memory estimate: {}), or no budget",
        factor_memory_budget_text, format_bytes(factor_memory_budget), std::ceil(need),
        format_bytes(need), largest->name, largest->plan->memory.describe()));
}

}  // namespace fe2
