#include "coordinator/FarmOptions.h"

namespace fe2 {

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
  farm.finish();
  return fo;
}

}  // namespace fe2
