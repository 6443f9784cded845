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
  throw InputError(fmt::format("placement policy '{}': expected one of {}", name,
                               fmt::join(n, ", ")));
}

const char* FarmOptions::name_of(Policy p) {
  return policy_names().at(static_cast<size_t>(p)).c_str();
}

FarmOptions FarmOptions::from_spec(SpecNode farm) {
  FarmOptions fo;
  fo.coordinators = farm.integer("coordinators", 1, Range::closed(1, 1e6),
                                 "ranks that own the macro problem (or --coordinators)");
  fo.coordinators_work = farm.boolean("coordinators_work", true,
                                      "coordinator ranks also hold units (paper ranks 0–63)");
  fo.policy = policy_of(farm.choice("policy", "cost_based", policy_names(),
                                    "unit placement: static, or rebalanced by measured cost"));
  fo.rebalance_at = farm.choice("rebalance_at", "iteration", {"iteration", "step"},
                                "when the cost-based policy may migrate units") == "iteration"
                        ? FarmOptions::When::iteration
                        : FarmOptions::When::step;
  fo.batch = farm.integer("batch", 4, Range::closed(1, 1e6), "jobs a worker pulls at once");
  fo.min_gain = farm.number("min_gain", 0.03, Range::closed(0.0, 1.0),
                            "least relative makespan gain worth a migration");
  fo.tolerated_imbalance = farm.number("tolerated_imbalance", 0.05, Range::closed(0.0, 10.0),
                                       "no rebalance while predicted max/mean load <= 1 + this");
  fo.latency = farm.number("latency", 2e-6, Range::non_negative(),
                           "network model: seconds per message");
  fo.bandwidth = farm.number("bandwidth", 5e9, Range::positive(),
                             "network model: bytes per second");
  fo.stall_timeout = farm.number(
      "stall_timeout", 600.0, Range::positive(),
      "liveness limit, wall seconds: a rank that waits this long for a message "
      "stops the job naming the silent rank; must exceed the longest wait of a "
      "healthy run: one Newton iteration (micro phase and macro solve) plus an "
      "output write");
  if (const json* b = farm.declared_value("factor_memory_budget", kBudgetType, kBudgetHelp)) {
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
      farm.choice("macro_law_points", "local", {"local", "farm"},
                  "where macro-law points are evaluated: local (by the coordinator that owns "
                  "their element, no messages) or farm (as jobs on the workers, like FE² units)") ==
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
